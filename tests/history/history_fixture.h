#pragma once
// Run folders for the history's tests: copies of the committed ci
// baseline's records (results/baselines/ci), each changed as a test needs,
// so that a history of many runs is made in milliseconds and its steps are
// known by construction.
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "../common/cli_run.h"

namespace sb::test {

inline const std::filesystem::path kCiBaseline =
    std::filesystem::path(SHADOWBENCH_SOURCE_DIR) / "results" / "baselines" / "ci";

// dir/name/results.jsonl: the baseline's records, each changed by `edit`.
inline std::filesystem::path run_folder(const std::filesystem::path& dir, const std::string& name,
                                        const std::function<void(nlohmann::json&)>& edit = {}) {
  std::filesystem::path run = dir / name;
  std::filesystem::create_directories(run);
  std::ofstream out(run / "results.jsonl");
  for (nlohmann::json j : jsonl_records(kCiBaseline)) {
    if (edit) edit(j);
    out << j.dump() << "\n";
  }
  return run;
}

// A record's started_at moved to day `day` (1 to 28) of its month: one run
// a day, so that each run of a history has a key of its own.
inline void start_on_day(nlohmann::json& j, int day) {
  std::string t = j["started_at"];
  t[8] = char('0' + day / 10);
  t[9] = char('0' + day % 10);
  j["started_at"] = t;
}

}  // namespace sb::test

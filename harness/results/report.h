#pragma once
// Tables made from a run's records: results.csv and summary.md, one row per
// technique variant, grouped by scene variant and resolution.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sb {

std::string make_csv(const std::vector<nlohmann::json>& records);
std::string make_markdown(const std::vector<nlohmann::json>& records, const std::string& title);
// Writes results.csv and summary.md into run_dir (atomically).
void write_reports(const std::string& run_dir, const std::vector<nlohmann::json>& records,
                   const std::string& title);

}  // namespace sb

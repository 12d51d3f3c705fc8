#include "record/classes_record.h"

#include <cmath>
#include <string>
#include <vector>

#include "record/record_json.h"

namespace sb::record {
namespace {
constexpr int kPenumbra = 1;
const char* const kOrder[3] = {"lit", "penumbra", "umbra"};
}  // namespace

std::optional<double> ClassesRecord::penumbra_missed() const {
  const auto& row = counts[kPenumbra];
  const std::int64_t all = row[0] + row[1] + row[2];
  if (all == 0) return std::nullopt;
  return double(all - row[kPenumbra]) / double(all);
}

std::optional<double> ClassesRecord::penumbra_invented() const {
  const std::int64_t all = counts[0][kPenumbra] + counts[1][kPenumbra] + counts[2][kPenumbra];
  if (all == 0) return std::nullopt;
  return double(all - counts[kPenumbra][kPenumbra]) / double(all);
}

nlohmann::json ClassesRecord::counts_json() const {
  nlohmann::json rows = nlohmann::json::object();
  for (size_t i = 0; i < 3; ++i) rows[kOrder[i]] = counts[i];
  return rows;
}

void ClassesRecord::read_counts(const Fields& f) {
  const Fields rows = f.object("counts");
  for (size_t i = 0; i < 3; ++i) {
    const auto row = rows.get<std::vector<double>>(kOrder[i]);
    bool fine = row.size() == 3;
    for (size_t j = 0; fine && j < 3; ++j) {
      fine = row[j] >= 0.0 && row[j] == std::floor(row[j]) && row[j] < 9.2e18;
      if (fine) counts[i][j] = static_cast<std::int64_t>(row[j]);
    }
    if (!fine)
      rows.fail(
          kOrder[i],
          "expected 3 non-negative integers (the technique's lit, penumbra and umbra pixels)");
  }
}

nlohmann::json ClassesRecord::to_json() const { return write_record(*this); }
ClassesRecord ClassesRecord::from_json(const Fields& f) { return read_record<ClassesRecord>(f); }

}  // namespace sb::record

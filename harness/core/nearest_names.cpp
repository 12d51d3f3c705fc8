#include "core/nearest_names.h"

#include <algorithm>
#include <numeric>
#include <utility>

namespace sb::core {

size_t edit_distance(const std::string& a, const std::string& b) {
  // One row of the dynamic programme at a time.
  std::vector<size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), size_t{0});
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::vector<std::string> nearest_names(const std::string& name,
                                       const std::vector<std::string>& known, size_t most,
                                       bool extensions) {
  const size_t threshold = std::max<size_t>(1, name.size() / 3);
  std::vector<std::pair<size_t, size_t>> near;  // (distance, index into known)
  for (size_t i = 0; i < known.size(); ++i) {
    const size_t d = edit_distance(name, known[i]);
    // Every character replaced ("q" for "k") is another name, not a typo.
    if (d >= std::max(name.size(), known[i].size())) continue;
    const bool contained = known[i].find(name) != std::string::npos;
    const bool extends = extensions && name.find(known[i]) != std::string::npos;
    if (d <= threshold || (name.size() >= 3 && (contained || extends))) near.emplace_back(d, i);
  }
  std::stable_sort(near.begin(), near.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::string> out;
  for (size_t k = 0; k < near.size() && k < most; ++k) out.push_back(known[near[k].second]);
  return out;
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& known,
                         bool extensions) {
  const std::vector<std::string> near = nearest_names(name, known, 3, extensions);
  if (near.empty()) return "";
  std::string out = " did you mean ";
  for (size_t i = 0; i < near.size(); ++i)
    out += (i == 0 ? "" : i + 1 == near.size() ? " or " : ", ") + near[i];
  return out + "?";
}

}  // namespace sb::core

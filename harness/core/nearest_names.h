#pragma once
// "Did you mean ...?": the known names nearest to one that is not known, by
// edit distance, for the hints of an unknown technique or scene type.
#include <string>
#include <vector>

namespace sb::core {

// Levenshtein distance: insertions, deletions and substitutions, each 1.
size_t edit_distance(const std::string& a, const std::string& b);

// Up to `most` of `known`, nearest first (ties in `known`'s order): those
// within an edit distance of max(1, |name| / 3), and those that contain
// `name` (3 characters or more) or that `name` contains. Empty when none is
// near enough to be a likely typo.
std::vector<std::string> nearest_names(const std::string& name,
                                       const std::vector<std::string>& known, size_t most = 3);

// " did you mean a, b or c?" for nearest_names(), or "" when there are none.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& known);

}  // namespace sb::core

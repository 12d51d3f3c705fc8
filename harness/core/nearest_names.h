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
// `name` (3 characters or more) or that `name` contains; never one that
// shares no character with it in place ("q" and "k"). Empty when none is
// near enough to be a likely typo.
// Without `extensions`, not those that `name` contains unless within that
// edit distance: a technique named
// for the one it varies (pcss_stochastic) is a name of its own, whose plugin
// was not loaded, not a typo of pcss.
std::vector<std::string> nearest_names(const std::string& name,
                                       const std::vector<std::string>& known, size_t most = 3,
                                       bool extensions = true);

// " did you mean a, b or c?" for nearest_names(), or "" when there are none.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& known,
                         bool extensions = true);

}  // namespace sb::core

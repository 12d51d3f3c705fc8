#include "results/control_baseline.h"

#include <algorithm>

namespace sb::results {

bool is_control(const std::vector<const record::JobRecord*>& group, const record::JobRecord& r) {
  const auto names_r = [&](const record::JobRecord* other) {
    return other->timing && other->timing->control &&
           other->timing->control->technique == r.technique_variant;
  };
  return names_r(&r) || std::any_of(group.begin(), group.end(), names_r);
}

}  // namespace sb::results

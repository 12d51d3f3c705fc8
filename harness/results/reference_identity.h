#pragma once
// What decides the reference a job's errors were measured against, as its
// record states it (record["reference"], docs/results.md): two jobs' errors
// compare only when these agree. A change of any one is a change of the
// yardstick, not of the technique, and can pass for an error regression.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "record/reference_record.h"

namespace sb::results {

// method, spp, seed, embree_isa, adaptive.pilot_spp,
// adaptive.target_std_error, cache_key (which also covers the reference's
// method version, Embree's version, the casters, the light and the
// G-buffer's points), in that order. A member the record lacks (no
// reference, no adaptive settings, a record without a cache key) is "".
std::vector<std::pair<std::string, std::string>> reference_identity_fields(
    const std::optional<record::ReferenceRecord>& reference);

}  // namespace sb::results

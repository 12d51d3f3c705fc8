#include "results/record_groups.h"

namespace sb::results {

using record::JobRecord;

std::vector<RecordGroup> by_scene_and_resolution(const std::vector<const JobRecord*>& records) {
  // The scene variant's length first: no two pairs share a key, whatever
  // bytes a record read from elsewhere holds.
  std::vector<RecordGroup> groups = group_by(records, [](const JobRecord& r) {
    return std::to_string(r.scene_variant.size()) + ":" + r.scene_variant + r.resolution;
  });
  for (RecordGroup& g : groups)
    g.key = g.records.front()->scene_variant + " @ " + g.records.front()->resolution;
  return groups;
}

std::vector<RecordGroup> by_scene_and_resolution(const std::vector<JobRecord>& records) {
  std::vector<const JobRecord*> all;
  all.reserve(records.size());
  for (const JobRecord& r : records) all.push_back(&r);
  return by_scene_and_resolution(all);
}

}  // namespace sb::results

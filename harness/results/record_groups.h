#pragma once
// Records in groups, groups and the records within each in the order they
// first appear: the one grouping of every report table, chart and LaTeX
// file, so that they all list a run's (scene, resolution)s alike.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

struct RecordGroup {
  std::string key;
  std::vector<const record::JobRecord*> records;
};

// Groups by `key(record)`, a string.
template <class Key>
std::vector<RecordGroup> group_by(const std::vector<const record::JobRecord*>& records, Key key) {
  std::vector<RecordGroup> groups;
  std::map<std::string, std::size_t> index;
  for (const record::JobRecord* r : records) {
    std::string k = key(*r);
    const auto [it, added] = index.emplace(k, groups.size());
    if (added) groups.push_back({std::move(k), {}});
    groups[it->second].records.push_back(r);
  }
  return groups;
}

// By scene variant and resolution, each group's key its heading
// "<scene variant> @ <WxH>".
std::vector<RecordGroup> by_scene_and_resolution(
    const std::vector<const record::JobRecord*>& records);
// The same over every record of a run (pointers into `records`).
std::vector<RecordGroup> by_scene_and_resolution(const std::vector<record::JobRecord>& records);

}  // namespace sb::results

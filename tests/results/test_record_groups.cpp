// Records by (scene variant, resolution) (results/record_groups.h), the
// grouping of summary.md, index.html, the LaTeX tables and the charts:
// groups and the records within each in the order they first appear, each
// pair its own group whatever its names hold.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "results/record_groups.h"

namespace sb {

using record::JobRecord;
using results::by_scene_and_resolution;
using results::RecordGroup;

namespace {

JobRecord grouped_record(const std::string& scene, const std::string& resolution,
                         const std::string& technique) {
  JobRecord r;
  r.scene_variant = scene;
  r.resolution = resolution;
  r.technique_variant = technique;
  return r;
}

std::vector<std::string> techniques_of(const RecordGroup& g) {
  std::vector<std::string> out;
  for (const JobRecord* r : g.records) out.push_back(r->technique_variant);
  return out;
}

TEST(RecordGroups, FirstAppearanceOrderOfGroupsAndMembers) {
  const std::vector<JobRecord> records = {
      grouped_record("b", "64x48", "t1"), grouped_record("a", "64x48", "t1"),
      grouped_record("b", "32x24", "t1"), grouped_record("a", "64x48", "t2"),
      grouped_record("b", "64x48", "t2")};
  const std::vector<RecordGroup> groups = by_scene_and_resolution(records);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0].key, "b @ 64x48");
  EXPECT_EQ(groups[1].key, "a @ 64x48");
  EXPECT_EQ(groups[2].key, "b @ 32x24");
  EXPECT_EQ(techniques_of(groups[0]), (std::vector<std::string>{"t1", "t2"}));
  EXPECT_EQ(techniques_of(groups[1]), (std::vector<std::string>{"t1", "t2"}));
  EXPECT_EQ(groups[0].records[1], &records[4]);  // pointers into the run's records
}

TEST(RecordGroups, PairsWhoseNamesRunTogetherStayApart) {
  // Joined with " @ " or a line break, each pair here would share a key.
  const std::vector<JobRecord> records = {
      grouped_record("s @ x", "y", "t1"), grouped_record("s", "x @ y", "t2"),
      grouped_record("s\nx", "y", "t3"), grouped_record("s", "x\ny", "t4")};
  const std::vector<RecordGroup> groups = by_scene_and_resolution(records);
  ASSERT_EQ(groups.size(), 4u);
  for (size_t i = 0; i < groups.size(); ++i) EXPECT_EQ(groups[i].records.size(), 1u);
}

TEST(RecordGroups, NoRecordsNoGroups) {
  EXPECT_TRUE(by_scene_and_resolution(std::vector<JobRecord>{}).empty());
}

}  // namespace
}  // namespace sb

// The record's schema is made from the record structs' descriptions: the
// tables in docs/results.md must be what `shadowbench list --record-schema`
// prints; a record with every member set must write each member the schema
// lists, and nothing it does not; and each record type must read back what
// it writes, whole and with nothing optional set.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "full_record.h"
#include "record/record_json.h"
#include "record/record_schema.h"

namespace sb {
namespace {

using json = nlohmann::json;

const char* const kBegin = "<!-- record-schema: begin";
const char* const kEnd = "<!-- record-schema: end -->";

TEST(RecordSchema, TheDocsHoldTheGeneratedTables) {
  std::ifstream in(std::string(SHADOWBENCH_SOURCE_DIR) + "/docs/results.md");
  std::stringstream file;
  file << in.rdbuf();
  const std::string text = file.str();
  const size_t begin = text.find(kBegin);
  ASSERT_NE(begin, std::string::npos) << "docs/results.md lacks " << kBegin;
  const size_t from = text.find('\n', begin) + 1;
  const size_t end = text.find(kEnd, from);
  ASSERT_NE(end, std::string::npos) << "docs/results.md lacks " << kEnd;
  EXPECT_EQ(text.substr(from, end - from), record_schema_markdown())
      << "regenerate the part between the markers: build/shadowbench list --record-schema";
}

bool listed(const std::vector<std::string>& patterns, const std::string& pointer) {
  for (const std::string& p : patterns)
    if (pointer_matches(p, pointer)) return true;
  return false;
}

// Every member's pointer in `j`, down to those the schema keeps as they are.
void members_of(const json& j, const std::string& at, const RecordPointers& schema,
                std::vector<std::string>& out) {
  if (!j.is_object() || (!at.empty() && listed(schema.opaque, at))) return;
  for (const auto& [key, value] : j.items()) {
    out.push_back(at + "/" + key);
    members_of(value, at + "/" + key, schema, out);
  }
}

TEST(RecordSchema, ItListsEveryMemberARecordWritesAndNoOther) {
  const RecordPointers schema = record_pointers();
  std::vector<std::string> written;
  members_of(test::every_member_record().to_json(), "", schema, written);
  for (const std::string& p : written) EXPECT_TRUE(listed(schema.members, p)) << p;
  for (const std::string& pattern : schema.members) {
    bool found = false;
    for (const std::string& p : written) found = found || pointer_matches(pattern, p);
    EXPECT_TRUE(found) << pattern << " is in the schema; every_member_record() does not write it";
  }
}

TEST(RecordSchema, PointersMatchTokenByToken) {
  EXPECT_TRUE(pointer_matches("/timing/shared/*/median_ms", "/timing/shared/gbuffer/median_ms"));
  EXPECT_FALSE(pointer_matches("/timing/shared/*", "/timing/shared/gbuffer/median_ms"));
  EXPECT_FALSE(pointer_matches("/timing/frame", "/timing/frames"));
}

TEST(RecordSchema, AFullRecordRoundTrips) {
  const json j = test::every_member_record().to_json();
  EXPECT_EQ(JobRecord::from_json(json::parse(j.dump())).to_json(), j);
}

// Each record type: written, read and written again, as it comes from {}
// and as the full record holds it.
template <class T>
void round_trip(const T& t, const std::string& what) {
  const json j = write_record(t);
  EXPECT_EQ(write_record(read_record<T>(Fields(json::parse(j.dump()), ""))), j) << what;
}

// T{} and the full record's T.
template <class T>
void round_trips(const T& full, const std::string& what) {
  round_trip(T{}, what + " as {}");
  round_trip(full, what);
}

TEST(RecordSchema, EachRecordTypeRoundTripsMinimalAndFull) {
  const JobRecord r = test::every_member_record();
  round_trips(r.timing->frame, "a timing series");
  round_trips(*r.timing, "timing");
  round_trips(*r.timing->control, "timing.control");
  round_trips(r.scene, "scene");
  round_trips(r.technique, "technique");
  round_trips(*r.reference, "reference");
  round_trips(*r.metrics, "metrics");
  round_trips(*r.stability, "stability");
  round_trips(r.host, "host");
  round_trips(r.build, "build");
  round_trips(*r.phases_s, "phases_s");
  round_trips(*r.classes, "classes");
  round_trips(*r.second_reference, "second_reference");
  round_trips(*r.visibility_check, "visibility_check");
  round_trips(r.images, "images");
}

TEST(RecordSchema, SeriesKeysTakeTheirUnit) {
  const json t = test::every_member_record().to_json()["timing"];
  EXPECT_TRUE(t["frame"].contains("median_ms"));
  EXPECT_TRUE(t["frame"].contains("samples_ms"));
  EXPECT_TRUE(t["frame"].contains("cv"));
  EXPECT_TRUE(t["control"]["frame_ratio"].contains("median"));
  EXPECT_FALSE(t["control"]["frame_ratio"].contains("median_ms"));
  EXPECT_TRUE(t["fine"]["technique"].contains("p90_ms"));
  EXPECT_TRUE(t["passes"]["depth"].contains("min_ms"));
}

}  // namespace
}  // namespace sb

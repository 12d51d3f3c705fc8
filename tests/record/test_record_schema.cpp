// The record's schema is made from the record structs' descriptions: the
// tables in docs/results.md must be what `shadowbench list --record-schema`
// prints; a record with every member set must write each member the schema
// lists, and nothing it does not; and each record type must read back what
// it writes, whole and with nothing optional set.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "full_record.h"
#include "record/plan_record.h"
#include "record/record_json.h"
#include "record/record_schema.h"

namespace sb {

using record::Fields;
using record::JobRecord;
using record::plan_difference;
using record::plan_pointers;
using record::plan_schema_markdown;
using record::PlanRecord;
using record::pointer_matches;
using record::read_record;
using record::record_pointers;
using record::record_schema_markdown;
using record::RecordError;
using record::RecordPointers;
using record::write_record;

namespace {

using json = nlohmann::json;

// The part of docs/results.md between the line holding `begin` and `end`.
std::string doc_region(const std::string& begin, const std::string& end) {
  std::ifstream in(std::string(SHADOWBENCH_SOURCE_DIR) + "/docs/results.md");
  std::stringstream file;
  file << in.rdbuf();
  const std::string text = file.str();
  const size_t at = text.find(begin);
  if (at == std::string::npos) return "docs/results.md lacks " + begin;
  const size_t from = text.find('\n', at) + 1;
  const size_t to = text.find(end, from);
  if (to == std::string::npos) return "docs/results.md lacks " + end;
  return text.substr(from, to - from);
}

TEST(RecordSchema, TheDocsHoldTheGeneratedTables) {
  EXPECT_EQ(doc_region("<!-- record-schema: begin", "<!-- record-schema: end -->"),
            record_schema_markdown())
      << "regenerate the part between the markers: build/shadowbench list --record-schema";
}

TEST(RecordSchema, TheDocsHoldThePlansGeneratedTables) {
  EXPECT_EQ(doc_region("<!-- plan-schema: begin", "<!-- plan-schema: end -->"),
            plan_schema_markdown())
      << "regenerate the part between the markers: build/shadowbench list --plan-schema";
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
    std::string member = at;
    member += "/" + key;
    out.push_back(member);
    members_of(value, member, schema, out);
  }
}

// Each written member is in the schema, and each schema member is written.
void expect_the_schema_is_what_is_written(const RecordPointers& schema,
                                          const std::vector<std::string>& written,
                                          const std::string& writer) {
  for (const std::string& p : written) EXPECT_TRUE(listed(schema.members, p)) << p;
  for (const std::string& pattern : schema.members) {
    bool found = false;
    for (const std::string& p : written) found = found || pointer_matches(pattern, p);
    EXPECT_TRUE(found) << pattern << " is in the schema; " << writer << " does not write it";
  }
}

TEST(RecordSchema, ItListsEveryMemberARecordWritesAndNoOther) {
  const RecordPointers schema = record_pointers();
  std::vector<std::string> written;
  members_of(test::every_member_record().to_json(), "", schema, written);
  expect_the_schema_is_what_is_written(schema, written, "every_member_record()");
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
  round_trips(*r.partial, "partial");
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

// A plan with every member set: two scenes (one that did not build), a job
// of each outcome over two shards.
PlanRecord every_member_plan() {
  PlanRecord p;
  p.config = "configs/two.json";
  p.name = "two";
  p.shard_count = 2;
  p.counts = {1, 1, 1};
  p.scenes = {{"grid", "", false, "", {"edge adjacency: 12 meshes", "closed: all"}},
              {"jeep", "cannot read", true, "jeep.gltf:3:5 (/accessors/0): bad", {}}};
  p.jobs = {
      {"grid@64x48@pcf_box", 0, "grid", "64x48", "pcf_box", "run", "", false, 2.5, 1},
      {"grid@64x48@shadow_volume", 1, "grid", "64x48", "shadow_volume", "skip",
       "needs closed casters", false, 1.25, 2},
      {"jeep@64x48@pcf_box", 2, "jeep", "64x48", "pcf_box", "fail", "cannot read", true, 0.5, 2}};
  return p;
}

TEST(RecordSchema, ThePlanSchemaListsEveryMemberAPlanWritesAndNoOther) {
  const RecordPointers schema = plan_pointers();
  std::vector<std::string> written;
  const json j = every_member_plan().to_json();
  members_of(j, "", schema, written);
  for (size_t i = 0; i < j["jobs"].size(); ++i)
    members_of(j["jobs"][i], "/jobs/" + std::to_string(i), schema, written);
  for (size_t i = 0; i < j["scenes"].size(); ++i)
    members_of(j["scenes"][i], "/scenes/" + std::to_string(i), schema, written);
  expect_the_schema_is_what_is_written(schema, written, "every_member_plan()");
}

TEST(RecordSchema, APlanRoundTripsEmptyAndFull) {
  for (const PlanRecord& p : {PlanRecord{}, every_member_plan()}) {
    const json j = p.to_json();
    const PlanRecord read = PlanRecord::from_json(json::parse(j.dump()));
    EXPECT_EQ(read, p);
    EXPECT_EQ(read.to_json(), j);
  }
  // The jobs are an array of objects, each at its own pointer.
  json j = every_member_plan().to_json();
  j["jobs"][1]["cost"] = "cheap";
  try {
    (void)PlanRecord::from_json(j);
    ADD_FAILURE() << "a string cost was read";
  } catch (const RecordError& e) {
    EXPECT_EQ(e.pointer(), "/jobs/1/cost");
  }
}

TEST(RecordSchema, PlansDifferOnlyInWhatTheyPlan) {
  const PlanRecord a = every_member_plan();
  PlanRecord b = a;
  b.config = "/elsewhere/two.json";
  EXPECT_EQ(plan_difference(a, b), "");
  b.jobs[1].shard = 1;
  EXPECT_EQ(plan_difference(a, b),
            "job 1 (grid@64x48@shadow_volume) is in shard 2, there in shard 1");
  b = a;
  b.jobs[0].outcome = "skip";
  b.jobs[0].reason = "no";
  EXPECT_EQ(plan_difference(a, b),
            "job 0 (grid@64x48@pcf_box) is planned to run, there to skip (no)");
  b = a;
  b.jobs.pop_back();
  EXPECT_EQ(plan_difference(a, b), "3 jobs, there 2");
  b = a;
  b.scenes[0].log.push_back("more");
  EXPECT_EQ(plan_difference(a, b), "scene \"grid\" is planned otherwise (its log or error)");
}

}  // namespace
}  // namespace sb

// Why a finished job runs again (record/spec_changes.h): each setting of
// the stored spec that differs from today's, named by its dotted path with
// both values, and a record without a stored spec said to be one.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "record/spec_changes.h"
#include "sample_records.h"

namespace sb {

using record::JobRecord;
using record::rerun_reason;
using record::spec_changes;

namespace {

using json = nlohmann::json;
using Changes = std::vector<std::string>;

json spec() {
  return {{"reference", {{"adaptive", false}, {"embree_isa", "avx2"}, {"spp", 256}}},
          {"frames", {{"control", {{"name", "none"}, {"params", json::object()}}}, {"timed", 10}}},
          {"backend", "osmesa"}};
}

TEST(SpecChanges, EqualSpecsHaveNoChange) { EXPECT_EQ(spec_changes(spec(), spec()), Changes{}); }

TEST(SpecChanges, EachChangedLeafIsNamedByItsPathWithBothValues) {
  json after = spec();
  after["reference"]["adaptive"] = true;
  after["reference"]["embree_isa"] = "sse2";
  after["frames"]["timed"] = 20;
  after["backend"] = "egl";
  EXPECT_EQ(spec_changes(spec(), after),
            (Changes{"backend changed (osmesa -> egl)", "frames.timed changed (10 -> 20)",
                     "reference.adaptive changed (false -> true)",
                     "reference.embree_isa changed (avx2 -> sse2)"}));
}

TEST(SpecChanges, AMemberOnOneSideIsAbsentOnTheOther) {
  json after = spec();
  after["build"] = {{"fingerprint", "0123456789abcdef"}};
  after["reference"].erase("spp");
  EXPECT_EQ(spec_changes(spec(), after),
            (Changes{"build changed (absent -> {\"fingerprint\":\"0123456789abcdef\"})",
                     "reference.spp changed (256 -> absent)"}));
}

TEST(SpecChanges, AnObjectReplacedByNullIsOneChangeAndLongValuesAreCut) {
  json after = spec();
  after["frames"]["control"] = nullptr;
  EXPECT_EQ(spec_changes(spec(), after),
            Changes{"frames.control changed ({\"name\":\"none\",\"params\":{}} -> null)"});
  after["backend"] = std::string(100, 'x');
  const Changes c = spec_changes(spec(), after);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0], "backend changed (osmesa -> " + std::string(77, 'x') + "...)");
}

TEST(SpecChanges, NumbersEqualInValueAreEqualWhateverTheirJsonType) {
  // A stored spec read back from a file holds unsigned integers where the
  // spec made today holds signed ones.
  EXPECT_EQ(spec_changes(json::parse(spec().dump()), spec()), Changes{});
}

TEST(RerunReason, ARecordOfTheSameHashIsKept) {
  JobRecord r = test::identity_record("s", "64x48", "none");
  r.spec_hash = "00000000000000aa";
  EXPECT_EQ(rerun_reason(r, spec(), "00000000000000aa"), "");
}

TEST(RerunReason, ARecordWithoutAStoredSpecSaysSo) {
  JobRecord r = test::identity_record("s", "64x48", "none");
  r.spec_hash = "00000000000000aa";
  EXPECT_NE(rerun_reason(r, spec(), "00000000000000bb").find("its record stores no spec"),
            std::string::npos);
}

TEST(RerunReason, TheChangedSettingsAreNamedThreeAtMost) {
  JobRecord r = test::identity_record("s", "64x48", "none");
  r.spec = spec();
  json after = spec();
  after["reference"]["spp"] = 64;
  EXPECT_EQ(rerun_reason(r, after, "00000000000000bb"), "reference.spp changed (256 -> 64)");
  after["reference"]["adaptive"] = true;
  after["reference"]["embree_isa"] = "sse2";
  after["frames"]["timed"] = 20;
  after["backend"] = "egl";
  EXPECT_EQ(rerun_reason(r, after, "00000000000000bb"),
            "backend changed (osmesa -> egl); frames.timed changed (10 -> 20); "
            "reference.adaptive changed (false -> true); and 2 more");
}

// The spec's technique member as job_spec writes it, for a plugin of this hash.
json with_plugin(const std::string& sha256) {
  json s = spec();
  s["technique"] = {{"name", "my_pcf"},
                    {"params", {{"k", 3}}},
                    {"plugin", {{"file", "my_pcf.so"}, {"sha256", sha256}, {"api_version", 1}}}};
  return s;
}

TEST(RerunReason, ARebuiltPluginIsNamedByItsFileWithBothHashesShort) {
  JobRecord r = test::identity_record("s", "64x48", "my_pcf");
  r.spec = with_plugin("ab12ab12ab12ab12ab12ab12ab12ab12ab12ab12ab12ab12ab12ab12ab12ab12");
  const json after =
      with_plugin("cd34cd34cd34cd34cd34cd34cd34cd34cd34cd34cd34cd34cd34cd34cd34cd34");
  EXPECT_EQ(rerun_reason(r, after, "00000000000000bb"),
            "plugin my_pcf.so changed (sha256 ab12ab12ab12.. -> cd34cd34cd34..)");
  // The control's plugin is named the same way.
  json control_before = spec(), control_after = spec();
  control_before["frames"]["control"]["plugin"] = r.spec->at("technique").at("plugin");
  control_after["frames"]["control"]["plugin"] = after.at("technique").at("plugin");
  r.spec = control_before;
  EXPECT_EQ(rerun_reason(r, control_after, "00000000000000bb"),
            "plugin my_pcf.so changed (sha256 ab12ab12ab12.. -> cd34cd34cd34..)");
}

TEST(RerunReason, ARebuiltHarnessIsNamedWithShortHashes) {
  JobRecord r = test::identity_record("s", "64x48", "none");
  json before = spec(), after = spec();
  before["build"] = {{"core_sha256", std::string(64, 'a')}};
  after["build"] = {{"core_sha256", std::string(64, 'b')}};
  r.spec = before;
  EXPECT_EQ(rerun_reason(r, after, "00000000000000bb"),
            "build.core_sha256 changed (aaaaaaaaaaaa.. -> bbbbbbbbbbbb..)");
}

// The spec's scene member as job_spec writes it for a glTF file
// (config/identity.h): its content and what it read, no path.
json with_file(const std::string& gltf, const json& reads) {
  json s = spec();
  s["scene"] = {{"type", "gltf"},
                {"params", {{"file", {{"sha256", gltf}, {"reads", reads}}}, {"scale", 1.0}}}};
  return s;
}

TEST(RerunReason, AChangedFileIsNamedByTheRecordsPathAndSaysItsContentChanged) {
  const std::string a(64, 'a'), b(64, 'b'), c(64, 'c');
  JobRecord r = test::identity_record("casters", "64x48", "none");
  r.scene.params = {{"file", "models/casters.gltf"}, {"scale", 1.0}};
  r.spec = with_file(a, {{"casters.bin", b}, {"textures/leaf.png", c}});
  // The .gltf itself.
  EXPECT_EQ(rerun_reason(r, with_file(b, {{"casters.bin", b}, {"textures/leaf.png", c}}),
                         "00000000000000bb"),
            "file models/casters.gltf: content changed (sha256 aaaaaaaaaaaa.. -> bbbbbbbbbbbb..)");
  // A texture it reads, one it no longer reads, one it reads now.
  EXPECT_EQ(
      rerun_reason(r, with_file(a, {{"textures/leaf.png", a}, {"textures/bark.png", c}}),
                   "00000000000000bb"),
      "file casters.bin of models/casters.gltf: content changed (sha256 bbbbbbbbbbbb.. -> "
      "absent); file textures/bark.png of models/casters.gltf: content changed (sha256 absent -> "
      "cccccccccccc..); file textures/leaf.png of models/casters.gltf: content changed (sha256 "
      "cccccccccccc.. -> aaaaaaaaaaaa..)");
  // A file that cannot be read now.
  json gone = with_file(a, {{"casters.bin", b}, {"textures/leaf.png", c}});
  gone["scene"]["params"]["file"]["sha256"] = nullptr;
  EXPECT_EQ(spec_changes(*r.spec, gone),
            Changes{"file scene.params.file: content changed (sha256 aaaaaaaaaaaa.. -> "
                    "unreadable)"});
}

TEST(RerunReason, AnEqualSpecUnderAnotherHashIsSaidToBeSo) {
  JobRecord r = test::identity_record("s", "64x48", "none");
  r.spec = spec();
  EXPECT_EQ(rerun_reason(r, spec(), "00000000000000bb"),
            "its spec_hash is not that of its stored spec");
}

}  // namespace
}  // namespace sb

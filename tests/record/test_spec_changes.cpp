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

TEST(RerunReason, AnEqualSpecUnderAnotherHashIsSaidToBeSo) {
  JobRecord r = test::identity_record("s", "64x48", "none");
  r.spec = spec();
  EXPECT_EQ(rerun_reason(r, spec(), "00000000000000bb"),
            "its spec_hash is not that of its stored spec");
}

}  // namespace
}  // namespace sb

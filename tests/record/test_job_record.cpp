// The typed record: to_json/from_json round trips for an ok job with every
// optional part, a skipped job and a failed one; a record of another
// schema_version refused with a clear message; a missing or ill-typed member
// named by its JSON pointer, in memory and in a run folder's file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <tuple>

#include "../metrics/test_util.h"
#include "core/error.h"
#include "full_record.h"
#include "record/job_record.h"
#include "sample_records.h"
#include "store/results_store.h"

namespace sb {

using core::InputError;
using record::AdaptiveReferenceRecord;
using record::BuiltScene;
using record::ClassesRecord;
using record::JobRecord;
using record::JobStatus;
using record::MetricPath;
using record::PluginRecord;
using record::RecordError;
using record::SecondReferenceRecord;
using store::read_job_records;

namespace {

using json = nlohmann::json;

using test::full_record;
using test::region;

TEST(JobRecord, FullRecordRoundTrips) {
  const json j = full_record().to_json();
  const JobRecord back = JobRecord::from_json(j);
  EXPECT_EQ(back.to_json(), j);
  // The documented spelling of what the types do not show.
  EXPECT_EQ(j["schema_version"], 1);
  EXPECT_EQ(j["status"], "ok");
  EXPECT_FALSE(j.contains("reason"));
  EXPECT_EQ(j["metrics"]["shaded"]["all"]["psnr"], "inf");
  EXPECT_EQ(j["metrics"]["shaded"]["penumbra"]["ssim"], "nan");
  EXPECT_EQ(j["metrics"]["shaded"]["soft_union"]["mean_signed"], "-inf");
  EXPECT_EQ(j["metrics"]["visibility"]["all"]["max_pixel"], json::array({17, 3}));
  EXPECT_TRUE(j["metrics"]["visibility"]["all"].contains("frac_over_0.05"));
  EXPECT_EQ(j["timing"]["pass_order"], json::array({"depth", "lookup"}));
  EXPECT_EQ(j["timing"]["fine"]["frames"], 3);
  EXPECT_EQ(j["timing"]["passes"]["lookup"]["samples_ms"].size(), 3u);
  EXPECT_EQ(j["timing"]["shared"].size(), 2u);
  EXPECT_EQ(j["scene"]["derived"]["inferred_receivers"], json::array({"ground"}));
  EXPECT_EQ(j["scene"]["light"]["size"], json::array({2.0, 2.0}));
  EXPECT_EQ(j["reference"]["seed"], std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(j["host"]["lp_num_threads"], "2");
  EXPECT_EQ(j["build"]["version"], "0.1.0");
  EXPECT_EQ(j["images"].size(), 12u);  // ten paths, the full scale and the masks
  EXPECT_EQ(j["images"]["masks"]["soft_union"], "jobs/x/mask_soft_union.png");
  EXPECT_EQ(back.images.masks.size(), 2u);
  EXPECT_TRUE(std::isnan(back.metrics->shaded.penumbra.ssim));
  EXPECT_EQ(back.timing->fine->pass_order, (std::vector<std::string>{"depth", "lookup"}));
  EXPECT_DOUBLE_EQ(back.timing->frame.median, 11.0);
  EXPECT_DOUBLE_EQ(j["overhead_s"].get<double>(), 0.5 - 0.4);
  EXPECT_EQ(j["phases_s"].size(), 5u);
}

TEST(JobRecord, AnAdaptiveReferenceRoundTripsAndUniformOnesLackIt) {
  JobRecord r = full_record();
  EXPECT_FALSE(r.to_json()["reference"].contains("adaptive"));
  r.reference->method = "embree_stratified_adaptive";
  r.reference->adaptive = AdaptiveReferenceRecord{16, 0.01, 123.5, 1024, {}, {}};
  json j = r.to_json();
  EXPECT_EQ(j["reference"]["adaptive"]["mean_spp"], 123.5);
  EXPECT_EQ(j["reference"]["adaptive"]["max_spp"], 1024);
  EXPECT_FALSE(j["reference"]["adaptive"].contains("unproven_stops"));  // an older record's
  EXPECT_EQ(JobRecord::from_json(j).to_json(), j);
  r.reference->adaptive->unproven_stops = 7;
  r.reference->adaptive->stop_bias_bound = 0.0223;
  j = r.to_json();
  EXPECT_EQ(j["reference"]["adaptive"]["unproven_stops"], 7);
  EXPECT_EQ(j["reference"]["adaptive"]["stop_bias_bound"], 0.0223);
  EXPECT_EQ(JobRecord::from_json(j).to_json(), j);
}

TEST(JobRecord, TheStoredSpecRoundTripsAndOlderRecordsLackIt) {
  JobRecord r = full_record();
  EXPECT_FALSE(r.to_json().contains("spec"));  // a record from before specs were stored
  r.spec = json{{"reference", {{"adaptive", true}, {"spp", 64}, {"target_std_error", 0.01}}},
                {"frames", {{"control", nullptr}}},
                {"build", {{"fingerprint", "0123456789abcdef"}}}};
  const json j = r.to_json();
  EXPECT_EQ(j["spec"]["reference"]["adaptive"], true);
  const JobRecord back = JobRecord::from_json(j);
  ASSERT_TRUE(back.spec.has_value());
  EXPECT_EQ(*back.spec, *r.spec);
  EXPECT_EQ(back.to_json(), j);
  json bad = j;
  bad["spec"] = "adaptive";
  try {
    (void)JobRecord::from_json(bad);
    FAIL() << "a spec that is not an object was read";
  } catch (const RecordError& e) {
    EXPECT_EQ(e.pointer(), "/spec") << e.what();
  }
}

// A session read from a run folder from elsewhere is printed by the
// reports' banners: what no run writes is refused, naming its place.
TEST(JobRecord, ASessionNoRunWritesIsRefusedNamingItsPlace) {
  const json j = test::every_member_record().to_json();
  ASSERT_TRUE(j.contains("session"));
  EXPECT_NO_THROW((void)JobRecord::from_json(j));
  const std::vector<std::pair<std::string, json>> bad = {
      {"id", "not-hex-at-all!!"},
      {"id", "0123456789abcdef0"},
      {"started", std::string("2026-12-07T12:00:00Z\x1b[2J")},
      {"host", std::string(256, 'h')},
      {"host", std::string("vm\x1b]0;title\x07")},
      {"load_average", -1.0},
      {"retimed_from", "someone else"}};
  for (const auto& [key, value] : bad) {
    json r = j;
    r["session"][key] = value;
    try {
      (void)JobRecord::from_json(r);
      ADD_FAILURE() << key << " = " << value.dump() << " was read";
    } catch (const RecordError& e) {
      EXPECT_EQ(e.pointer(), "/session/" + key) << e.what();
    }
  }
}

TEST(JobRecord, ThePluginAndTheCodeHashesRoundTripAndOlderRecordsLackThem) {
  JobRecord r = full_record();
  json j = r.to_json();  // a record from before plugin identities and code hashes
  EXPECT_FALSE(j["technique"].contains("plugin"));
  EXPECT_FALSE(j["build"].contains("core_sha256"));
  EXPECT_FALSE(JobRecord::from_json(j).technique.plugin.has_value());
  const std::string abc = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
  r.technique.plugin = PluginRecord{"shadow_map.so", 812345, abc, 1};
  r.build.driver_sha256 = std::string(64, 'd');
  r.build.core_sha256 = std::string(64, 'c');
  r.build.plugin_api_sha256 = std::string(64, 'a');
  j = r.to_json();
  EXPECT_EQ(
      j["technique"]["plugin"],
      (json{{"file", "shadow_map.so"}, {"size", 812345}, {"sha256", abc}, {"api_version", 1}}));
  EXPECT_EQ(j["build"]["driver_sha256"], std::string(64, 'd'));
  EXPECT_EQ(j["build"]["core_sha256"], std::string(64, 'c'));
  EXPECT_EQ(j["build"]["plugin_api_sha256"], std::string(64, 'a'));
  const JobRecord back = JobRecord::from_json(json::parse(j.dump()));
  ASSERT_TRUE(back.technique.plugin.has_value());
  EXPECT_EQ(*back.technique.plugin, *r.technique.plugin);
  EXPECT_EQ(back.build.core_sha256, r.build.core_sha256);
  EXPECT_EQ(back.to_json(), j);
  json bad = j;
  bad["technique"]["plugin"].erase("sha256");
  try {
    (void)JobRecord::from_json(bad);
    FAIL() << "a plugin without its hash was read";
  } catch (const RecordError& e) {
    EXPECT_EQ(e.pointer(), "/technique/plugin") << e.what();
    EXPECT_EQ(e.problem(), "missing required key \"sha256\" in this object");
  }
}

TEST(JobRecord, GpuBytesRoundTripAndOlderRecordsLackThem) {
  JobRecord r = full_record();
  json j = r.to_json();  // a record from before the GPU memory meter
  EXPECT_FALSE(j["technique"].contains("gpu_bytes"));
  EXPECT_FALSE(JobRecord::from_json(j).technique.gpu_bytes.has_value());
  r.technique.gpu_bytes = std::int64_t(5) << 32;  // past 32 bits: 20 GiB
  j = r.to_json();
  EXPECT_EQ(j["technique"]["gpu_bytes"], 21474836480);
  const JobRecord back = JobRecord::from_json(json::parse(j.dump()));
  EXPECT_EQ(back.technique.gpu_bytes, std::int64_t(21474836480));
  j["technique"]["gpu_bytes"] = "4 MiB";
  try {
    (void)JobRecord::from_json(j);
    FAIL() << "gpu_bytes as a string was read";
  } catch (const RecordError& e) {
    EXPECT_EQ(e.pointer(), "/technique/gpu_bytes") << e.what();
  }
}

TEST(JobRecord, GpuBytesAreTheTechniquesOwnPlusItsNeedsAndOlderRecordsHaveNoTotal) {
  JobRecord r = full_record();
  r.technique.set_gpu_bytes(32768, {{"edge_adjacency", 1000}, {"silhouette_edges", 640}});
  EXPECT_EQ(r.technique.gpu_bytes, 32768 + 1000 + 640);
  json j = r.to_json();
  EXPECT_EQ(j["technique"]["gpu_bytes"], 34408);
  EXPECT_EQ(j["technique"]["gpu_own_bytes"], 32768);
  EXPECT_EQ(j["technique"]["gpu_need_bytes"],
            json({{"edge_adjacency", 1000}, {"silhouette_edges", 640}}));
  const JobRecord back = JobRecord::from_json(json::parse(j.dump()));
  EXPECT_EQ(back.technique.gpu_own_bytes, 32768);
  EXPECT_EQ(back.technique.gpu_need_bytes, r.technique.gpu_need_bytes);
  EXPECT_EQ(back.technique.gpu_total_bytes(), 34408);
  // No needs on the GPU: an empty map, written, so the total is known.
  r.technique.set_gpu_bytes(4096, {});
  j = r.to_json();
  EXPECT_EQ(j["technique"]["gpu_need_bytes"], json::object());
  EXPECT_EQ(JobRecord::from_json(j).technique.gpu_total_bytes(), 4096);

  // A record from before the needs were counted: gpu_bytes alone, the
  // technique's own; it reads, without a total.
  json older = j;
  older["technique"].erase("gpu_own_bytes");
  older["technique"].erase("gpu_need_bytes");
  const JobRecord old = JobRecord::from_json(older);
  EXPECT_EQ(old.technique.gpu_bytes, 4096);
  EXPECT_FALSE(old.technique.gpu_own_bytes.has_value());
  EXPECT_FALSE(old.technique.gpu_need_bytes.has_value());
  EXPECT_FALSE(old.technique.gpu_total_bytes().has_value());

  // A total that is not the sum of its parts is refused where it is.
  json wrong = j;
  wrong["technique"]["gpu_bytes"] = 4000;
  try {
    (void)JobRecord::from_json(wrong);
    FAIL() << "a gpu_bytes other than its parts' sum was read";
  } catch (const RecordError& e) {
    EXPECT_EQ(e.pointer(), "/technique/gpu_bytes") << e.what();
    EXPECT_NE(e.problem().find("4096"), std::string::npos) << e.what();
  }
  json half = j;
  half["technique"].erase("gpu_need_bytes");
  try {
    (void)JobRecord::from_json(half);
    FAIL() << "gpu_own_bytes without gpu_need_bytes was read";
  } catch (const RecordError& e) {
    EXPECT_EQ(e.pointer(), "/technique/gpu_own_bytes") << e.what();
  }
  json as_text = j;
  as_text["technique"]["gpu_need_bytes"] = {{"edge_adjacency", "1 KiB"}};
  try {
    (void)JobRecord::from_json(as_text);
    FAIL() << "a need's bytes as a string was read";
  } catch (const RecordError& e) {
    EXPECT_EQ(e.pointer(), "/technique/gpu_need_bytes/edge_adjacency") << e.what();
  }
}

TEST(JobRecord, AnalyticCastersAreRecordedAndOlderRecordsReadAsNone) {
  json j = full_record().to_json();
  EXPECT_EQ(j["scene"]["analytic_casters"], 81);
  j["scene"].erase("analytic_casters");  // a record from before the field
  const JobRecord back = JobRecord::from_json(j);
  ASSERT_TRUE(back.scene.built.has_value());
  EXPECT_EQ(back.scene.built->analytic_casters, 0);
  EXPECT_EQ(back.to_json()["scene"]["analytic_casters"], 0);
}

TEST(JobRecord, TheReceiversRegionRoundTripsAndOlderRecordsLackIt) {
  JobRecord r = full_record();
  r.metrics->visibility.receivers = region(0.125);
  const json j = r.to_json();
  EXPECT_EQ(j["metrics"]["visibility"]["receivers"]["rmse"], 0.125);
  EXPECT_FALSE(j["metrics"]["shaded"].contains("receivers"));
  const JobRecord back = JobRecord::from_json(j);
  EXPECT_EQ(back.to_json(), j);
  const auto path = MetricPath::parse("visibility.receivers.rmse");
  ASSERT_TRUE(path.has_value());
  EXPECT_EQ(path->of(*back.metrics), 0.125);
  // Absent (an older record, or no receiver in view): NaN, never 0.
  EXPECT_TRUE(std::isnan(MetricPath::parse("shaded.receivers.rmse")->of(*back.metrics)));
  EXPECT_FALSE(MetricPath::parse("visibility.ground.rmse").has_value());
}

TEST(JobRecord, TheGeometryRegionRoundTripsInBothImagesAndOlderRecordsLackIt) {
  JobRecord r = full_record();
  r.metrics->visibility.geometry = region(0.0625);
  r.metrics->shaded.geometry = region(0.03125);
  const json j = r.to_json();
  EXPECT_EQ(j["metrics"]["visibility"]["geometry"]["rmse"], 0.0625);
  EXPECT_EQ(j["metrics"]["shaded"]["geometry"]["rmse"], 0.03125);
  const JobRecord back = JobRecord::from_json(j);
  EXPECT_EQ(back.to_json(), j);
  EXPECT_EQ(MetricPath::parse("visibility.geometry.rmse")->of(*back.metrics), 0.0625);
  EXPECT_EQ(MetricPath::parse("shaded.geometry.rmse")->of(*back.metrics), 0.03125);
  // A record written before the region existed reads, and its geometry
  // figures are NaN, never `all`'s.
  json old = j;
  old["metrics"]["visibility"].erase("geometry");
  old["metrics"]["shaded"].erase("geometry");
  const JobRecord older = JobRecord::from_json(old);
  EXPECT_FALSE(older.metrics->visibility.geometry.has_value());
  EXPECT_TRUE(std::isnan(MetricPath::parse("visibility.geometry.rmse")->of(*older.metrics)));
}

TEST(JobRecord, TheTerminatorRegionAndTheWholeImageFlipRoundTripAndOlderRecordsLackThem) {
  JobRecord r = full_record();
  r.metrics->visibility.terminator = region(0.25);
  r.metrics->shaded.terminator = region(0.125);
  r.metrics->flip_shaded = 0.0625;
  const json j = r.to_json();
  EXPECT_EQ(j["metrics"]["visibility"]["terminator"]["rmse"], 0.25);
  EXPECT_EQ(j["metrics"]["flip_shaded"], 0.0625);
  const JobRecord back = JobRecord::from_json(j);
  EXPECT_EQ(back.to_json(), j);
  EXPECT_EQ(MetricPath::parse("visibility.terminator.rmse")->of(*back.metrics), 0.25);
  EXPECT_EQ(MetricPath::parse("shaded.terminator.rmse")->of(*back.metrics), 0.125);
  // A record written before them reads; its terminator figures are NaN.
  json old = j;
  for (const char* image : {"visibility", "shaded"}) old["metrics"][image].erase("terminator");
  old["metrics"].erase("flip_shaded");
  const JobRecord older = JobRecord::from_json(old);
  EXPECT_FALSE(older.metrics->flip_shaded.has_value());
  EXPECT_TRUE(std::isnan(MetricPath::parse("visibility.terminator.rmse")->of(*older.metrics)));
}

TEST(JobRecord, TheDistanceThirdsRoundTripAndRecordsWithoutThemReadNaN) {
  JobRecord r = full_record();
  r.metrics->visibility.near_third = region(0.25);
  r.metrics->visibility.middle_third = region(0.125);
  r.metrics->visibility.far_third = region(0.0625);
  const json j = r.to_json();
  EXPECT_EQ(j["metrics"]["visibility"]["near_third"]["rmse"], 0.25);
  EXPECT_EQ(j["metrics"]["visibility"]["far_third"]["rmse"], 0.0625);
  const JobRecord back = JobRecord::from_json(j);
  EXPECT_EQ(back.to_json(), j);
  EXPECT_EQ(MetricPath::parse("visibility.middle_third.rmse")->of(*back.metrics), 0.125);
  EXPECT_TRUE(std::isnan(MetricPath::parse("shaded.near_third.rmse")->of(*back.metrics)));
  EXPECT_TRUE(
      std::isnan(MetricPath::parse("visibility.far_third.rmse")->of(*full_record().metrics)));
}

TEST(JobRecord, ASecondReferenceRoundTripsAndOtherRecordsLackIt) {
  JobRecord r = full_record();
  EXPECT_FALSE(r.to_json().contains("second_reference"));
  SecondReferenceRecord second;
  second.reference = *r.reference;
  second.reference.method = "exact_clipper";
  second.reference.spp = 0;
  second.visibility = {region(0.09), region(0.25), region(0.125)};
  r.second_reference = second;
  const json j = r.to_json();
  EXPECT_EQ(j["second_reference"]["reference"]["method"], "exact_clipper");
  EXPECT_EQ(j["second_reference"]["visibility"]["penumbra"]["rmse"], 0.25);
  EXPECT_FALSE(j["second_reference"].contains("shaded"));  // the visibility only
  const JobRecord back = JobRecord::from_json(j);
  EXPECT_EQ(back.to_json(), j);
  json bad = j;
  bad["second_reference"].erase("visibility");
  try {
    (void)JobRecord::from_json(bad);
    FAIL() << "a second reference without metrics was read";
  } catch (const RecordError& e) {
    EXPECT_EQ(std::string(e.what()),
              "at /second_reference: missing required key \"visibility\" in this object");
  }
}

TEST(JobRecord, ClassesRoundTripWithTheirSharesAndBadCountsAreNamed) {
  JobRecord r = full_record();
  EXPECT_FALSE(r.to_json().contains("classes"));
  ClassesRecord classes;
  classes.counts = {{{90, 10, 0}, {30, 50, 20}, {0, 0, 100}}};
  r.classes = classes;
  const json j = r.to_json();
  EXPECT_EQ(j["classes"]["counts"]["penumbra"], json::array({30, 50, 20}));
  EXPECT_DOUBLE_EQ(j["classes"]["penumbra_missed"].get<double>(), 0.5);  // 50 of 100
  EXPECT_DOUBLE_EQ(j["classes"]["penumbra_invented"].get<double>(), 10.0 / 60.0);
  const JobRecord back = JobRecord::from_json(j);
  EXPECT_EQ(back.to_json(), j);
  json bad = j;
  bad["classes"]["counts"]["umbra"] = json::array({0, -1, 100});
  try {
    (void)JobRecord::from_json(bad);
    FAIL() << "a negative count was read";
  } catch (const RecordError& e) {
    EXPECT_NE(std::string(e.what()).find("/classes/counts/umbra"), std::string::npos) << e.what();
  }
}

TEST(JobRecord, CoarseTimingHasNoPassDetail) {
  JobRecord r = full_record();
  r.timing->fine.reset();
  r.timing->pass_timing = "coarse";
  const json j = r.to_json();
  for (const char* key : {"passes", "pass_order", "fine"})
    EXPECT_FALSE(j["timing"].contains(key)) << key;
  EXPECT_EQ(JobRecord::from_json(j).to_json(), j);
}

TEST(JobRecord, SkippedRecordHasOnlyWhatWasKnown) {
  JobRecord r = test::identity_record("foliage", "64x48", "shadow_volume", JobStatus::Skipped);
  r.reason = "shadow_volume needs closed casters: mesh 'leaves' has 1834 boundary edges";
  r.scene.built = BuiltScene{};
  const json j = r.to_json();
  for (const char* key : {"timing", "metrics", "reference", "visibility_check", "images",
                          "warnings", "started_at", "duration_s"})
    EXPECT_FALSE(j.contains(key)) << key;
  EXPECT_EQ(j["status"], "skipped");
  EXPECT_TRUE(j["scene"].contains("derived"));
  const JobRecord back = JobRecord::from_json(j);
  EXPECT_EQ(back.status, JobStatus::Skipped);
  EXPECT_FALSE(back.timing || back.metrics || back.reference);
  EXPECT_EQ(back.to_json(), j);
}

TEST(JobRecord, FailedSceneRecordHasNoSceneData) {
  JobRecord r = test::identity_record("gltf/file=x.glb", "64x48", "none", JobStatus::Failed);
  r.reason = "x.glb: cannot open the file";
  const json j = r.to_json();
  EXPECT_EQ(j["scene"],
            json({{"type", "gltf"}, {"variant", "gltf/file=x.glb"}, {"params", json::object()}}));
  const JobRecord back = JobRecord::from_json(j);
  EXPECT_FALSE(back.scene.built.has_value());
  EXPECT_EQ(back.reason, r.reason);
  EXPECT_EQ(back.to_json(), j);
}

// A job that failed after timing (a visibility check): what it got to stays,
// under "partial", and no figure at the top level. A failed record written
// before "partial" existed, with its figures at the top level, reads the
// same way.
TEST(JobRecord, AFailedJobsMeasurementsAreUnderPartial) {
  JobRecord r = full_record();
  r.status = JobStatus::Failed;
  r.reason = "visibility outside [0,1]";
  r.images = {};
  r.images.visibility = "jobs/x/visibility.exr";
  r.images.invalid = "jobs/x/invalid.png";
  r.technique.gpu_bytes = 4096;
  r.second_reference = SecondReferenceRecord{*r.reference, r.metrics->visibility};
  r.classes = ClassesRecord{};
  ASSERT_TRUE(r.timing && r.metrics && r.second_reference && r.classes && r.technique.gpu_bytes);
  const json old = r.to_json();  // as a build before "partial" wrote it
  ASSERT_TRUE(old.contains("metrics"));
  ASSERT_FALSE(old.contains("partial"));

  const JobRecord back = JobRecord::from_json(old);
  EXPECT_FALSE(back.timing || back.metrics || back.second_reference || back.classes ||
               back.technique.gpu_bytes);
  EXPECT_FALSE(back.metric(*MetricPath::parse("visibility.geometry.rmse")));
  ASSERT_TRUE(back.partial);
  EXPECT_EQ(back.partial->timing->to_json(), r.timing->to_json());
  EXPECT_EQ(back.partial->metrics->to_json(), r.metrics->to_json());
  EXPECT_EQ(back.partial->second_reference->to_json(), r.second_reference->to_json());
  EXPECT_EQ(back.partial->classes->to_json(), r.classes->to_json());
  EXPECT_EQ(back.partial->gpu_bytes, r.technique.gpu_bytes);
  EXPECT_EQ(back.visibility_check->above_1, r.visibility_check->above_1);  // not a figure: kept

  const json j = back.to_json();
  for (const char* key : {"timing", "metrics", "second_reference", "classes"})
    EXPECT_FALSE(j.contains(key)) << key;
  EXPECT_FALSE(j["technique"].contains("gpu_bytes"));
  EXPECT_EQ(j["partial"]["metrics"], old["metrics"]);
  EXPECT_EQ(j["partial"]["timing"], old["timing"]);
  EXPECT_EQ(j["images"].size(), 2u);
  EXPECT_EQ(JobRecord::from_json(j).to_json(), j);

  // An ok record keeps its figures where they are.
  const json ok = full_record().to_json();
  EXPECT_EQ(JobRecord::from_json(ok).to_json(), ok);
  EXPECT_FALSE(ok.contains("partial"));
}

// What from_json throws for `j` (a test failure when it reads).
RecordError error_of(const json& j) {
  try {
    JobRecord::from_json(j);
  } catch (const RecordError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a RecordError";
  return RecordError("", "");
}

TEST(JobRecord, AnotherSchemaVersionIsRefused) {
  json j = full_record().to_json();
  j["schema_version"] = 2;
  const RecordError e = error_of(j);
  EXPECT_EQ(e.pointer(), "/schema_version");
  const std::string what = e.what();
  EXPECT_NE(what.find("schema_version 2"), std::string::npos) << what;
  EXPECT_NE(what.find("reads schema_version 1"), std::string::npos) << what;
  j.erase("schema_version");
  EXPECT_EQ(error_of(j).pointer(), "/schema_version");
  j["schema_version"] = "1";
  EXPECT_EQ(error_of(j).pointer(), "/schema_version");
}

TEST(JobRecord, MissingOrIllTypedMembersAreNamedByPointer) {
  const json good = full_record().to_json();
  struct Case {
    const char* pointer;
    json value;           // null: erase the member
    const char* at;       // the pointer the error names: a missing member's object
    const char* problem;  // the whole problem
  } cases[] = {
      {"/job_id", nullptr, "", "missing required key \"job_id\" in this object"},
      {"/width", "64", "/width", "expected an integer, found string \"64\""},
      {"/status", "done", "/status",
       "expected one of \"ok\", \"skipped\", \"failed\", found \"done\""},
      {"/scene/light/center", json::array({1, 2}), "/scene/light/center", "expected 3 numbers"},
      {"/timing/frame/median_ms", nullptr, "/timing/frame",
       "missing required key \"median_ms\" in this object"},
      {"/timing/frame/samples_ms/1", "fast", "/timing/frame/samples_ms/1",
       "expected a number (or \"nan\", \"inf\", \"-inf\"), found string \"fast\""},
      {"/metrics/visibility/all/rmse", true, "/metrics/visibility/all/rmse",
       "expected a number (or \"nan\", \"inf\", \"-inf\"), found boolean true"},
      {"/metrics/shaded/penumbra", json::array(), "/metrics/shaded/penumbra",
       "expected an object, found array []"},
      {"/reference/from_cache", 1, "/reference/from_cache",
       "expected true or false, found number 1"},
      {"/images/shaded", 3, "/images/shaded", "expected a string, found number 3"},
  };
  for (const auto& c : cases) {
    json j = good;
    const json::json_pointer p(c.pointer);
    if (c.value.is_null())
      j[p.parent_pointer()].erase(p.back());
    else
      j[p] = c.value;
    const RecordError e = error_of(j);
    EXPECT_EQ(e.pointer(), c.at) << c.pointer;
    EXPECT_EQ(e.problem(), c.problem) << c.pointer << ": " << e.what();
  }
  json j = good;
  j["timing"]["pass_order"][0] = "clear";
  const RecordError e = error_of(j);
  EXPECT_EQ(e.pointer(), "/timing/pass_order/0");
  EXPECT_NE(e.problem().find("which \"passes\" lacks"), std::string::npos) << e.what();
}

// Read from a run folder, the message names the file, the line and the place.
TEST(JobRecord, RunFolderReadingNamesFileLineAndPointer) {
  test::TempDir dir("record_file");
  const JobRecord r = full_record();
  json bad = r.to_json();
  bad["metrics"]["visibility"]["all"]["rmse"] = "low";
  json newer = r.to_json();
  newer["schema_version"] = 7;
  for (const auto& [second, pointer, what] :
       {std::tuple<json, std::string, std::string>{bad, "/metrics/visibility/all/rmse",
                                                   "expected a number"},
        {newer, "/schema_version", "schema_version 7"}}) {
    std::ofstream(dir.file("results.jsonl")) << r.to_json().dump() << "\n" << second.dump() << "\n";
    try {
      read_job_records(dir.path().string());
      FAIL() << "expected an InputError";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(e.file(), dir.file("results.jsonl"));
      EXPECT_NE(e.where().find("line 2"), std::string::npos) << msg;
      EXPECT_NE(e.where().find(pointer), std::string::npos) << msg;
      EXPECT_NE(msg.find(what), std::string::npos) << msg;
    }
  }
}

}  // namespace
}  // namespace sb

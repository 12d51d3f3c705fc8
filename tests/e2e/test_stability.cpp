// The stability figures of a run with a "stability" block: flicker is 0 for
// `none` and for a light that does not move, and positive for a hard shadow
// map under sub-texel motion; a deliberately broken variant (linear-space
// ESM at c = 200) is a failed record with its NaN count, shown broken in the
// stability table, while the other jobs run; and the sensitivity the probe
// records equals a central difference of two separately run variants.
// tests/stress runs configs/stress.json itself.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "e2e_util.h"
#include "record/job_record.h"
#include "results/report.h"

namespace sb {

using core::ImageF;
using record::JobRecord;
using results::make_markdown;

namespace {

using json = nlohmann::json;

json stability_config(const json& techniques, const json& stability) {
  return {{"scenes", {test::small_scene(1.0)}}, {"techniques", techniques},
          {"resolutions", {{160, 120}}},        {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"method", "exact"}}}, {"stability", stability}};
}

TEST(Stability, FlickerIsZeroForNoneAndAStillLightAndPositiveForAHardMapUnderSubTexelMotion) {
  const json techniques = {"none", {{"name", "shadow_map"}, {"params", {{"size", 256}}}}};
  // A 256² map over the casters' extent: 1/1024 of its diagonal is about a
  // quarter of a texel per frame.
  const test::RunOutput moving = test::run_config(
      stability_config(
          techniques,
          {{"flicker_frames", 5}, {"flicker_step", 1.0 / 1024}, {"sensitivity", false}}),
      "stability_flicker_moving");
  const json& none = moving.record("none")["stability"]["flicker"];
  EXPECT_EQ(none["frames"], 5);
  EXPECT_EQ(none["mean"], 0.0);
  EXPECT_EQ(none["max"], 0.0);
  EXPECT_GT(none["reference"]["mean"], 0.0);  // the penumbra really moves
  const json& map = moving.record("shadow_map/size=256")["stability"]["flicker"];
  EXPECT_GT(map["mean"], 0.0);
  EXPECT_GT(map["frac_over_0.05"], 0.0);  // hard edges pop: whole pixels flip
  EXPECT_EQ(map["max"], 1.0);
  EXPECT_EQ(map["reference"]["frac_over_0.05"], 0.0);  // the true shadow drifts
  EXPECT_FALSE(moving.record("shadow_map/size=256")["stability"].contains("sensitivity"));

  const test::RunOutput still = test::run_config(
      stability_config(techniques,
                       {{"flicker_frames", 3}, {"flicker_step", 0.0}, {"sensitivity", false}}),
      "stability_flicker_still");
  for (const json& r : still.records) {
    SCOPED_TRACE(r["technique_variant"].get<std::string>());
    EXPECT_EQ(r["stability"]["flicker"]["mean"], 0.0);
    EXPECT_EQ(r["stability"]["flicker"]["reference"]["mean"], 0.0);
    // Nothing moved: the first and last frames' error is the job's own.
    const double job_rmse = r["metrics"]["visibility"]["all"]["rmse"].get<double>();
    EXPECT_NEAR(r["stability"]["flicker"]["rmse_first"].get<double>(), job_rmse, 1e-6);
    EXPECT_NEAR(r["stability"]["flicker"]["rmse_last"].get<double>(), job_rmse, 1e-6);
  }
}

TEST(Stability, ABrokenVariantIsReportedBrokenWithItsNaNCountAndTheOthersRun) {
  const json techniques = {
      {{"name", "esm"},
       {"params", {{"exponent", 200}, {"log_space", {true, false}}, {"size", 256}}}}};
  const test::RunOutput out = test::run_config(
      stability_config(techniques, {{"flicker_frames", 2}, {"sensitivity", false}}),
      "stability_broken");
  const json& linear = out.record("esm/exponent=200,log_space=false,size=256");
  EXPECT_EQ(linear["status"], "failed");
  const std::int64_t nans = linear["visibility_check"]["nonfinite"].get<std::int64_t>();
  EXPECT_GT(nans, 0);
  EXPECT_NE(linear["reason"].get<std::string>().find("NaN/Inf"), std::string::npos);
  EXPECT_FALSE(linear.contains("stability"));
  const json& logspace = out.record("esm/exponent=200,log_space=true,size=256");
  EXPECT_EQ(logspace["status"], "ok");
  EXPECT_TRUE(logspace["stability"].contains("flicker"));

  std::vector<JobRecord> records;
  for (const json& r : out.records) records.push_back(JobRecord::from_json(r));
  const std::string md = make_markdown(records, "stability");
  EXPECT_NE(md.find("| esm/exponent=200,log_space=false,size=256 | **broken**: " +
                    std::to_string(nans) + " NaN/Inf"),
            std::string::npos)
      << md;
}

TEST(Stability, ASensitivityIsTheCentralDifferenceOfTwoVariants) {
  // ESM's exponent at 40: the probe renders 39.6 and 40.4. Run them as
  // variants of their own and difference their visibility images.
  const json esm = {{"name", "esm"}, {"params", {{"exponent", 40.0}, {"size", 256}}}};
  const test::RunOutput probed = test::run_config(
      stability_config(json::array({esm}), {{"flicker_frames", 0}, {"sensitivity_step", 0.01}}),
      "stability_sensitivity");
  const json& s = probed.records.at(0)["stability"]["sensitivity"];
  ASSERT_TRUE(s.contains("exponent")) << s.dump();
  EXPECT_FALSE(s.contains("sigma"));  // 0 is its sentinel: "from k"
  // The contact option's, with contact off: its variants would be equal.
  EXPECT_FALSE(s.contains("contact_length"));
  EXPECT_FALSE(s.contains("contact_thickness"));
  EXPECT_TRUE(s["light_size"].contains("reference_relative"));

  json sweep = stability_config(
      json::array({{{"name", "esm"}, {"params", {{"exponent", {39.6, 40.4}}, {"size", 256}}}}}),
      json::object());
  sweep.erase("stability");
  const test::RunOutput pair = test::run_config(sweep, "stability_sensitivity_pair");
  const ImageF lo = pair.visibility("esm/exponent=39.6,size=256");
  const ImageF hi = pair.visibility("esm/exponent=40.4,size=256");
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < lo.pixel_count(); ++i) {
    sum += std::fabs(double(hi.data[i]) - double(lo.data[i])) / 0.8;
    ++n;
  }
  // Over every pixel, against the probe's measured pixels (all but the few
  // whose tangent plane cuts the light): their share of the mean differs.
  const double expected = sum / double(n);
  const double measured_share =
      probed.records.at(0)["metrics"]["visibility"]["all"]["pixel_count"].get<double>() / double(n);
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(s["exponent"]["dv_dp"].get<double>(), expected / measured_share, 0.05 * expected)
      << "pixels measured: " << measured_share;
  EXPECT_NEAR(s["exponent"]["relative"].get<double>(), 40.0 * s["exponent"]["dv_dp"].get<double>(),
              1e-9);
  EXPECT_NEAR(s["exponent"]["step"].get<double>(), 0.4, 1e-12);
}

}  // namespace
}  // namespace sb

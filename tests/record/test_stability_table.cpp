// The stability table's verdicts from records with known figures: ok,
// degraded by each rule (RMSE over the case's threshold, mean flicker or
// popping over the reference's by the factor, a stiff parameter), broken
// (the visibility check's counts), failed and skipped; its layout (cases as
// columns, "@ WxH" only when a run has several resolutions); and the record
// members round-tripping through JSON.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "record/job_record.h"
#include "results/report.h"
#include "results/stability_table.h"
#include "sample_records.h"

namespace sb {

using record::FlickerRecord;
using record::JobRecord;
using record::JobStatus;
using record::MetricsRecord;
using record::SensitivityRecord;
using record::StabilityRecord;
using record::VisibilityCheckRecord;
using results::make_markdown;
using results::stability_cell;
using results::stability_table;
using results::StabilityCell;
using results::StabilityVerdict;

namespace {

JobRecord measured(const std::string& scene, const std::string& technique, double rmse,
                   double flicker, double popping) {
  JobRecord r = test::identity_record(scene, "64x48", technique);
  MetricsRecord m;
  m.visibility.all.rmse = rmse;
  r.metrics = m;
  r.visibility_check = VisibilityCheckRecord{0, 0, 0, 1e-5};
  StabilityRecord s;
  s.max_rmse = 0.1;
  s.flicker_factor = 2.0;
  s.stiff_threshold = 0.5;
  FlickerRecord f;
  f.frames = 8;
  f.step = 0.001;
  f.mean = flicker;
  f.frac_over_005 = popping;
  f.reference_mean = 0.001;
  f.reference_frac_over_005 = 0.0;
  s.flicker = f;
  r.stability = s;
  return r;
}

TEST(StabilityTable, EachRuleGivesItsVerdictWithTheFigureBehindIt) {
  const JobRecord ok = measured("plates", "pcf", 0.05, 0.0015, 0.0);
  EXPECT_EQ(stability_cell(ok).verdict, StabilityVerdict::Ok);
  EXPECT_EQ(stability_cell(ok).figure,
            "rmse 0.0500; flicker 1.50e-03, popping 0.00e+00 (reference 1.00e-03, 0.00e+00)");

  EXPECT_EQ(stability_cell(measured("plates", "pcf", 0.25, 0.0015, 0.0)).figure.substr(0, 17),
            "rmse 0.2500 > 0.1");
  // Flicker over 2 × 0.001 + 1e-4, and popping over 2 × 0 + 1e-4.
  EXPECT_EQ(stability_cell(measured("plates", "pcf", 0.05, 0.0022, 0.0)).verdict,
            StabilityVerdict::Degraded);
  EXPECT_EQ(stability_cell(measured("plates", "pcf", 0.05, 0.0020, 0.0)).verdict,
            StabilityVerdict::Ok);
  EXPECT_EQ(stability_cell(measured("plates", "pcf", 0.05, 0.001, 0.0002)).verdict,
            StabilityVerdict::Degraded);
  EXPECT_EQ(stability_cell(measured("plates", "pcf", 0.05, 0.001, 0.00009)).verdict,
            StabilityVerdict::Ok);

  JobRecord stiff = measured("plates", "esm", 0.05, 0.001, 0.0);
  SensitivityRecord exponent;
  exponent.relative = 3.25;
  exponent.stiff = true;
  stiff.stability->sensitivity["exponent"] = exponent;
  const StabilityCell s = stability_cell(stiff);
  EXPECT_EQ(s.verdict, StabilityVerdict::Degraded);
  EXPECT_EQ(s.figure.substr(0, 21), "stiff: exponent 3.25;");

  JobRecord broken = test::identity_record("plates", "64x48", "esm", JobStatus::Failed);
  broken.reason = "visibility outside [0,1]";
  broken.visibility_check = VisibilityCheckRecord{1536, 2, 0, 1e-5};
  EXPECT_EQ(stability_cell(broken).verdict, StabilityVerdict::Broken);
  EXPECT_EQ(stability_cell(broken).figure, "1536 NaN/Inf, 2 below 0, 0 above 1");

  JobRecord failed = test::identity_record("plates", "64x48", "vsm", JobStatus::Failed);
  failed.reason = "GL_OUT_OF_MEMORY";
  EXPECT_EQ(stability_cell(failed).verdict, StabilityVerdict::Failed);
  JobRecord skipped = test::identity_record("plates", "64x48", "shadow_volume", JobStatus::Skipped);
  EXPECT_EQ(stability_cell(skipped).verdict, StabilityVerdict::Skipped);
}

TEST(StabilityTable, CasesAreColumnsAndTechniquesRows) {
  std::vector<JobRecord> rs{measured("plates", "pcf", 0.05, 0.001, 0.0),
                            measured("plates", "esm", 0.25, 0.001, 0.0),
                            measured("grazing", "pcf", 0.05, 0.001, 0.0)};
  const auto t = stability_table(rs);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->cases, (std::vector<std::string>{"plates", "grazing"}));
  EXPECT_EQ(t->techniques, (std::vector<std::string>{"pcf", "esm"}));
  EXPECT_EQ(t->cells[1][0], &rs[1]);
  EXPECT_EQ(t->cells[1][1], nullptr);  // esm did not run on grazing
  const std::string md = make_markdown(rs, "stress");
  EXPECT_NE(md.find("| technique | plates | grazing |"), std::string::npos) << md;
  EXPECT_NE(md.find("| esm | **degraded**: rmse 0.2500 \\> 0.1; flicker"), std::string::npos) << md;

  rs[2].resolution = "128x96";
  EXPECT_EQ(stability_table(rs)->cases,
            (std::vector<std::string>{"plates @ 64x48", "grazing @ 128x96"}));
  // A run without the block has no table.
  for (auto& r : rs) r.stability.reset();
  EXPECT_FALSE(stability_table(rs).has_value());
  EXPECT_EQ(make_markdown(rs, "plain").find("## Stability"), std::string::npos);
}

TEST(StabilityTable, StabilityFiguresRoundTrip) {
  JobRecord r = measured("plates", "esm", 0.05, 0.001, 0.0);
  SensitivityRecord size;
  size.value = 1.0;
  size.step = 0.01;
  size.dv_dp = 0.09;
  size.relative = 0.09;
  size.reference_relative = 0.02;
  r.stability->sensitivity["light_size"] = size;
  SensitivityRecord failed;
  failed.error = "GL_OUT_OF_MEMORY";
  r.stability->sensitivity["exponent"] = failed;
  const nlohmann::json j = r.to_json();
  EXPECT_EQ(j["stability"]["flicker"]["frac_over_0.05"], 0.0);
  EXPECT_EQ(j["stability"]["sensitivity"]["light_size"]["reference_relative"], 0.02);
  EXPECT_EQ(j["stability"]["sensitivity"]["exponent"]["error"], "GL_OUT_OF_MEMORY");
  EXPECT_FALSE(j["stability"]["sensitivity"]["exponent"].contains("reference_relative"));
  EXPECT_EQ(JobRecord::from_json(j).to_json(), j);
}

}  // namespace
}  // namespace sb

// The `terminator` region: the pixels whose tangent plane cuts the light
// (reference.horizon_cut_pixels), which every other region leaves out, get
// their own figures in every record. On the sphere grid (curved casters,
// each with a terminator band) the record's terminator figures are
// recomputed here from the files the run wrote (the EXRs read with
// OpenImageIO, the mask PNG), and the band is checked to be outside
// `geometry` and `all`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "e2e_util.h"

namespace sb::test {
namespace {

using core::ImageF;
using nlohmann::json;

TEST(TerminatorRegion, HoldsTheHorizonCutPixelsWithFiguresOfTheirOwnThatGeometryLeavesOut) {
  const json config = {{"name", "terminator"},
                       {"scenes", {small_scene(2.0)}},
                       {"techniques",
                        {{{"name", "shadow_map"}, {"params", {{"size", 512}}}},
                         {{"name", "pcss"}, {"params", {{"size", 512}}}}}},
                       {"resolutions", {{96, 72}}},
                       {"frames", {{"warmup", 0}, {"timed", 1}}},
                       {"reference", {{"spp", 16}}}};
  const RunOutput out = run_config(config, "terminator_region");
  ASSERT_EQ(out.records.size(), 2u);
  for (const json& r : out.records) {
    SCOPED_TRACE(r["technique_variant"].get<std::string>());
    ASSERT_EQ(r["status"], "ok") << r.value("reason", "");
    const std::int64_t cut = r["reference"]["horizon_cut_pixels"];
    EXPECT_GT(cut, 0);  // curved casters: a band at each sphere's terminator
    const json& m = r["metrics"];
    for (const char* image : {"visibility", "shaded"}) {
      ASSERT_TRUE(m[image].contains("terminator")) << image;
      EXPECT_EQ(m[image]["terminator"]["pixel_count"], cut) << image;
    }

    // The mask is the band: disjoint from `all` and `geometry`, and with
    // `all` every pixel.
    const std::vector<uint8_t> band = out.mask(r, "terminator");
    const std::vector<uint8_t> all = out.mask(r, "all");
    const std::vector<uint8_t> geometry = out.mask(r, "geometry");
    std::int64_t in_band = 0, in_geometry = 0;
    for (std::size_t p = 0; p < band.size(); ++p) {
      in_band += band[p];
      in_geometry += geometry[p];
      EXPECT_NE(band[p], all[p]) << "pixel " << p;
      EXPECT_FALSE(band[p] && geometry[p]) << "pixel " << p;
    }
    EXPECT_EQ(in_band, cut);
    EXPECT_EQ(m["visibility"]["geometry"]["pixel_count"], in_geometry);

    // Its figures are the technique's own values there against the
    // reference's: recomputed from the EXRs over the mask, in double.
    const ImageF v = out.image(r, "visibility"), ref = out.image(r, "reference_visibility");
    double sq = 0, abs = 0, signed_sum = 0, largest = 0;
    for (std::size_t p = 0; p < band.size(); ++p)
      if (band[p]) {
        const double d = double(v.data[p] - ref.data[p]);  // subtracted in float, as OIIO does
        sq += d * d, abs += std::fabs(d), signed_sum += d;
        largest = std::max(largest, std::fabs(d));
      }
    const json& t = m["visibility"]["terminator"];
    const double n = double(in_band);
    EXPECT_NEAR(t["rmse"].get<double>(), std::sqrt(sq / n), 1e-9);
    EXPECT_NEAR(t["mae"].get<double>(), abs / n, 1e-9);
    EXPECT_NEAR(t["mean_signed"].get<double>(), signed_sum / n, 1e-9);
    EXPECT_NEAR(t["max_error"].get<double>(), largest, 1e-9);
    EXPECT_GT(t["rmse"].get<double>(), 0.0);  // the map techniques test the light's centre only
    ASSERT_TRUE(t.contains("flip_mean"));
    EXPECT_GT(t["flip_mean"].get<double>(), 0.0);
  }
}

}  // namespace
}  // namespace sb::test

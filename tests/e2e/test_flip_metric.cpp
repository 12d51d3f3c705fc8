// The FLIP errors a record holds (metrics.<image>.<region>.flip_mean) are
// FLIP (metrics/flip.h, tested against NVIDIA's implementation in
// tests/metrics) of the files the run wrote: the shaded PNGs decoded from
// sRGB, as FLIP's own tool reads them, and the visibility EXRs as grey
// images, the unmeasured pixels given the reference's values, averaged over
// the region's mask; at the config's metrics.flip_pixels_per_degree.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/image.h"
#include "e2e_util.h"
#include "metrics/flip.h"
#include "metrics/image_io.h"
#include "metrics/regions.h"

namespace sb::test {
namespace {

using core::ImageF;
using nlohmann::json;
namespace fs = std::filesystem;

json small_config(double ppd) {
  return {{"name", "flip"},
          {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 3}, {"light_size", 2.0}}}}}},
          {"techniques",
           {{{"name", "shadow_map"}, {"params", {{"size", 512}}}},
            {{"name", "pcss"}, {"params", {{"size", 512}}}}}},
          {"resolutions", {{96, 72}}},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", 16}}},
          {"metrics", {{"flip_pixels_per_degree", ppd}}}};
}

double flip_of_files(const fs::path& run, const json& r, const std::string& image,
                     const std::string& region, double ppd) {
  const json& images = r["images"];
  const ImageF mask_image =
      metrics::io::read_image((run / images["masks"][region].get<std::string>()).string());
  std::vector<uint8_t> mask(mask_image.pixel_count());
  for (std::size_t p = 0; p < mask.size(); ++p) mask[p] = mask_image.data[p] > 0.5f ? 1 : 0;
  const ImageF all_mask =
      metrics::io::read_image((run / images["masks"]["all"].get<std::string>()).string());
  std::vector<uint8_t> measured(all_mask.pixel_count());
  for (std::size_t p = 0; p < measured.size(); ++p) measured[p] = all_mask.data[p] > 0.5f ? 1 : 0;
  ImageF test, ref;
  if (image == "shaded") {
    test = metrics::linear_from_srgb(
        metrics::io::read_image((run / images["shaded"].get<std::string>()).string()));
    ref = metrics::linear_from_srgb(
        metrics::io::read_image((run / images["reference_shaded"].get<std::string>()).string()));
  } else {
    test = metrics::io::read_image((run / images["visibility"].get<std::string>()).string());
    ref =
        metrics::io::read_image((run / images["reference_visibility"].get<std::string>()).string());
  }
  const ImageF map =
      metrics::flip(metrics::with_unmeasured_from(test, ref, measured), ref, ppd).error;
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t p = 0; p < mask.size(); ++p)
    if (mask[p]) sum += map.data[p], ++n;
  return sum / static_cast<double>(n);
}

TEST(FlipMetric, TheRecordsFlipMeansAreFlipOfTheFilesAtTheConfigsDistance) {
  constexpr double kPpd = 40.0;
  const RunOutput out = run_config(small_config(kPpd), "flip_metric");
  ASSERT_EQ(out.records.size(), 2u);
  for (const json& r : out.records) {
    ASSERT_EQ(r["status"], "ok") << r.value("reason", "");
    EXPECT_EQ(r["spec"]["metrics"]["flip_pixels_per_degree"], kPpd);
    ASSERT_TRUE(r["images"].contains("flip_shaded"));
    EXPECT_TRUE(
        fs::is_regular_file(fs::path(out.dir) / r["images"]["flip_shaded"].get<std::string>()));
    for (const std::string image : {"shaded", "visibility"})
      for (const std::string region : {"all", "geometry", "penumbra"}) {
        SCOPED_TRACE(r["technique_variant"].get<std::string>() + " " + image + "." + region);
        const double recorded = r["metrics"][image][region]["flip_mean"];
        EXPECT_NEAR(recorded, flip_of_files(out.dir, r, image, region, kPpd), 1e-6);
        EXPECT_GT(recorded, 0.0);
      }
  }
  // The hard shadow map looks worse than PCSS's soft shadows to FLIP, as to the eye.
  EXPECT_GT(out.record("shadow_map/size=512")["metrics"]["shaded"]["penumbra"]["flip_mean"],
            out.record("pcss/size=512")["metrics"]["shaded"]["penumbra"]["flip_mean"]);
}

TEST(FlipMetric, TheViewingDistanceChangesTheFigure) {
  const RunOutput near = run_config(small_config(20.0), "flip_metric_near");
  const RunOutput far = run_config(small_config(120.0), "flip_metric_far");
  const double a = near.record("pcss/size=512")["metrics"]["shaded"]["all"]["flip_mean"];
  const double b = far.record("pcss/size=512")["metrics"]["shaded"]["all"]["flip_mean"];
  EXPECT_NE(a, b);
}

}  // namespace
}  // namespace sb::test

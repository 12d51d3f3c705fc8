// The FLIP errors a record holds (metrics.<image>.<region>.flip_mean) are
// FLIP (metrics/flip.h, tested against NVIDIA's implementation in
// tests/metrics) of the files the run wrote: the shaded PNGs decoded from
// sRGB, as FLIP's own tool reads them, and the visibility EXRs as grey
// images, the pixels outside the region's SSIM rule given the reference's
// values (outside the measured ones; outside the region itself for
// `geometry` and `terminator`), averaged over the region's mask; at the
// config's metrics.flip_pixels_per_degree. metrics.flip_shaded is what
// FLIP's tool prints for the two shaded PNGs: every pixel, nothing replaced.
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

// The job's and the reference's images as FLIP reads them.
std::pair<ImageF, ImageF> images_of(const fs::path& run, const json& r, const std::string& image) {
  const json& images = r["images"];
  if (image == "shaded")
    return {metrics::linear_from_srgb(
                metrics::io::read_image((run / images["shaded"].get<std::string>()).string())),
            metrics::linear_from_srgb(metrics::io::read_image(
                (run / images["reference_shaded"].get<std::string>()).string()))};
  return {
      metrics::io::read_image((run / images["visibility"].get<std::string>()).string()),
      metrics::io::read_image((run / images["reference_visibility"].get<std::string>()).string())};
}

double flip_of_files(const RunOutput& run, const json& r, const std::string& image,
                     const std::string& region, double ppd) {
  const std::vector<uint8_t> mask = run.mask(r, region);
  const bool own = region == "geometry" || region == "terminator";
  const std::vector<uint8_t> inside = own ? mask : run.mask(r, "all");
  const auto [test, ref] = images_of(run.dir, r, image);
  const ImageF map =
      metrics::flip(ref, metrics::with_unmeasured_from(test, ref, inside), ppd).error;
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
      for (const std::string region : {"all", "geometry", "penumbra", "terminator"}) {
        std::string where = r["technique_variant"].get<std::string>();
        where += " " + image;
        where += "." + region;
        SCOPED_TRACE(where);
        const double recorded = r["metrics"][image][region]["flip_mean"];
        EXPECT_NEAR(recorded, flip_of_files(out, r, image, region, kPpd), 1e-6);
        EXPECT_GT(recorded, 0.0);
      }
    // FLIP as its tool prints it for the two PNGs: every pixel, the
    // terminator band's errors included.
    const auto [test, ref] = images_of(out.dir, r, "shaded");
    ASSERT_TRUE(r["metrics"].contains("flip_shaded"));
    const double whole = r["metrics"]["flip_shaded"];
    EXPECT_NEAR(whole, metrics::flip(ref, test, kPpd).mean, 1e-6);
    EXPECT_NE(whole, r["metrics"]["shaded"]["all"]["flip_mean"].get<double>());
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

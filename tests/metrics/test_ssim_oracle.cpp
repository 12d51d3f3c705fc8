// SSIM against scikit-image (tests/metrics/ssim_oracle.py run by
// /usr/bin/python3). A missing scikit-image is a failure, not a skip: CI
// installs python3-skimage.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "metrics/geometry_region.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "test_util.h"

namespace sb::metrics {

using core::ImageF;

namespace {

constexpr double kTol = 1e-4;

struct OracleRun {
  bool ok = false;
  double value = 0;
  std::string output;
};

std::string quote(const std::string& s) { return "'" + s + "'"; }

OracleRun run_oracle(const std::string& args) {
  const std::string cmd =
      "/usr/bin/python3 " +
      quote(std::string(SHADOWBENCH_SOURCE_DIR) + "/tests/metrics/ssim_oracle.py") + " " + args +
      " 2>&1";
  OracleRun run;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) {
    run.output = "popen failed for: " + cmd;
    return run;
  }
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) run.output += buf;
  const int status = ::pclose(p);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 3) {
    run.output =
        "scikit-image is not importable by /usr/bin/python3: install python3-skimage "
        "(apt-get install python3-skimage). Oracle said: " +
        run.output;
    return run;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    run.output = "oracle failed (" + cmd + "): " + run.output;
    return run;
  }
  try {
    run.value = std::stod(run.output);
    run.ok = true;
  } catch (const std::exception&) {
    run.output = "unparsable oracle output: " + run.output;
  }
  return run;
}

// Writes the pair as EXR, reads it back (the path real results take), dumps
// it for the oracle and compares the mean SSIM both ways (float64 and float32
// skimage), and the full map.
void check_against_skimage(const std::string& name, const ImageF& a0, const ImageF& b0) {
  test::TempDir dir("ssim_" + name);
  metrics::io::write_exr(dir.file("a.exr"), a0);
  metrics::io::write_exr(dir.file("b.exr"), b0);
  const ImageF a = metrics::io::read_image(dir.file("a.exr"));
  const ImageF b = metrics::io::read_image(dir.file("b.exr"));
  test::write_dump(dir.file("a.sbf"), a);
  test::write_dump(dir.file("b.sbf"), b);
  const std::string files = quote(dir.file("a.sbf")) + " " + quote(dir.file("b.sbf"));

  const OracleRun ref = run_oracle(files + " --map " + quote(dir.file("map.sbf")));
  ASSERT_TRUE(ref.ok) << ref.output;
  const double ours = ssim(a, b);
  EXPECT_NEAR(ours, ref.value, kTol) << name;
  std::printf("[ %s ] ssim ours %.12f skimage(f64) %.12f diff %.3g\n", name.c_str(), ours,
              ref.value, ours - ref.value);

  const OracleRun ref32 = run_oracle("--float32 " + files);
  ASSERT_TRUE(ref32.ok) << ref32.output;
  EXPECT_NEAR(ours, ref32.value, kTol) << name << " (float32 skimage)";
  std::printf("[ %s ] skimage(f32) %.12f diff %.3g\n", name.c_str(), ref32.value,
              ours - ref32.value);

  // Full map, borders included (reflect mode).
  const ImageF ref_map = test::read_dump(dir.file("map.sbf"));
  const ImageF map = ssim_map(a, b);
  ASSERT_TRUE(map.same_shape(ref_map));
  double worst = 0;
  for (size_t i = 0; i < map.data.size(); ++i) {
    worst = std::fmax(worst, std::fabs(static_cast<double>(map.data[i]) - ref_map.data[i]));
  }
  EXPECT_LT(worst, kTol) << name << " map";
  std::printf("[ %s ] map max |diff| %.3g\n", name.c_str(), worst);

  // Masked mean = mean of skimage's map over masked interior pixels.
  std::vector<uint8_t> mask(a.pixel_count(), 0);
  for (size_t p = 0; p < mask.size(); ++p) mask[p] = (p * 7 + p / a.width) % 3 == 0;
  double sum = 0;
  size_t count = 0;
  for (int y = kSsimRadius; y < a.height - kSsimRadius; ++y) {
    for (int x = kSsimRadius; x < a.width - kSsimRadius; ++x) {
      if (!mask[static_cast<size_t>(y) * a.width + x]) continue;
      for (int c = 0; c < a.channels; ++c) sum += ref_map.at(x, y, c);
      ++count;
    }
  }
  ASSERT_GT(count, 0u);
  EXPECT_NEAR(ssim(a, b, 1.0, &mask), sum / static_cast<double>(count * a.channels), kTol)
      << name << " masked";
}

TEST(metrics_ssim_oracle, NoiseOneChannel) {
  check_against_skimage("noise1", test::noise_image(67, 45, 1, 1), test::noise_image(67, 45, 1, 2));
}

TEST(metrics_ssim_oracle, NoisyCopyOneChannel) {
  const ImageF a = test::pattern_image(53, 31, 1);
  ImageF b = a;
  const ImageF n = test::noise_image(53, 31, 1, 3, -0.1f, 0.1f);
  for (size_t i = 0; i < b.data.size(); ++i) b.data[i] += n.data[i];
  check_against_skimage("noisy1", a, b);
}

TEST(metrics_ssim_oracle, BlurredShiftedPatternThreeChannels) {
  const ImageF a = test::pattern_image(67, 45, 3);
  check_against_skimage("blur3", a, test::blur_shift(a, 2, -1));
}

TEST(metrics_ssim_oracle, NoiseThreeChannelsSmall) {
  check_against_skimage("noise3", test::noise_image(23, 19, 3, 4), test::noise_image(23, 19, 3, 5));
}

TEST(metrics_ssim_oracle, SmallestImage) {
  // 11 rows: the cropped interior is a single row.
  const ImageF a = test::pattern_image(13, 11, 1);
  check_against_skimage("smallest", a, test::blur_shift(a, 1, 1));
}

// The geometry region's SSIM (compare_within) against skimage on the image
// whose pixels outside the region took the reference's values, averaged over
// the region's interior pixels: the oracle does both steps itself. The test
// image is wrong everywhere outside the region (a sky the technique got
// wrong), which must not reach the region's windows.
void check_region_against_skimage(const std::string& name, const ImageF& a, const ImageF& b,
                                  const std::vector<uint8_t>& region) {
  test::TempDir dir("ssim_region_" + name);
  ImageF mask(a.width, a.height, 1);
  for (size_t p = 0; p < region.size(); ++p) mask.data[p] = region[p] ? 1.0f : 0.0f;
  test::write_dump(dir.file("a.sbf"), a);
  test::write_dump(dir.file("b.sbf"), b);
  test::write_dump(dir.file("region.sbf"), mask);
  const OracleRun ref = run_oracle(quote(dir.file("a.sbf")) + " " + quote(dir.file("b.sbf")) +
                                   " --region " + quote(dir.file("region.sbf")));
  ASSERT_TRUE(ref.ok) << ref.output;
  const double ours = compare_within(a, b, region).ssim;
  EXPECT_NEAR(ours, ref.value, kTol) << name;
  std::printf("[ %s ] region ssim ours %.12f skimage %.12f\n", name.c_str(), ours, ref.value);
}

// A disc of surface in a frame of sky; the test image's sky is noise.
std::vector<uint8_t> disc(int w, int h) {
  std::vector<uint8_t> region(static_cast<size_t>(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double dx = x - 0.5 * w, dy = y - 0.55 * h;
      region[static_cast<size_t>(y) * w + x] = dx * dx + dy * dy < 0.12 * w * w ? 1 : 0;
    }
  return region;
}

TEST(metrics_ssim_oracle, GeometryRegionOneChannel) {
  const ImageF ref = test::pattern_image(47, 39, 1);
  ImageF test = test::blur_shift(ref, 2, 1);
  const std::vector<uint8_t> region = disc(47, 39);
  const ImageF sky = test::noise_image(47, 39, 1, 6);
  for (size_t p = 0; p < region.size(); ++p)
    if (!region[p]) test.data[p] = sky.data[p];
  check_region_against_skimage("geometry1", test, ref, region);
}

TEST(metrics_ssim_oracle, GeometryRegionThreeChannels) {
  const ImageF ref = test::pattern_image(41, 33, 3);
  ImageF test = test::blur_shift(ref, -1, 2);
  const std::vector<uint8_t> region = disc(41, 33);
  const ImageF sky = test::noise_image(41, 33, 3, 7);
  for (size_t p = 0; p < region.size(); ++p)
    if (!region[p])
      for (size_t c = 0; c < 3; ++c) test.data[p * 3 + c] = sky.data[p * 3 + c];
  check_region_against_skimage("geometry3", test, ref, region);
}

}  // namespace
}  // namespace sb::metrics

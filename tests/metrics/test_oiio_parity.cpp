// compare() against OpenImageIO's ImageBufAlgo::compare (what idiff reports),
// on float EXR pairs written by metrics::io::write_exr and read back by OIIO itself.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <cmath>

#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "test_util.h"

namespace sb::metrics {

using core::ImageF;

namespace {

void expect_rel(double ours, double theirs, const char* what) {
  EXPECT_LE(std::fabs(ours - theirs), 1e-6 * std::fabs(theirs))
      << what << ": ours " << ours << ", OIIO " << theirs;
}

void check_parity(int channels, uint32_t seed) {
  test::TempDir dir("parity" + std::to_string(channels));
  const int w = 37, h = 23;
  const ImageF ref = test::noise_image(w, h, channels, seed);
  ImageF test = ref;
  // Small noise everywhere plus a few large outliers.
  const ImageF n = test::noise_image(w, h, channels, seed + 1, -0.03f, 0.03f);
  for (size_t i = 0; i < test.data.size(); ++i) {
    test.data[i] = std::fmin(1.0f, std::fmax(0.0f, test.data[i] + n.data[i]));
  }
  test.at(13, 7, channels - 1) = 1.0f - ref.at(13, 7, channels - 1) * 0.1f;
  test.at(30, 20, 0) = 0.0f;

  const std::string ft = dir.file("test.exr"), fr = dir.file("ref.exr");
  metrics::io::write_exr(ft, test);
  metrics::io::write_exr(fr, ref);

  OIIO::ImageBuf a(ft), b(fr);
  // Huge thresholds: OIIO sets .error whenever a value exceeds failthresh.
  const OIIO::ImageBufAlgo::CompareResults r = OIIO::ImageBufAlgo::compare(a, b, 1e30f, 1e30f);
  ASSERT_FALSE(r.error) << a.geterror() << b.geterror();
  ASSERT_EQ(a.nchannels(), channels);

  const ErrorStats s = compare(metrics::io::read_image(ft), metrics::io::read_image(fr));
  expect_rel(s.rmse, r.rms_error, "rmse");
  expect_rel(s.mae, r.meanerror, "mae");
  expect_rel(s.psnr, r.PSNR, "psnr");
  EXPECT_EQ(s.max_error, r.maxerror);
  EXPECT_EQ(s.max_x, r.maxx);
  EXPECT_EQ(s.max_y, r.maxy);
  EXPECT_EQ(s.max_channel, r.maxc);
  // EXR float is lossless: the in-memory images give the same figures.
  const ErrorStats mem = compare(test, ref);
  EXPECT_EQ(mem.rmse, s.rmse);
  EXPECT_EQ(mem.max_error, s.max_error);
}

TEST(metrics_oiio_parity, OneChannel) { check_parity(1, 100); }
TEST(metrics_oiio_parity, ThreeChannels) { check_parity(3, 200); }

}  // namespace
}  // namespace sb::metrics

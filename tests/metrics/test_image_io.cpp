// sb::io writers and reader: round trips, channel naming, atomic replacement
// and error reporting.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "metrics/image_io.h"
#include "test_util.h"

namespace sb::metrics::io {

using core::ImageF;
using core::JobError;

namespace {

std::vector<std::string> leftovers(const std::filesystem::path& dir) {
  std::vector<std::string> tmp;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().filename().string().find(".tmp-") != std::string::npos) {
      tmp.push_back(e.path().string());
    }
  }
  return tmp;
}

TEST(metrics_image_io, ExrRoundTripIsExactWithChannelNames) {
  test::TempDir dir("exr");
  const char* names[] = {"Y", "YA", "RGB", "RGBA"};
  for (int c = 1; c <= 4; ++c) {
    const ImageF img = test::noise_image(19, 7, c, static_cast<uint32_t>(c), -2.0f, 5.0f);
    const std::string path = dir.file("img" + std::to_string(c) + ".exr");
    write_exr(path, img);
    const ImageF back = read_image(path);
    ASSERT_TRUE(back.same_shape(img));
    EXPECT_EQ(back.data, img.data);

    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in);
    EXPECT_EQ(std::string(in->format_name()), "openexr");
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
    std::string joined;
    for (const auto& n : in->spec().channelnames) joined += n;
    EXPECT_EQ(joined, names[c - 1]);
  }
  EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(metrics_image_io, PngRoundTripClampsAndRounds) {
  test::TempDir dir("png");
  for (int c : {1, 3, 4}) {
    ImageF img(9, 4, c);
    for (size_t i = 0; i < img.data.size(); ++i) {
      img.data[i] = static_cast<float>(i % 256) / 255.0f;
    }
    img.data[0] = -0.5f;                                    // -> 0
    img.data[1] = 1.7f;                                     // -> 255
    img.data[2] = std::numeric_limits<float>::quiet_NaN();  // -> 0
    img.data[3] = 100.4f / 255.0f;                          // -> 100
    img.data[4] = 100.6f / 255.0f;                          // -> 101
    img.data[img.data.size() - 1] = 0.0f;                   // alpha 0 must not wipe colour
    const std::string path = dir.file("img" + std::to_string(c) + ".png");
    write_png(path, img);
    const ImageF back = read_image(path);
    ASSERT_TRUE(back.same_shape(img));
    for (size_t i = 0; i < img.data.size(); ++i) {
      float want = std::isnan(img.data[i]) ? 0.0f : std::fmin(1.0f, std::fmax(0.0f, img.data[i]));
      want = std::round(want * 255.0f) / 255.0f;
      ASSERT_NEAR(back.data[i], want, 1e-6) << "channels " << c << " value " << i;
    }
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in);
    EXPECT_EQ(std::string(in->format_name()), "png");
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
    EXPECT_EQ(in->spec().nchannels, c);
  }
  EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(metrics_image_io, MaskPngIsOneGreyChannelOf255WhereIncluded) {
  test::TempDir dir("mask");
  const std::vector<uint8_t> mask = {0, 1, 7, 0, 0, 1};  // any nonzero is "in"
  const std::string path = dir.file("mask.png");
  write_mask_png(path, mask, 3, 2);
  const ImageF back = read_image(path);
  ASSERT_EQ(back.width, 3);
  ASSERT_EQ(back.height, 2);
  ASSERT_EQ(back.channels, 1);
  for (size_t i = 0; i < mask.size(); ++i)
    EXPECT_EQ(back.data[i], mask[i] != 0 ? 1.0f : 0.0f) << i;  // 255 and 0 as bytes
  EXPECT_THROW(write_mask_png(dir.file("short.png"), mask, 4, 2), std::invalid_argument);
  EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(metrics_image_io, OverwritesAtomically) {
  test::TempDir dir("overwrite");
  const std::string path = dir.file("x.exr");
  write_exr(path, ImageF(4, 4, 1, 0.25f));
  write_exr(path, ImageF(6, 2, 3, 0.75f));
  const ImageF back = read_image(path);
  EXPECT_EQ(back.width, 6);
  EXPECT_EQ(back.channels, 3);
  EXPECT_EQ(back.data[0], 0.75f);
  EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(metrics_image_io, FailuresThrowJobErrorNamingThePath) {
  test::TempDir dir("fail");
  const std::string missing_dir = dir.file("no/such/dir/x.exr");
  try {
    write_exr(missing_dir, ImageF(4, 4, 1));
    FAIL() << "no exception";
  } catch (const JobError& e) {
    EXPECT_NE(std::string(e.what()).find(missing_dir), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_png(dir.file("five.png"), ImageF(4, 4, 5)), JobError);
  EXPECT_THROW(write_exr(dir.file("empty.exr"), ImageF()), JobError);
  const std::string absent = dir.file("absent.exr");
  try {
    read_image(absent);
    FAIL() << "no exception";
  } catch (const JobError& e) {
    EXPECT_NE(std::string(e.what()).find(absent), std::string::npos) << e.what();
  }
  EXPECT_TRUE(leftovers(dir.path()).empty());
  EXPECT_FALSE(std::filesystem::exists(dir.file("five.png")));
}

// An image that does not fit says why ("No space left
// on device"), for OpenImageIO's writers too. A 16 KiB tmpfs mounted on a
// test folder: root only, skipped elsewhere (core's FailedWriteNamesTheReason
// covers the reason without privileges).
TEST(metrics_image_io, FullFileSystemIsNamedForImages) {
  test::TempDir dir("full");
  const std::string mnt = dir.file("small");
  std::filesystem::create_directories(mnt);
  if (::geteuid() != 0 || ::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=16k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (not root)";
  struct Unmount {
    std::string at;
    ~Unmount() { ::umount2(at.c_str(), MNT_DETACH); }
  } unmount{mnt};
  const ImageF noise = test::noise_image(256, 256, 4, 7u, 0.0f, 1.0f);  // 256 KiB, incompressible
  for (const std::string& name : {std::string("shaded.png"), std::string("v.exr")}) {
    const std::string path = (std::filesystem::path(mnt) / name).string();
    try {
      if (name == "v.exr")
        write_exr(path, noise);
      else
        write_png(path, noise);
      FAIL() << "wrote " << name << " into 16 KiB";
    } catch (const JobError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find("No space left on device"), std::string::npos) << what;
    }
  }
  EXPECT_TRUE(std::filesystem::is_empty(mnt));
}

// png_byte against std::lround(clamp(v) * 255) on every float within 4096
// ulps of each value where the rounding changes (v * 255 = k + 1/2) and of
// the clamp's ends, plus a stride through all of [0, 1] and the odd values.
TEST(metrics_image_io, PngBytesRoundHalfAwayFromZeroAsLroundDoes) {
  const auto truth = [](float v) {
    const float c = v > 0.0f ? std::min(v, 1.0f) : 0.0f;
    return static_cast<uint8_t>(std::lround(c * 255.0f));
  };
  std::vector<float> centres = {0.0f, 1.0f};
  for (int k = 0; k < 255; ++k) centres.push_back((float(k) + 0.5f) / 255.0f);
  size_t checked = 0;
  for (const float centre : centres) {
    float below = centre, above = centre;
    for (int step = 0; step < 4096; ++step) {
      for (const float v : {below, above}) {
        ASSERT_EQ(png_byte(v), truth(v)) << std::hexfloat << v;
        ++checked;
      }
      below = std::nextafter(below, -1.0f);
      above = std::nextafter(above, 2.0f);
    }
  }
  for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 997) {
    float v;
    std::memcpy(&v, &bits, sizeof v);
    ASSERT_EQ(png_byte(v), truth(v)) << std::hexfloat << v;
    ++checked;
  }
  EXPECT_EQ(png_byte(std::nanf("")), 0);
  EXPECT_EQ(png_byte(-std::numeric_limits<float>::infinity()), 0);
  EXPECT_EQ(png_byte(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(png_byte(-0.0f), 0);
  EXPECT_GT(checked, 2000000u);
}

}  // namespace
}  // namespace sb::metrics::io

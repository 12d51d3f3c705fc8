#include "metrics/image_io.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_codec.h"

namespace sb::metrics::io {

using core::AtomicFile;
using core::image_codec;
using core::ImageF;
using core::JobError;

namespace {

// What the codec cannot be asked to write: no pixels, or a channel count
// with no channel names.
void check_writable(const std::string& path, const ImageF& img) {
  if (img.width <= 0 || img.height <= 0 ||
      img.data.size() != img.pixel_count() * static_cast<size_t>(std::max(img.channels, 0))) {
    throw JobError(path + ": cannot write an empty or malformed image (" +
                   std::to_string(img.width) + "x" + std::to_string(img.height) + "x" +
                   std::to_string(img.channels) + ")");
  }
  if (img.channels < 1 || img.channels > 4)
    throw JobError(path + ": cannot write an image with " + std::to_string(img.channels) +
                   " channels (1 to 4 supported)");
}

// `write` writes the temporary file it is given and returns "" or its error.
template <typename Write>
void write_atomic(const std::string& path, Write write) {
  AtomicFile file(path, path + ": ");
  if (const std::string err = write(file.temp_path()); !err.empty())
    throw JobError(path + ": " + err);
  file.commit();
}

const core::ImageCodec& codec_for(const std::string& path) {
  try {
    return image_codec();
  } catch (const std::runtime_error& e) {
    throw JobError(path + ": " + e.what());
  }
}

}  // namespace

void write_exr(const std::string& path, const ImageF& img) {
  check_writable(path, img);
  const core::ImageCodec& codec = codec_for(path);
  write_atomic(path, [&](const std::string& temp) { return codec.write_exr(temp, img); });
}

uint8_t png_byte(float v) {
  const float c = v > 0.0f ? std::min(v, 1.0f) : 0.0f;  // NaN -> 0
  // std::lround(c * 255), exactly (adding 0.5 to a float is exact in double,
  // and the value is not negative), but a plain conversion, not a libm call.
  // NOLINTNEXTLINE(bugprone-incorrect-roundings): exact here, as said above
  return static_cast<uint8_t>(static_cast<double>(c * 255.0f) + 0.5);
}

namespace {

using core::PngPacking;

// Fast for the images (write_png), small for the masks (write_mask_png).
void write_png_packed(const std::string& path, const ImageF& img, PngPacking packing) {
  check_writable(path, img);
  const core::ImageCodec& codec = codec_for(path);
  core::Image8 bytes{img.width, img.height, img.channels, std::vector<uint8_t>(img.data.size())};
  for (size_t i = 0; i < bytes.data.size(); ++i) bytes.data[i] = png_byte(img.data[i]);
  write_atomic(path,
               [&](const std::string& temp) { return codec.write_png(temp, bytes, packing); });
}

}  // namespace

void write_png(const std::string& path, const ImageF& img) {
  write_png_packed(path, img, PngPacking::Fast);
}

void write_mask_png(const std::string& path, const std::vector<uint8_t>& mask, int width,
                    int height) {
  ImageF img(std::max(width, 0), std::max(height, 0), 1);
  if (mask.size() != img.pixel_count())
    throw std::invalid_argument(path + ": a mask of " + std::to_string(mask.size()) +
                                " pixels for a " + std::to_string(width) + "x" +
                                std::to_string(height) + " image");
  for (size_t i = 0; i < mask.size(); ++i) img.data[i] = mask[i] != 0 ? 1.0f : 0.0f;
  write_png_packed(path, img, PngPacking::Small);
}

ImageF read_image(const std::string& path) {
  ImageF img;
  if (const std::string err = codec_for(path).read_image(path, img); !err.empty())
    throw JobError(path + ": " + err);
  return img;
}

}  // namespace sb::metrics::io

#include "metrics/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

namespace sb::metrics::io {

using core::AtomicFile;
using core::ImageF;
using core::JobError;

namespace {

std::vector<std::string> channel_names(const std::string& path, int channels) {
  switch (channels) {
    case 1:
      return {"Y"};
    case 2:
      return {"Y", "A"};
    case 3:
      return {"R", "G", "B"};
    case 4:
      return {"R", "G", "B", "A"};
    default:
      throw JobError(path + ": cannot write an image with " + std::to_string(channels) +
                     " channels (1 to 4 supported)");
  }
}

OIIO::ImageSpec make_spec(const std::string& path, const ImageF& img, const OIIO::TypeDesc& type) {
  if (img.width <= 0 || img.height <= 0 ||
      img.data.size() != img.pixel_count() * static_cast<size_t>(std::max(img.channels, 0))) {
    throw JobError(path + ": cannot write an empty or malformed image (" +
                   std::to_string(img.width) + "x" + std::to_string(img.height) + "x" +
                   std::to_string(img.channels) + ")");
  }
  OIIO::ImageSpec spec(img.width, img.height, img.channels, type);
  spec.channelnames = channel_names(path, img.channels);
  spec.alpha_channel = (img.channels == 2 || img.channels == 4) ? img.channels - 1 : -1;
  return spec;
}

void write_atomic(const std::string& path, const char* format, const OIIO::ImageSpec& spec,
                  const void* pixels) {
  AtomicFile file(path, path + ": ");
  // Create by format name: the temporary name has no usable extension.
  auto out = OIIO::ImageOutput::create(format);
  if (!out) {
    throw JobError(path + ": no " + format + " writer: " + OIIO::geterror());
  }
  bool ok = out->open(file.temp_path(), spec) && out->write_image(spec.format, pixels);
  std::string err = ok ? std::string() : out->geterror();
  if (!out->close() && ok) {
    ok = false;
    err = out->geterror();
  }
  if (!ok) throw JobError(path + ": writing " + format + " failed: " + err);
  file.commit();
}

}  // namespace

void write_exr(const std::string& path, const ImageF& img) {
  OIIO::ImageSpec spec = make_spec(path, img, OIIO::TypeDesc::FLOAT);
  // OIIO stamps the current time unless told otherwise; a fixed stamp keeps
  // identical runs byte-identical (the record says when the job ran).
  spec.attribute("DateTime", "1970:01:01 00:00:00");
  // zlib level 1, not OpenEXR's default 6: a 640×480 visibility.exr is 4%
  // larger and its write much faster (docs/performance.md).
  spec.attribute("compression", "zip:1");
  write_atomic(path, "openexr", spec, img.data.data());
}

uint8_t png_byte(float v) {
  const float c = v > 0.0f ? std::min(v, 1.0f) : 0.0f;  // NaN -> 0
  // std::lround(c * 255), exactly (adding 0.5 to a float is exact in double,
  // and the value is not negative), but a plain conversion, not a libm call.
  // NOLINTNEXTLINE(bugprone-incorrect-roundings): exact here, as said above
  return static_cast<uint8_t>(static_cast<double>(c * 255.0f) + 0.5);
}

namespace {

// zlib level and PNG row filter: fast for the images (write_png), small for
// the masks (write_mask_png).
enum class PngPacking { Fast, Small };

void write_png_packed(const std::string& path, const ImageF& img, PngPacking packing) {
  OIIO::ImageSpec spec = make_spec(path, img, OIIO::TypeDesc::UINT8);
  // Otherwise OIIO treats the pixels as premultiplied and divides by alpha.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (packing == PngPacking::Fast) {
    // zlib level 1, not libpng's default 6: a shaded.png is 24% larger, the
    // write much faster (docs/performance.md). And no row filter, not libpng's
    // choice among all five per row: half the time again, and smaller files
    // on these images (a 640×480 job's shaded.png 162 → 167 KB, its error.png
    // 95 → 52 KB).
    spec.attribute("png:compressionLevel", 1);
    spec.attribute("png:filter", 0x08);  // PNG_FILTER_NONE
  } else {
    // A mask is a few runs per row: level 9 with libpng's filters halves a
    // 640×480 penumbra mask (11.8 → 6.4 KB) at no cost worth measuring.
    spec.attribute("png:compressionLevel", 9);
  }
  std::vector<uint8_t> bytes(img.data.size());
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = png_byte(img.data[i]);
  write_atomic(path, "png", spec, bytes.data());
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
  OIIO::ImageSpec config;
  // Return stored values: no premultiplication of unassociated-alpha formats.
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) {
    throw JobError(path + ": cannot open image: " + OIIO::geterror());
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.depth > 1 || spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw JobError(path + ": unsupported image layout (" + std::to_string(spec.width) + "x" +
                   std::to_string(spec.height) + "x" + std::to_string(spec.depth) + ", " +
                   std::to_string(spec.nchannels) + " channels)");
  }
  ImageF img(spec.width, spec.height, spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.data.data())) {
    throw JobError(path + ": cannot read image: " + in->geterror());
  }
  in->close();
  return img;
}

}  // namespace sb::metrics::io

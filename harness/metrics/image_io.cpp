#include "metrics/image_io.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <system_error>
#include <vector>

#include "core/error.h"

namespace sb::io {

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

// Unique per process and call, so concurrent writers of one path never share
// a temporary file.
std::string temp_path(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void write_atomic(const std::string& path, const char* format, const OIIO::ImageSpec& spec,
                  const void* pixels) {
  const std::string tmp = temp_path(path);
  // Create by format name: the temporary name has no usable extension.
  auto out = OIIO::ImageOutput::create(format);
  if (!out) {
    throw JobError(path + ": no " + format + " writer: " + OIIO::geterror());
  }
  bool ok = out->open(tmp, spec) && out->write_image(spec.format, pixels);
  std::string err = ok ? std::string() : out->geterror();
  if (!out->close() && ok) {
    ok = false;
    err = out->geterror();
  }
  std::error_code ec;
  if (!ok) {
    std::filesystem::remove(tmp, ec);
    throw JobError(path + ": writing " + format + " failed: " + err);
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw JobError(path + ": cannot rename " + tmp + " into place: " + ec.message());
  }
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

void write_png(const std::string& path, const ImageF& img) {
  OIIO::ImageSpec spec = make_spec(path, img, OIIO::TypeDesc::UINT8);
  // Otherwise OIIO treats the pixels as premultiplied and divides by alpha.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  // zlib level 1, not libpng's default 6: a shaded.png is 24% larger, the
  // write much faster (docs/performance.md). And no row filter, not libpng's
  // choice among all five per row: half the time again, and smaller files
  // on these images (a 640×480 job's shaded.png 162 → 167 KB, its error.png
  // 95 → 52 KB).
  spec.attribute("png:compressionLevel", 1);
  spec.attribute("png:filter", 0x08);  // PNG_FILTER_NONE
  std::vector<uint8_t> bytes(img.data.size());
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = png_byte(img.data[i]);
  write_atomic(path, "png", spec, bytes.data());
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

}  // namespace sb::io

// core::ImageCodec done by OpenImageIO: the one file that calls it, built as
// the module libshadowbench_image_codec.so, which core/image_codec.cpp loads
// on first use (a process that handles no image does not load OIIO).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "core/image_codec.h"

namespace sb::image_codec {

using core::HeaderCheck;
using core::Image8;
using core::ImageF;
using core::PngPacking;

namespace {

std::vector<std::string> channel_names(int channels) {
  switch (channels) {
    case 1:
      return {"Y"};
    case 2:
      return {"Y", "A"};
    case 3:
      return {"R", "G", "B"};
    default:
      return {"R", "G", "B", "A"};
  }
}

OIIO::ImageSpec make_spec(int width, int height, int channels, const OIIO::TypeDesc& type) {
  OIIO::ImageSpec spec(width, height, channels, type);
  spec.channelnames = channel_names(channels);
  spec.alpha_channel = (channels == 2 || channels == 4) ? channels - 1 : -1;
  return spec;
}

// Writes `bytes` to `path` (the caller's temporary file, which it made):
// "" or the reason, in strerror's words. OIIO's own file writers do not
// report a failed write: a PNG cut short by a full disk came back as written.
std::string write_bytes(const std::string& path, const std::vector<unsigned char>& bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return std::strerror(errno);
  const unsigned char* p = bytes.data();
  size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      return std::strerror(err);
    }
    p += n;
    left -= size_t(n);
  }
  if (::close(fd) != 0 && errno != EINTR) return std::strerror(errno);
  return "";
}

// Encodes by format name (the caller's temporary file name has no usable
// extension) into memory, then writes the bytes, so that a failed write
// says why.
std::string write_file(const std::string& path, const char* format, const OIIO::ImageSpec& spec,
                       const void* pixels) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto out = OIIO::ImageOutput::create(format, &proxy);
  if (!out) return std::string("no ") + format + " writer: " + OIIO::geterror();
  if (!out->supports("ioproxy")) return std::string(format) + " writer cannot write to memory";
  bool ok = out->open(path, spec) && out->write_image(spec.format, pixels);
  std::string err = ok ? std::string() : out->geterror();
  if (!out->close() && ok) {
    ok = false;
    err = out->geterror();
  }
  if (ok) err = write_bytes(path, bytes);
  return err.empty() ? std::string() : std::string("writing ") + format + " failed: " + err;
}

class OiioImageCodec final : public core::ImageCodec {
 public:
  std::string write_exr(const std::string& path, const ImageF& img) const override {
    OIIO::ImageSpec spec = make_spec(img.width, img.height, img.channels, OIIO::TypeDesc::FLOAT);
    // OIIO stamps the current time unless told otherwise; a fixed stamp keeps
    // identical runs byte-identical (the record says when the job ran).
    spec.attribute("DateTime", "1970:01:01 00:00:00");
    // zlib level 1, not OpenEXR's default 6: a 640×480 visibility.exr is 4%
    // larger and its write much faster (docs/performance.md).
    spec.attribute("compression", "zip:1");
    return write_file(path, "openexr", spec, img.data.data());
  }

  std::string write_png(const std::string& path, const Image8& img,
                        PngPacking packing) const override {
    OIIO::ImageSpec spec = make_spec(img.width, img.height, img.channels, OIIO::TypeDesc::UINT8);
    // Otherwise OIIO treats the pixels as premultiplied and divides by alpha.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (packing == PngPacking::Fast) {
      // zlib level 1, not libpng's default 6: a shaded.png is 24% larger, the
      // write much faster (docs/performance.md). And no row filter, not
      // libpng's choice among all five per row: half the time again, and
      // smaller files on these images (a 640×480 job's shaded.png 162 → 167
      // KB, its error.png 95 → 52 KB).
      spec.attribute("png:compressionLevel", 1);
      spec.attribute("png:filter", 0x08);  // PNG_FILTER_NONE
    } else {
      // A mask is a few runs per row: level 9 with libpng's filters halves a
      // 640×480 penumbra mask (11.8 → 6.4 KB) at no cost worth measuring.
      spec.attribute("png:compressionLevel", 9);
    }
    return write_file(path, "png", spec, img.data.data());
  }

  std::string read_image(const std::string& path, ImageF& img) const override {
    OIIO::ImageSpec config;
    // Return stored values: no premultiplication of unassociated-alpha formats.
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) return "cannot open image: " + OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.depth > 1 || spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
      return "unsupported image layout (" + std::to_string(spec.width) + "x" +
             std::to_string(spec.height) + "x" + std::to_string(spec.depth) + ", " +
             std::to_string(spec.nchannels) + " channels)";
    }
    img = ImageF(spec.width, spec.height, spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.data.data()))
      return "cannot read image: " + in->geterror();
    in->close();
    return "";
  }

  std::string decode(const std::vector<uint8_t>& bytes, const std::string& format,
                     const HeaderCheck& check, Image8& img) const override {
    OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // glTF alpha is straight: keep rgb as stored
    // With a config, readers take the proxy from it (OIIO 2.4), not from open()'s argument.
    OIIO::Filesystem::IOProxy* proxy = &memory;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto in = OIIO::ImageInput::open("image." + format, &config, &memory);
    if (!in) return OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    check(spec.width, spec.height, spec.depth, spec.nchannels);
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.nchannels;
    img.data.assign(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels), 0);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, img.data.data()))
      return in->geterror();
    return "";
  }

  std::string encode_png(const Image8& img, std::vector<uint8_t>& bytes) const override {
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    auto o = OIIO::ImageOutput::create("png", &proxy);
    if (!o) return "cannot create a PNG writer: " + OIIO::geterror();
    OIIO::ImageSpec spec(img.width, img.height, img.channels, OIIO::TypeDesc::UINT8);
    // The bytes are straight (unassociated) alpha already: write them as they are.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (!o->open("texture.png", spec) || !o->write_image(OIIO::TypeDesc::UINT8, img.data.data()) ||
        !o->close())
      return o->geterror();
    return "";
  }
};

}  // namespace

}  // namespace sb::image_codec

// The module's one entry point (core::kImageCodecEntry).
extern "C" __attribute__((visibility("default"))) const sb::core::ImageCodec*
shadowbench_image_codec_v1() {
  static const sb::image_codec::OiioImageCodec codec;
  return &codec;
}

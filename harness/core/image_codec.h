#pragma once
// Image encoding and decoding, done by OpenImageIO in a module of its own
// (libshadowbench_image_codec.so, harness/image_codec/) that the first call
// of image_codec() loads: a process that reads or writes no image never
// loads OpenImageIO and its ~260 libraries. The interface speaks our types;
// every call returns "" on success, else what went wrong in OpenImageIO's
// words, and the caller says which file or image it was.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/image.h"

namespace sb::core {

// 8-bit pixels, row-major, channels interleaved (1 grey, 2 grey+alpha,
// 3 RGB, 4 RGBA), alpha straight (not premultiplied).
struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<uint8_t> data;
};

// zlib level and PNG row filter: fast to write, or small.
enum class PngPacking { Fast, Small };

// A decoder's look at an image's header before a pixel is decoded: throws
// to refuse it (too large, too many channels).
using HeaderCheck = std::function<void(int width, int height, int depth, int channels)>;

class ImageCodec {
 public:
  // Float32 OpenEXR at `path`; channels named Y, Y A, R G B or R G B A; a
  // fixed DateTime and zip level 1 compression.
  virtual std::string write_exr(const std::string& path, const ImageF& img) const = 0;
  // PNG at `path`, the bytes stored as given.
  virtual std::string write_png(const std::string& path, const Image8& img,
                                PngPacking packing) const = 0;
  // The first subimage of any file OpenImageIO reads, as float (8-bit
  // values become v/255), alpha as stored.
  virtual std::string read_image(const std::string& path, ImageF& img) const = 0;
  // A PNG or JPEG (`format` "png" or "jpg") in memory, as 8-bit values with
  // the file's channels; `check` sees the header first.
  virtual std::string decode(const std::vector<uint8_t>& bytes, const std::string& format,
                             const HeaderCheck& check, Image8& img) const = 0;
  // RGBA8 as a PNG in memory.
  virtual std::string encode_png(const Image8& img, std::vector<uint8_t>& bytes) const = 0;

 protected:
  ImageCodec() = default;
  ImageCodec(const ImageCodec&) = default;
  ImageCodec& operator=(const ImageCodec&) = default;
  ~ImageCodec() = default;
};

// The codec, its module loaded on the first call (once, from any thread)
// from the folder of libshadowbench_core.so: <build>/harness in a build tree,
// <prefix>/lib/shadowbench installed. Throws std::runtime_error naming the
// module's path and dlerror()'s words when it cannot be loaded.
const ImageCodec& image_codec();

// The module's path, as image_codec() loads it.
std::string image_codec_path();

// The name of the function the module exports: it returns its ImageCodec.
// The version changes with ImageCodec's methods.
inline constexpr const char* kImageCodecEntry = "shadowbench_image_codec_v1";

}  // namespace sb::core

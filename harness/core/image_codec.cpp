#include "core/image_codec.h"

#include <dlfcn.h>

#include <filesystem>

#include "core/lazy_library.h"

namespace sb::core {

std::string image_codec_path() {
  // This library's own file: the module is installed and built beside it.
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&image_codec_path), &info) == 0 ||
      info.dli_fname == nullptr)
    return "libshadowbench_image_codec.so";
  return (std::filesystem::path(info.dli_fname).parent_path() / "libshadowbench_image_codec.so")
      .string();
}

const ImageCodec& image_codec() {
  static LazyLibrary module(image_codec_path(), "the image codec module");
  // A magic static: one thread loads it, the others wait; a failure throws
  // again at the next call.
  static const ImageCodec& codec = *module.function<const ImageCodec* (*)()>(kImageCodecEntry)();
  return codec;
}

}  // namespace sb::core

#pragma once
// Decoding glTF images into RGBA8 textures, within caps. Only PNG and JPEG
// (by their signatures, whatever the mimeType says); at most
// kGltfMaxTextureSide texels per side; and all the images of one file
// together at most kGltfMaxDecodedTexels, checked on the header before a
// pixel is decoded (a small file can unpack to gigabytes). A PNG's chunks
// and CRCs are checked before OpenImageIO (core/image_codec.h) sees it:
// libpng reports damage by longjmp through OpenImageIO, which leaks.
#include "core/scene.h"
#include "scenes/gltf_common.h"

namespace sb::gltf {

class ImageDecoder : public ImportStep {
 public:
  explicit ImageDecoder(const std::string& file) : ImportStep(file) {}
  // Image `index` of the model, as straight (unassociated) RGBA8.
  core::TextureImage decode(const tg::Image& img, size_t index);

 private:
  size_t decoded_texels_ = 0;  // of every image decoded so far
};

}  // namespace sb::gltf

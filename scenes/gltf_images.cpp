#include "scenes/gltf_images.h"

#include <array>
#include <cstring>

#include "core/image_codec.h"
#include "scenes/gltf_import.h"

namespace sb::gltf {

using core::TextureImage;

namespace {

uint32_t be32(const unsigned char* p) {
  return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

uint32_t crc32(const unsigned char* p, size_t n) {
  static const auto table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  uint32_t c = 0xFFFFFFFFu;
  for (size_t i = 0; i < n; ++i) c = table[(c ^ p[i]) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

// "" when the PNG's chunks are complete and their CRCs match, else what is
// wrong. libpng reports such damage by longjmp through OpenImageIO, which
// leaks; checking first also gives a clearer message.
std::string png_damage(const std::vector<unsigned char>& b) {
  size_t at = 8;
  bool first = true;
  while (true) {
    if (b.size() - at < 12) return "truncated (no IEND chunk)";
    const uint32_t length = be32(&b[at]);
    if (length > b.size() - at - 12) return "truncated (chunk at byte " + str(at) + ")";
    const std::string type(reinterpret_cast<const char*>(&b[at + 4]), 4);
    if (crc32(&b[at + 4], 4 + size_t(length)) != be32(&b[at + 8 + length]))
      return "chunk " + quoted(type) + " at byte " + str(at) + " has a bad CRC (corrupt file)";
    if (first && (type != "IHDR" || length != 13)) return "does not start with an IHDR chunk";
    if (first) {
      const uint32_t w = be32(&b[at + 8]), h = be32(&b[at + 12]);
      if (w < 1 || h < 1 || w > uint32_t(kGltfMaxTextureSide) || h > uint32_t(kGltfMaxTextureSide))
        return "size " + str(w) + "x" + str(h) + " is outside [1, " +
               str(size_t(kGltfMaxTextureSide)) + "] per side";
    }
    if (type == "IEND") return "";
    first = false;
    at += 12 + size_t(length);
  }
}
}  // namespace

TextureImage ImageDecoder::decode(const tg::Image& img, size_t index) {
  const std::string where = named("image", img.name, index);
  const std::vector<unsigned char>& bytes = img.image;
  if (bytes.empty()) fail(img.uri.empty() ? where : where + " uri", "no image data could be read");
  static const unsigned char png[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  std::string ext;
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), png, 8) == 0)
    ext = "png";
  else if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF)
    ext = "jpg";
  else
    fail(where, "is neither a PNG nor a JPEG image (mimeType " + quoted(img.mimeType) + ")");
  if (ext == "png")
    if (const std::string damage = png_damage(bytes); !damage.empty()) fail(where, "PNG " + damage);
  // Throws std::runtime_error, not bad input, when the codec module is missing.
  const core::ImageCodec& codec = core::image_codec();
  // Checked on the header, before decoding: small files can unpack to gigabytes.
  const auto check = [&](int width, int height, int depth, int channels) {
    if (width < 1 || height < 1 || width > kGltfMaxTextureSide || height > kGltfMaxTextureSide ||
        depth != 1)
      fail(where, "size " + std::to_string(width) + "x" + std::to_string(height) +
                      " is outside [1, " + std::to_string(kGltfMaxTextureSide) + "] per side");
    if (channels < 1 || channels > 4)
      fail(where, std::to_string(channels) + " channels (expected 1 to 4)");
    decoded_texels_ += size_t(width) * size_t(height);
    if (decoded_texels_ > kGltfMaxDecodedTexels)
      fail(where, "decoding it would bring the scene's textures to " + str(decoded_texels_) +
                      " texels, over the limit of " + str(kGltfMaxDecodedTexels));
  };
  core::Image8 raw;
  if (const std::string err = codec.decode(bytes, ext, check, raw); !err.empty())
    fail(where, "cannot decode the " + ext + " image: " + first_line(err));
  const int channels = raw.channels;
  const size_t texels = size_t(raw.width) * size_t(raw.height);
  TextureImage t;
  t.name = img.name.empty() ? "image" + str(index) : img.name;
  t.width = raw.width;
  t.height = raw.height;
  t.rgba.resize(texels * 4);
  for (size_t i = 0; i < texels; ++i) {
    const uint8_t* s = &raw.data[i * size_t(channels)];
    uint8_t* d = &t.rgba[i * 4];
    const bool grey = channels <= 2;
    d[0] = s[0];
    d[1] = grey ? s[0] : s[1];
    d[2] = grey ? s[0] : s[2];
    d[3] = channels == 2 ? s[1] : channels == 4 ? s[3] : 255;
  }
  return t;
}

}  // namespace sb::gltf

#include "scenes/gltf_container.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "core/sha256.h"

namespace sb::gltf {

using core::InputError;

namespace {

namespace fs = std::filesystem;

// Keeps the encoded bytes; images are decoded later (and only if used) by
// OpenImageIO, which checks the size before it allocates.
bool keep_encoded_image(tg::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (size > 0) image->image.assign(bytes, bytes + size);
  image->width = image->height = image->component = image->bits = 0;
  return true;
}

std::vector<unsigned char> read_whole_file(const std::string& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) throw InputError(file, "", "file not found");
  if (!fs::is_regular_file(file, ec)) throw InputError(file, "", "not a regular file");
  const auto size = fs::file_size(file, ec);
  if (ec) throw InputError(file, "", "cannot read: " + ec.message());
  if (size > std::numeric_limits<uint32_t>::max())
    throw InputError(file, "", "larger than 4 GiB, the limit of glTF");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "", std::string("cannot open: ") + std::strerror(errno));
  std::vector<unsigned char> bytes(size);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (!in) throw InputError(file, "", "cannot read the whole file");
  if (bytes.empty()) throw InputError(file, "", "file is empty");
  return bytes;
}

uint32_t le32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

}  // namespace

GltfContainer::GltfContainer(const std::string& file)
    : ImportStep(file), bytes_(read_whole_file(file)) {
  glb_ = bytes_.size() >= 4 && std::memcmp(bytes_.data(), "glTF", 4) == 0;
  json_begin_ = bytes_.data();
  json_size_ = bytes_.size();
}

void GltfContainer::check_chunks() {
  if (!glb_) return;
  const std::vector<unsigned char>& b = bytes_;
  const size_t n = b.size();
  if (n < 12)
    fail("GLB header", "file is truncated: " + str(n) + " bytes, the header alone needs 12");
  const uint32_t version = le32(&b[4]);
  if (version != 2) fail("GLB header", "version " + str(version) + " is not supported (only 2)");
  const uint32_t length = le32(&b[8]);
  if (length > n)
    fail("GLB header",
         "file is truncated: the header says " + str(length) + " bytes, the file has " + str(n));
  if (length < n)
    fail("GLB header", "the header says " + str(length) + " bytes but the file has " + str(n));
  if (n - 12 < 8) fail("GLB JSON chunk", "missing (the file is truncated)");
  const uint32_t json_length = le32(&b[12]);
  if (le32(&b[16]) != 0x4E4F534Au) fail("GLB JSON chunk", "the first chunk is not JSON");
  if (json_length == 0) fail("GLB JSON chunk", "empty");
  if (json_length > n - 20)
    fail("GLB JSON chunk",
         "its length " + str(json_length) + " runs past the end of the file (truncated?)");
  json_begin_ = &b[20];
  json_size_ = json_length;
  size_t offset = 20 + size_t(json_length);
  for (int chunk = 1; offset < n; ++chunk) {
    const std::string where = chunk == 1 ? "GLB BIN chunk" : "GLB chunk " + str(size_t(chunk));
    if (n - offset < 8) fail(where, "truncated chunk header at byte " + str(offset));
    const uint32_t length_i = le32(&b[offset]);
    const uint32_t type = le32(&b[offset + 4]);
    if (length_i > n - offset - 8)
      fail(where, "its length " + str(length_i) + " runs past the end of the file (truncated?)");
    if (type == 0x004E4942u && chunk != 1)
      fail(where, "a second BIN chunk (only one, right after the JSON chunk, is allowed)");
    offset += 8 + size_t(length_i);
  }
}

std::string GltfContainer::sha256() const {
  return core::sha256_hex(
      std::string_view(reinterpret_cast<const char*>(bytes_.data()), bytes_.size()));
}

tg::Model GltfContainer::parse(UriSandbox& sandbox) const {
  tg::Model model;
  tg::TinyGLTF loader;
  loader.SetFsCallbacks(sandbox.callbacks());
  loader.SetImageLoader(&keep_encoded_image, nullptr);
  std::string err, warn;
  bool ok = false;
  const std::string base = sandbox.dir().string();
  try {
    ok = glb_ ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes_.data(),
                                            static_cast<unsigned int>(bytes_.size()), base)
              : loader.LoadASCIIFromString(&model, &err, &warn,
                                           reinterpret_cast<const char*>(json_begin_),
                                           static_cast<unsigned int>(json_size_), base);
  } catch (const std::exception& e) {
    fail("", std::string("invalid glTF: ") + e.what());
  }
  if (!ok) fail("", "invalid glTF: " + first_line(err));
  return model;
}

}  // namespace sb::gltf

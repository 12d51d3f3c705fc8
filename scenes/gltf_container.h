#pragma once
// The container: a glTF file's bytes up to tinygltf's model. A .gltf file is
// JSON text; a .glb is a 12-byte header and chunks (JSON, then at most one
// BIN). The GLB's header and chunk headers are checked here before tinygltf
// reads them (tinygltf 2.7 trusts the BIN chunk's length a little), and
// tinygltf reads external files only through the URI sandbox. Images are
// kept encoded: gltf_images decodes the ones a material uses, within caps.
#include <string>
#include <vector>

#include "scenes/gltf_common.h"
#include "scenes/gltf_uri_sandbox.h"

namespace sb::gltf {

class GltfContainer : public ImportStep {
 public:
  // Reads the whole file (at most 4 GiB, the limit of glTF).
  explicit GltfContainer(const std::string& file);
  // Checks a .glb's header and chunks; then json_data() is its JSON chunk
  // (for a .gltf, the whole file).
  void check_chunks();
  const unsigned char* json_data() const { return json_begin_; }
  // SHA-256 of the file's bytes, as read.
  std::string sha256() const;
  size_t json_size() const { return json_size_; }
  // tinygltf's model of the file, external files read through `sandbox`.
  tg::Model parse(UriSandbox& sandbox) const;

 private:
  std::vector<unsigned char> bytes_;
  bool glb_ = false;
  const unsigned char* json_begin_ = nullptr;
  size_t json_size_ = 0;
};

}  // namespace sb::gltf

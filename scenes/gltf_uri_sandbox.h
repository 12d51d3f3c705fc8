#pragma once
// Which files a glTF file may make the importer read. Buffers and images are
// named by URI, and a hostile file could name an absolute path, climb out
// with '..', leave through a symbolic link, or (through tinygltf's own file
// access, which also tries the working directory and expands '~' and
// environment variables) reach anything. Only data: URIs and relative paths
// that resolve inside the glTF file's own folder are allowed. The rule is
// applied twice: to every URI in the JSON before tinygltf runs (check_uri,
// whose message names the place), and by the only file callbacks tinygltf
// is given (callbacks()).
#include <filesystem>
#include <string>
#include <vector>

#include "core/scene.h"
#include "scenes/gltf_common.h"

namespace sb::gltf {

class UriSandbox : public ImportStep {
 public:
  // Resolves the folder of `file`.
  explicit UriSandbox(const std::string& file);
  UriSandbox(const UriSandbox&) = delete;  // callbacks() points into it
  UriSandbox& operator=(const UriSandbox&) = delete;
  const std::filesystem::path& dir() const { return state_.dir; }
  // Throws unless `value` is a data: URI or names a regular file inside dir().
  void check_uri(const json& value, const std::string& where) const;
  // tinygltf's file access, confined to dir(); valid while this object lives.
  tg::FsCallbacks callbacks();
  // The files read through callbacks(), each once, in the order first read:
  // named by their path relative to dir(), with the SHA-256 of the bytes read.
  const std::vector<core::InputFile>& reads() const { return state_.reads; }

  struct State {
    std::filesystem::path dir;
    std::vector<core::InputFile> reads;
  };

 private:
  State state_;
};

}  // namespace sb::gltf

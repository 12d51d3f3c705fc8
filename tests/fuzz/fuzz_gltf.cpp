// libFuzzer target: a glTF file's bytes through the importer, as a scene
// entry `{"type": "gltf"}` reads it. The bytes are written to a folder of
// their own (as .glb when they start with the GLB magic, else .gltf), so the
// importer's real path runs, URI sandbox included: a URI can reach no file
// but the input itself.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_input.h"
#include "scenes/gltf_import.h"

namespace {

std::filesystem::path input_folder() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() /
             ("shadowbench_fuzz_gltf_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::filesystem::path file = input_folder() / (glb ? "input.glb" : "input.gltf");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  return sb::fuzz::expect_only_input_errors("fuzz_gltf",
                                            [&] { (void)sb::load_gltf(file.string()); });
}

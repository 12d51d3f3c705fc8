// libFuzzer target: a scene named on the command line (`shadowbench scene
// info SPEC`): "type:key=value,..." or a JSON object, parsed and the scene
// built, within the documented limits.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input.h"
#include "scenes/scene_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return sb::fuzz::expect_only_input_errors("fuzz_scene_spec", [&] {
    const std::string spec(reinterpret_cast<const char*>(data), size);
    (void)sb::describe_scene(sb::build_scene_from_spec(spec));
  });
}

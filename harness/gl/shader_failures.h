#pragma once
// The shaders that failed to compile since the harness last asked: a
// technique's prepare() compiles them, and its job fails with the
// compiler's log; the harness then writes each one's assembled source
// beside the job's images (shader-<program>-<stage>.glsl), the text the
// log's "0:" line numbers count.
#include <string>
#include <vector>

namespace sb::gl {

struct FailedShader {
  std::string program;  // Program's name, e.g. "pcss_lookup"
  std::string stage;    // "vertex", "fragment", ...
  std::string source;   // as compiled
};

// Program notes each failure (gl/program.cpp).
void note_failed_shader(FailedShader shader);
// The failures noted since the last call, cleared on return.
std::vector<FailedShader> take_failed_shaders();

}  // namespace sb::gl

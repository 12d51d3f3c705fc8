#include "gl/shader_failures.h"

#include <mutex>
#include <utility>

namespace sb::gl {

namespace {

// At most a few per job: a plugin that fails to compile in a loop must not
// fill memory before its job ends.
constexpr size_t kKept = 16;

std::mutex& failures_mutex() {
  static std::mutex m;
  return m;
}

std::vector<FailedShader>& failures() {
  static std::vector<FailedShader> list;
  return list;
}

}  // namespace

void note_failed_shader(FailedShader shader) {
  const std::lock_guard lock(failures_mutex());
  if (failures().size() < kKept) failures().push_back(std::move(shader));
}

std::vector<FailedShader> take_failed_shaders() {
  const std::lock_guard lock(failures_mutex());
  return std::exchange(failures(), {});
}

}  // namespace sb::gl

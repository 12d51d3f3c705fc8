#include "gl/debug.h"

#include <mutex>

#include "core/error.h"
#include "gl/gl.h"

namespace sb::gl {

using core::JobError;

namespace {

std::mutex g_mutex;
std::vector<std::string> g_errors;

void GLAPIENTRY on_debug_message(GLenum /*source*/, GLenum type, GLuint /*id*/, GLenum severity,
                                 GLsizei length, const GLchar* message, const void* /*user*/) {
  if (type != GL_DEBUG_TYPE_ERROR && severity != GL_DEBUG_SEVERITY_HIGH) return;
  std::lock_guard lock(g_mutex);
  if (g_errors.size() < 16)
    g_errors.emplace_back(message, length < 0 ? std::char_traits<char>::length(message)
                                              : static_cast<size_t>(length));
}

const char* error_name(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return "GL error";
  }
}

}  // namespace

void enable_debug_output() {
  if (glDebugMessageCallback == nullptr) return;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(on_debug_message, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

std::vector<std::string> take_debug_errors() {
  std::lock_guard lock(g_mutex);
  std::vector<std::string> out;
  out.swap(g_errors);
  return out;
}

void throw_if_errors(const std::string& where) {
  std::string message;
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError())
    message += std::string(message.empty() ? "" : "; ") + error_name(e);
  for (const auto& m : take_debug_errors()) message += std::string(message.empty() ? "" : "; ") + m;
  if (!message.empty()) throw JobError(where + ": " + message);
}

}  // namespace sb::gl

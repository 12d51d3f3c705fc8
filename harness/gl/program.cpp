#include "gl/program.h"

#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/glsl_pieces.h"
#include "gl/shader_failures.h"

namespace sb::gl {

using core::JobError;

namespace {

GLuint compile(const std::string& program, GLenum stage, const std::string& source) {
  GLuint s = glCreateShader(stage);
  const char* src = source.c_str();
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
    std::vector<char> log(static_cast<size_t>(len) + 1, '\0');
    glGetShaderInfoLog(s, len, nullptr, log.data());
    glDeleteShader(s);
    const char* kind = stage == GL_VERTEX_SHADER            ? "vertex"
                       : stage == GL_GEOMETRY_SHADER        ? "geometry"
                       : stage == GL_TESS_CONTROL_SHADER    ? "tessellation control"
                       : stage == GL_TESS_EVALUATION_SHADER ? "tessellation evaluation"
                       : stage == GL_COMPUTE_SHADER         ? "compute"
                                                            : "fragment";
    // The driver may also have queued the error as a debug message: it is in
    // this exception, and must not fail the next unrelated throw_if_errors.
    (void)gl::take_debug_errors();
    note_failed_shader({program, kind, source});
    std::string message = "shader '" + program + "' (" + kind + ") failed to compile: ";
    message += glsl_log_in_pieces(log.data());
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    // Which numbers the log's "N:line(column)" count in.
    if (const auto strings = glsl_source_strings(source); !strings.empty()) {
      message += " (source strings: 0 is the assembled shader";
      for (const std::string& piece : strings) message += ", " + piece + " as written";
      message += ")";
    }
    throw JobError(message);
  }
  return s;
}

}  // namespace

namespace {

std::vector<std::pair<GLenum, std::string>> graphics_stages(
    const ShaderSources& s, const std::string& tess_control = "",
    const std::string& tess_evaluation = "") {
  std::vector<std::pair<GLenum, std::string>> stages = {{GL_VERTEX_SHADER, s.vertex}};
  if (!tess_control.empty()) stages.emplace_back(GL_TESS_CONTROL_SHADER, tess_control);
  if (!tess_evaluation.empty()) stages.emplace_back(GL_TESS_EVALUATION_SHADER, tess_evaluation);
  if (!s.geometry.empty()) stages.emplace_back(GL_GEOMETRY_SHADER, s.geometry);
  if (!s.fragment.empty()) stages.emplace_back(GL_FRAGMENT_SHADER, s.fragment);
  return stages;
}

}  // namespace

Program::Program(std::string name, const ShaderSources& sources)
    : Program(std::move(name), graphics_stages(sources)) {}

Program Program::tessellated(std::string name, const ShaderSources& sources,
                             const std::string& tess_control, const std::string& tess_evaluation) {
  if (tess_control.empty() || tess_evaluation.empty())
    throw std::logic_error("program '" + name + "': tessellation needs both of its stages");
  return Program(std::move(name), graphics_stages(sources, tess_control, tess_evaluation));
}

Program Program::compute(std::string name, const std::string& source) {
  return Program(std::move(name), {{GL_COMPUTE_SHADER, source}});
}

Program::Program(std::string name, const std::vector<std::pair<GLenum, std::string>>& stages)
    : name_(std::move(name)) {
  std::vector<GLuint> shaders;
  shaders.reserve(stages.size());
  for (const auto& [stage, source] : stages) shaders.push_back(compile(name_, stage, source));
  id_ = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(id_, s);
  glLinkProgram(id_);
  for (GLuint s : shaders) {
    glDetachShader(id_, s);
    glDeleteShader(s);
  }
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &len);
    std::vector<char> log(static_cast<size_t>(len) + 1, '\0');
    glGetProgramInfoLog(id_, len, nullptr, log.data());
    glDeleteProgram(id_);
    id_ = 0;
    (void)gl::take_debug_errors();  // as for a compile error
    throw JobError("program '" + name_ + "' failed to link: " + log.data());
  }
}

Program::~Program() {
  if (id_ != 0) glDeleteProgram(id_);
}

Program::Program(Program&& o) noexcept
    : name_(std::move(o.name_)),
      id_(std::exchange(o.id_, 0)),
      locations_(std::move(o.locations_)) {}

Program& Program::operator=(Program&& o) noexcept {
  if (this != &o) {
    if (id_ != 0) glDeleteProgram(id_);
    name_ = std::move(o.name_);
    id_ = std::exchange(o.id_, 0);
    locations_ = std::move(o.locations_);
  }
  return *this;
}

// Looked up once per name, absent ones too (-1): lookups run in timed passes.
GLint Program::cached_location(const std::string& uniform) const {
  auto it = locations_.find(uniform);
  if (it != locations_.end()) return it->second;
  const GLint loc = glGetUniformLocation(id_, uniform.c_str());
  locations_.emplace(uniform, loc);
  return loc;
}

GLint Program::location(const std::string& uniform) const {
  const GLint loc = cached_location(uniform);
  if (loc < 0) throw JobError("program '" + name_ + "' has no active uniform '" + uniform + "'");
  return loc;
}

void Program::set(const std::string& u, const std::vector<float>& values) const {
  glProgramUniform1fv(id_, location(u), static_cast<GLsizei>(values.size()), values.data());
}

void Program::set(const std::string& u, const std::vector<glm::vec2>& values) const {
  glProgramUniform2fv(id_, location(u), static_cast<GLsizei>(values.size()),
                      glm::value_ptr(values.front()));
}

bool Program::has_uniform(const std::string& uniform) const {
  return cached_location(uniform) >= 0;
}

void Program::set(const std::string& u, const glm::vec2& v) const {
  glProgramUniform2fv(id_, location(u), 1, glm::value_ptr(v));
}
void Program::set(const std::string& u, const glm::vec3& v) const {
  glProgramUniform3fv(id_, location(u), 1, glm::value_ptr(v));
}
void Program::set(const std::string& u, const glm::vec4& v) const {
  glProgramUniform4fv(id_, location(u), 1, glm::value_ptr(v));
}
void Program::set(const std::string& u, const glm::mat4& m) const {
  glProgramUniformMatrix4fv(id_, location(u), 1, GL_FALSE, glm::value_ptr(m));
}

}  // namespace sb::gl

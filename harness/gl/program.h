#pragma once
// A linked GLSL program built from sources; compile and link logs become
// JobErrors that name the program.
#include <glm/glm.hpp>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "gl/gl.h"

namespace sb::gl {

struct ShaderSources {
  std::string vertex;
  std::string geometry;  // optional
  std::string fragment;  // optional (depth-only passes)
};

class Program {
 public:
  Program() = default;
  Program(std::string name, const ShaderSources& sources);
  // A graphics program with tessellation between vertex and geometry.
  static Program tessellated(std::string name, const ShaderSources& sources,
                             const std::string& tess_control, const std::string& tess_evaluation);
  // A compute program (run it with glDispatchCompute after use()).
  static Program compute(std::string name, const std::string& source);
  ~Program();
  Program(Program&& o) noexcept;
  Program& operator=(Program&& o) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  GLuint id() const { return id_; }
  void use() const { glUseProgram(id_); }
  GLint location(const std::string& uniform) const;
  // False for uniforms the compiler removed (unused by this variant's shader).
  bool has_uniform(const std::string& uniform) const;

  void set(const std::string& u, int v) const { glProgramUniform1i(id_, location(u), v); }
  void set(const std::string& u, float v) const { glProgramUniform1f(id_, location(u), v); }
  void set(const std::string& u, const glm::ivec2& v) const {
    glProgramUniform2i(id_, location(u), v.x, v.y);
  }
  void set(const std::string& u, const glm::vec2& v) const;
  void set(const std::string& u, const glm::vec3& v) const;
  void set(const std::string& u, const glm::vec4& v) const;
  void set(const std::string& u, const glm::mat4& m) const;
  // A `float u[N]` uniform array from its first element on.
  void set(const std::string& u, const std::vector<float>& values) const;
  void set(const std::string& u, const std::vector<glm::vec2>& values) const;
  // set() when the uniform is active, nothing when the compiler removed it:
  // for programs assembled from shared pieces that not every variant reads.
  template <class T>
  void set_if_active(const std::string& u, const T& value) const {
    if (has_uniform(u)) set(u, value);
  }

 private:
  Program(std::string name, const std::vector<std::pair<GLenum, std::string>>& stages);
  GLint cached_location(const std::string& uniform) const;
  std::string name_;
  GLuint id_ = 0;
  mutable std::unordered_map<std::string, GLint> locations_;
};

}  // namespace sb::gl

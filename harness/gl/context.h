#pragma once
// One headless GL 4.5 core context. Two backends: OSMesa (default) and EGL
// (device platform where a GPU exists, surfaceless otherwise). Every GL entry
// point is loaded through glad from the backend's GetProcAddress; nothing is
// linked against libGL/libOpenGL: with libglvnd loaded, calling gl* by
// symbol makes every OSMesa call a silent no-op (docs/design.md, "GL").
#include <cstddef>
#include <memory>
#include <string>

namespace sb::gl {

enum class Backend { OSMesa, EGL };

std::string to_string(Backend b);
Backend backend_from_string(const std::string& name);  // throws InputError

class Context {
 public:
  virtual ~Context() = default;
  virtual Backend backend() const = 0;
  virtual void make_current() = 0;
  // "osmesa", "egl-device", "egl-surfaceless"
  virtual std::string platform() const = 0;

  std::string renderer() const;
  std::string version() const;
  // llvmpipe/softpipe: GL_TIME_ELAPSED is wrong there (each rasterizer
  // thread overwrites the query's timestamps, so it reads about one tile's
  // time), so passes are timed with glFinish-bracketed CPU clocks.
  bool is_software() const;

 protected:
  // Loads GL through glad with the backend's loader and turns on KHR_debug.
  void load_gl(void* (*get_proc)(const char*));
};

// How many contexts this process asked for: the plan stage's tests check
// that planning creates none.
std::size_t contexts_created();
// Throws std::runtime_error with the backend's reason if it cannot be created.
std::unique_ptr<Context> create_context(Backend backend);

// True when the backend was compiled in.
bool backend_available(Backend backend);

// Opens the backend's library (libOSMesa, libEGL) without making a context,
// so that forked children which make one inherit it instead of each opening
// it. False when it cannot be opened; create_context() then says why.
bool load_backend_library(Backend backend);

}  // namespace sb::gl

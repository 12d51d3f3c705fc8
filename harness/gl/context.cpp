#include "gl/context.h"

#include <stdexcept>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/gl.h"
#include "gl/objects.h"

namespace sb::gl {

using core::InputError;

std::string to_string(Backend b) { return b == Backend::OSMesa ? "osmesa" : "egl"; }

Backend backend_from_string(const std::string& name) {
  if (name == "osmesa") return Backend::OSMesa;
  if (name == "egl") return Backend::EGL;
  throw InputError("", "--backend", "expected \"osmesa\" or \"egl\", found \"" + name + "\"");
}

namespace {
void* g_get_proc_fn = nullptr;
GLADapiproc load_with(const char* name) {
  auto fn = reinterpret_cast<void* (*)(const char*)>(g_get_proc_fn);
  return reinterpret_cast<GLADapiproc>(fn(name));
}
}  // namespace

void Context::load_gl(void* (*get_proc)(const char*)) {
  g_get_proc_fn = reinterpret_cast<void*>(get_proc);
  const int version = gladLoadGL(load_with);
  if (version == 0) throw std::runtime_error("glad could not load GL entry points");
  if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 45)
    throw std::runtime_error("GL 4.5 core is required, the context offers " +
                             std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                             std::to_string(GLAD_VERSION_MINOR(version)));
  enable_debug_output();
  forget_context_objects();
}

std::string Context::renderer() const {
  const auto* s = glGetString(GL_RENDERER);
  return s ? reinterpret_cast<const char*>(s) : "";
}

std::string Context::version() const {
  const auto* s = glGetString(GL_VERSION);
  return s ? reinterpret_cast<const char*>(s) : "";
}

bool Context::is_software() const {
  const std::string r = renderer();
  return r.find("llvmpipe") != std::string::npos || r.find("softpipe") != std::string::npos ||
         r.find("Software") != std::string::npos;
}

std::unique_ptr<Context> create_osmesa_context();
std::unique_ptr<Context> create_egl_context();
void load_osmesa_library();
void load_egl_library();

bool backend_available(Backend backend) {
#if defined(SHADOWBENCH_HAVE_OSMESA)
  if (backend == Backend::OSMesa) return true;
#endif
#if defined(SHADOWBENCH_HAVE_EGL)
  if (backend == Backend::EGL) return true;
#endif
  (void)backend;
  return false;
}

bool load_backend_library(Backend backend) {
  try {
#if defined(SHADOWBENCH_HAVE_OSMESA)
    if (backend == Backend::OSMesa) load_osmesa_library();
#endif
#if defined(SHADOWBENCH_HAVE_EGL)
    if (backend == Backend::EGL) load_egl_library();
#endif
    return backend_available(backend);
  } catch (const std::runtime_error&) {
    return false;
  }
}

namespace {
std::size_t g_contexts_created = 0;
}  // namespace

std::size_t contexts_created() { return g_contexts_created; }

std::unique_ptr<Context> create_context(Backend backend) {
  ++g_contexts_created;
  if (!backend_available(backend))
    throw std::runtime_error("backend '" + to_string(backend) + "' was not compiled in");
#if defined(SHADOWBENCH_HAVE_OSMESA)
  if (backend == Backend::OSMesa) return create_osmesa_context();
#endif
#if defined(SHADOWBENCH_HAVE_EGL)
  if (backend == Backend::EGL) return create_egl_context();
#endif
  return nullptr;
}

}  // namespace sb::gl

// EGL backend: the device platform when a real GPU device exists, the Mesa
// surfaceless platform otherwise. Kept apart from the GL headers. libEGL is
// opened when the first context is created, not linked, like libOSMesa
// (context_osmesa.cpp): nine entry points, taken with dlsym.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/lazy_library.h"
#include "gl/context.h"

namespace sb::gl {
namespace {

struct EglApi {
  decltype(&eglGetError) get_error;
  decltype(&eglGetProcAddress) get_proc_address;
  decltype(&eglQueryString) query_string;
  decltype(&eglInitialize) initialize;
  decltype(&eglBindAPI) bind_api;
  decltype(&eglCreateContext) create_context;
  decltype(&eglMakeCurrent) make_current;
  decltype(&eglDestroyContext) destroy_context;
  decltype(&eglTerminate) terminate;
};

const EglApi& egl() {
  static const EglApi api = [] {
    // libglvnd's dispatcher (Debian's libegl1), which finds Mesa's driver.
    static core::LazyLibrary lib("libEGL.so.1", "the EGL backend's library");
    return EglApi{lib.function<decltype(&eglGetError)>("eglGetError"),
                  lib.function<decltype(&eglGetProcAddress)>("eglGetProcAddress"),
                  lib.function<decltype(&eglQueryString)>("eglQueryString"),
                  lib.function<decltype(&eglInitialize)>("eglInitialize"),
                  lib.function<decltype(&eglBindAPI)>("eglBindAPI"),
                  lib.function<decltype(&eglCreateContext)>("eglCreateContext"),
                  lib.function<decltype(&eglMakeCurrent)>("eglMakeCurrent"),
                  lib.function<decltype(&eglDestroyContext)>("eglDestroyContext"),
                  lib.function<decltype(&eglTerminate)>("eglTerminate")};
  }();
  return api;
}

std::string egl_error(const char* what) {
  return std::string(what) + " failed (EGL error 0x" + [] {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%04x", egl().get_error());
    return std::string(buf);
  }() + ")";
}

template <typename F>
F load_egl(const char* name) {
  auto p = reinterpret_cast<F>(egl().get_proc_address(name));
  if (p == nullptr) throw std::runtime_error(std::string("EGL entry point missing: ") + name);
  return p;
}

// Picks a hardware device (one with a DRM render node) if any; nullptr if none.
EGLDeviceEXT find_gpu_device() {
  const char* client_ext = egl().query_string(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (client_ext == nullptr || std::strstr(client_ext, "EGL_EXT_device_enumeration") == nullptr)
    return nullptr;
  auto query_devices = load_egl<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto query_string = load_egl<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  EGLint count = 0;
  if (!query_devices(0, nullptr, &count) || count <= 0) return nullptr;
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
  query_devices(count, devices.data(), &count);
  for (EGLDeviceEXT d : devices) {
    const char* ext = query_string(d, EGL_EXTENSIONS);
    if (ext == nullptr) continue;
    // Mesa's software device has no DRM file; a GPU has one.
    if (std::strstr(ext, "EGL_EXT_device_drm") != nullptr &&
        std::strstr(ext, "EGL_MESA_device_software") == nullptr)
      return d;
  }
  return nullptr;
}

class EGLContextImpl final : public Context {
 public:
  EGLContextImpl() {
    auto get_platform_display =
        load_egl<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    if (EGLDeviceEXT gpu = find_gpu_device(); gpu != nullptr) {
      display_ = get_platform_display(EGL_PLATFORM_DEVICE_EXT, gpu, nullptr);
      platform_ = "egl-device";
    }
    if (display_ == EGL_NO_DISPLAY) {
      display_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      platform_ = "egl-surfaceless";
    }
    if (display_ == EGL_NO_DISPLAY) throw std::runtime_error(egl_error("eglGetPlatformDisplay"));
    EGLint major = 0;
    EGLint minor = 0;
    if (!egl().initialize(display_, &major, &minor))
      throw std::runtime_error(egl_error("eglInitialize"));
    if (!egl().bind_api(EGL_OPENGL_API)) throw std::runtime_error(egl_error("eglBindAPI"));
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              4,
                              EGL_CONTEXT_MINOR_VERSION,
                              5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    context_ = egl().create_context(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (context_ == EGL_NO_CONTEXT)
      throw std::runtime_error(egl_error("eglCreateContext 4.5 core"));
    make_current();
    load_gl([](const char* name) { return reinterpret_cast<void*>(egl().get_proc_address(name)); });
  }
  ~EGLContextImpl() override {
    if (display_ != EGL_NO_DISPLAY) {
      egl().make_current(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context_ != EGL_NO_CONTEXT) egl().destroy_context(display_, context_);
      egl().terminate(display_);
    }
  }
  EGLContextImpl(const EGLContextImpl&) = delete;
  EGLContextImpl& operator=(const EGLContextImpl&) = delete;

  Backend backend() const override { return Backend::EGL; }
  std::string platform() const override { return platform_; }
  void make_current() override {
    if (!egl().make_current(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw std::runtime_error(egl_error("eglMakeCurrent"));
  }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string platform_;
};

}  // namespace

std::unique_ptr<Context> create_egl_context() { return std::make_unique<EGLContextImpl>(); }
void load_egl_library() { egl(); }

}  // namespace sb::gl

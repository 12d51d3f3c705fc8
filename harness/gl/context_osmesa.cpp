// OSMesa backend. Kept in its own file: osmesa.h must not meet other GL headers.
// libOSMesa is opened when the first context is created, not linked: it
// brings in LLVM, ~60 ms at every process start. Four entry points, so
// dlsym rather than a module of our own.
#include <GL/osmesa.h>

#include <memory>
#include <stdexcept>
#include <vector>

#include "core/lazy_library.h"
#include "gl/context.h"

namespace sb::gl {
namespace {

struct OSMesaApi {
  decltype(&OSMesaCreateContextAttribs) create_context_attribs;
  decltype(&OSMesaMakeCurrent) make_current;
  decltype(&OSMesaDestroyContext) destroy_context;
  decltype(&OSMesaGetProcAddress) get_proc_address;
};

const OSMesaApi& osmesa() {
  static const OSMesaApi api = [] {
    // Debian's libosmesa6.
    static core::LazyLibrary lib("libOSMesa.so.8", "the OSMesa backend's library");
    return OSMesaApi{
        lib.function<decltype(&OSMesaCreateContextAttribs)>("OSMesaCreateContextAttribs"),
        lib.function<decltype(&OSMesaMakeCurrent)>("OSMesaMakeCurrent"),
        lib.function<decltype(&OSMesaDestroyContext)>("OSMesaDestroyContext"),
        lib.function<decltype(&OSMesaGetProcAddress)>("OSMesaGetProcAddress")};
  }();
  return api;
}

class OSMesaContextImpl final : public Context {
 public:
  OSMesaContextImpl() {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_STENCIL_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    ctx_ = osmesa().create_context_attribs(attribs, nullptr);
    if (ctx_ == nullptr)
      throw std::runtime_error("OSMesaCreateContextAttribs failed for GL 4.5 core");
    make_current();
    load_gl(
        [](const char* name) { return reinterpret_cast<void*>(osmesa().get_proc_address(name)); });
  }
  ~OSMesaContextImpl() override {
    if (ctx_ != nullptr) osmesa().destroy_context(ctx_);
  }
  OSMesaContextImpl(const OSMesaContextImpl&) = delete;
  OSMesaContextImpl& operator=(const OSMesaContextImpl&) = delete;

  Backend backend() const override { return Backend::OSMesa; }
  std::string platform() const override { return "osmesa"; }
  void make_current() override {
    // OSMesa has no surfaceless make-current: bind a tiny buffer; all real
    // rendering goes to framebuffer objects.
    if (osmesa().make_current(ctx_, dummy_.data(), 0x1401 /*GL_UNSIGNED_BYTE*/, 1, 1) == 0)
      throw std::runtime_error("OSMesaMakeCurrent failed");
  }

 private:
  OSMesaContext ctx_ = nullptr;
  std::vector<unsigned char> dummy_ = std::vector<unsigned char>(4 * 4, 0);
};

}  // namespace

std::unique_ptr<Context> create_osmesa_context() { return std::make_unique<OSMesaContextImpl>(); }
void load_osmesa_library() { osmesa(); }

}  // namespace sb::gl

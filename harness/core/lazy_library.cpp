#include "core/lazy_library.h"

#include <dlfcn.h>

#include <atomic>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace sb::core {

namespace {
std::atomic<std::size_t> g_threads_started{0};
}  // namespace

std::size_t thread_count() {
  std::size_t n = 0;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator("/proc/self/task", ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec))
    ++n;
  return n;
}

std::size_t threads_started_by_lazy_libraries() { return g_threads_started.load(); }

LazyLibrary::LazyLibrary(std::string path, std::string what)
    : path_(std::move(path)), what_(std::move(what)) {}

void* LazyLibrary::symbol(const char* name) {
  std::call_once(once_, [this] {
    const std::size_t before = thread_count();
    handle_ = dlopen(path_.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle_ == nullptr) {
      const char* why = dlerror();
      error_ =
          "cannot load " + what_ + " (" + path_ + "): " + (why != nullptr ? why : "dlopen failed");
      return;
    }
    if (const std::size_t after = thread_count(); after > before)
      g_threads_started += after - before;
  });
  if (handle_ == nullptr) throw std::runtime_error(error_);
  dlerror();  // clear: a null symbol is not necessarily an error
  void* address = dlsym(handle_, name);
  if (address == nullptr) {
    const char* why = dlerror();
    throw std::runtime_error(what_ + " (" + path_ + ") lacks " + name + ": " +
                             (why != nullptr ? why : "the symbol is null"));
  }
  return address;
}

}  // namespace sb::core

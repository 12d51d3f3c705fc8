#pragma once
// A shared library opened on first use rather than linked: OpenImageIO (its
// ~260 dependencies cost every process ~0.4 s to start) and the GL backends
// are loaded only by the processes that read an image or create a context.
#include <cstddef>
#include <mutex>
#include <string>

namespace sb::core {

class LazyLibrary {
 public:
  // `path`: a file name the dynamic linker searches for ("libOSMesa.so.8")
  // or a full path. `what` names it in errors ("the OSMesa backend").
  LazyLibrary(std::string path, std::string what);
  LazyLibrary(const LazyLibrary&) = delete;
  LazyLibrary& operator=(const LazyLibrary&) = delete;

  // The address of `name`, opening the library on the first call (once, from
  // any thread; it stays open). Throws std::runtime_error naming the path and
  // dlerror()'s words when the library or the symbol cannot be loaded.
  void* symbol(const char* name);
  template <typename F>
  F function(const char* name) {
    return reinterpret_cast<F>(symbol(name));
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::string what_;
  std::once_flag once_;
  void* handle_ = nullptr;
  std::string error_;  // why opening failed, for every later call
};

// Threads that libraries opened this way started while loading (Debian's
// log4cplus, which OpenImageIO brings in, starts four idle workers): like
// those of the linked libraries, they are not ours, and a forked child never
// calls into them (run/child_process.h).
std::size_t threads_started_by_lazy_libraries();

// This process's threads, from /proc/self/task; 0 when it cannot be read.
std::size_t thread_count();

}  // namespace sb::core

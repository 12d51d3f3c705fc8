#pragma once
// One computation per cache key across processes (reference.h: get()): the
// shards of a run that share a cache folder take the key's lock file before
// computing, so the others wait and then read the first one's file.
#include <filesystem>

namespace sb::reference::detail {

// An exclusive flock on a cache key's lock file, held while its reference is
// computed; the kernel drops it when the process dies. The file stays (a
// removed lock file could be locked by two processes at once). Throws
// JobError ("reference cache: cannot open|lock <file>: <reason>").
class KeyLock {
 public:
  explicit KeyLock(const std::filesystem::path& file);
  ~KeyLock();
  KeyLock(const KeyLock&) = delete;
  KeyLock& operator=(const KeyLock&) = delete;

 private:
  int fd_;
};

}  // namespace sb::reference::detail

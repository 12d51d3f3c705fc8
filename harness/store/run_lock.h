#pragma once
// One run at a time in a run folder. Two runs into one --out would interleave
// their records and inflate each other's timings; the second one is refused,
// naming who holds the folder.
#include <string>

namespace sb::store {

class RunFolderLock {
 public:
  // Creates `run_dir` if needed and takes an exclusive lock on
  // run_dir/.lock (flock: released by the kernel when the process dies, so a
  // killed run never leaves a stale lock). Throws std::runtime_error naming
  // the holder (pid, host, start time) when another process has it.
  explicit RunFolderLock(const std::string& run_dir);
  ~RunFolderLock();
  RunFolderLock(const RunFolderLock&) = delete;
  RunFolderLock& operator=(const RunFolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace sb::store

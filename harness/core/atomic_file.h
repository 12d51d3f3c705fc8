#pragma once
// Files that readers see whole or not at all: written under a temporary name
// in the same folder, then renamed over the final name (a rename within one
// file system replaces the file in one step). A process killed before the
// rename leaves only a temporary file, which is_atomic_temp_name() tells
// apart so that a later run can remove it (results/store.cpp).
//
// No fsync: what is guarded against is a killed writer, not a lost machine.
#include <string>
#include <string_view>

namespace sb::core {

// `context` starts every error message (e.g. "reference cache: "), so that
// callers keep their prefixes. Throws JobError naming the file and what
// failed; no temporary file is left behind.
void write_file_atomically(const std::string& path, std::string_view bytes,
                           const std::string& context = "");

// For writers that take a file name (OpenImageIO): write to temp_path(),
// then commit(). Destroyed without a commit, it removes the temporary file.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path, std::string context = "");
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& path() const { return path_; }
  // "<path>.tmp-<pid>-<n>": unique per process and per AtomicFile, so that
  // concurrent writers of one path never share a temporary file.
  const std::string& temp_path() const { return temp_; }
  // Renames the temporary file to path(); throws JobError when that fails
  // (the destructor then removes the temporary file).
  void commit();

 private:
  std::string path_;
  std::string temp_;
  std::string context_;
  bool committed_ = false;
};

// Whether a file name (no folder) is one AtomicFile's temporary names, or
// the "<name>.tmp-<pid>" of earlier versions: what a killed writer leaves.
bool is_atomic_temp_name(std::string_view name);

}  // namespace sb::core

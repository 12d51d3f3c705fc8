#pragma once
// Files that readers see whole or not at all: written under a temporary name
// in the same folder, then renamed over the final name (a rename within one
// file system replaces the file in one step).
//
// Writes that cannot be redirected: the temporary file is made new with
// O_CREAT|O_EXCL|O_NOFOLLOW, so a symlink or file planted at its name (a run
// folder from elsewhere) is never written through: another name is tried.
// The rename replaces a symlink at the final name itself and never follows
// it. Every error names the file and the reason (strerror's words: "No space
// left on device", "Permission denied", "Read-only file system"). A process killed before the
// rename leaves only a temporary file, which is_atomic_temp_name() tells
// apart so that a later run can remove it (store/results_store.cpp).
//
// No fsync: what is guarded against is a killed writer, not a lost machine.
#include <string>
#include <string_view>

namespace sb::core {

// `context` starts every error message (e.g. "reference cache: "), so that
// callers keep their prefixes. Throws JobError naming the file and what
// failed, with the reason; no temporary file is left behind.
void write_file_atomically(const std::string& path, std::string_view bytes,
                           const std::string& context = "");

// Makes the folder `root`/`rel` (root and its parents as needed, followed
// if symlinks: the user named root), each part of `rel` a real folder: a
// symlink or a file planted there (`report -> elsewhere` in a run folder from
// elsewhere) throws JobError naming it, and nothing is written through it.
void make_own_folder(const std::string& root, const std::string& rel,
                     const std::string& context = "");

// For writers that take a file name (OpenImageIO): write to temp_path(),
// then commit(); or write() the bytes, then commit(). Destroyed without a
// commit, it removes the temporary file.
class AtomicFile {
 public:
  // Creates the temporary file (empty, a regular file of this process's
  // making); throws JobError when it cannot.
  explicit AtomicFile(std::string path, std::string context = "");
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& path() const { return path_; }
  // "<path>.tmp-<pid>-<n>": unique per process and per AtomicFile, so that
  // concurrent writers of one path never share a temporary file.
  const std::string& temp_path() const { return temp_; }
  // Appends bytes to the temporary file; throws JobError with the reason.
  void write(std::string_view bytes);
  // Renames the temporary file to path(); throws JobError when that fails
  // (the destructor then removes the temporary file).
  void commit();

 private:
  std::string path_;
  std::string temp_;
  std::string context_;
  int fd_ = -1;
  bool committed_ = false;
};

// Whether a file name (no folder) is one AtomicFile's temporary names, or
// the "<name>.tmp-<pid>" of earlier versions: what a killed writer leaves.
bool is_atomic_temp_name(std::string_view name);

}  // namespace sb::core

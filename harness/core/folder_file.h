#pragma once
// Files that a folder names: an image path in a record, a run folder's
// results.jsonl or plan.json. Run folders, histories and baselines come from
// elsewhere (CI artifacts, other nodes' shards, downloads), so a path one of
// them names is opened inside its folder or not at all: relative, without a
// "..", no symbolic link on the way (one pointing inside the folder
// included: shadowbench never writes one), and a regular file at the end (no
// FIFO, device or folder). docs/robustness.md, "Reads inside the folder".
//
// The folder itself is opened as the caller names it (the user chose it on
// the command line): only the part below it is checked.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace sb::core {

// Why `rel` cannot name a file inside a folder ("is absolute", "has a '..'
// component", ...), or "" when it can. Lexical only: see open_in_folder.
std::string folder_path_problem(std::string_view rel);

// A regular file inside a folder, open for reading (closed on destruction).
class FolderFile {
 public:
  FolderFile(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
  FolderFile(FolderFile&& other) noexcept;
  FolderFile& operator=(FolderFile&&) = delete;
  FolderFile(const FolderFile&) = delete;
  FolderFile& operator=(const FolderFile&) = delete;
  ~FolderFile();

  int fd() const { return fd_; }
  // folder/rel, for messages and for readers that take a name (OpenImageIO).
  const std::string& path() const { return path_; }
  // The whole file; throws InputError naming path() when it holds more than
  // max_bytes or cannot be read (with strerror's reason).
  std::string read_all(std::size_t max_bytes) const;

 private:
  int fd_ = -1;
  std::string path_;
};

// Opens folder/rel for reading, walking rel's components from `folder` with
// openat(O_NOFOLLOW). std::nullopt when a component is not there (an image
// of a run with --no-images, a folder cleaned up). Throws InputError naming
// folder/rel and why when rel is refused: absolute, "..", empty, a NUL, a
// symbolic link at any component, or not a regular file.
std::optional<FolderFile> open_in_folder(const std::string& folder, std::string_view rel);

}  // namespace sb::core

#include "core/folder_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

#include "core/error.h"

namespace sb::core {

namespace {

namespace fs = std::filesystem;

// The components of a relative path, "." and empty ones left out.
std::vector<std::string> components(std::string_view rel) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= rel.size()) {
    const size_t end = std::min(rel.find('/', start), rel.size());
    const std::string_view part = rel.substr(start, end - start);
    if (!part.empty() && part != ".") out.emplace_back(part);
    start = end + 1;
  }
  return out;
}

// What is at dir/name, said when opening it failed.
std::string what_is_there(int dir, const std::string& name, int open_errno) {
  struct stat st {};
  if (::fstatat(dir, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0) {
    if (S_ISLNK(st.st_mode))
      return "passes through the symbolic link " + name +
             ": files a folder names are read inside it, and shadowbench writes no link";
    if (!S_ISDIR(st.st_mode)) return "passes through " + name + ", which is not a folder";
  }
  return std::string("cannot be opened: ") + std::strerror(open_errno);
}

class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  int release() { return std::exchange(fd_, -1); }
  void reset(int fd) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
  }

 private:
  int fd_;
};

}  // namespace

std::string folder_path_problem(std::string_view rel) {
  if (rel.empty()) return "is empty";
  if (rel.find('\0') != std::string_view::npos) return "holds a NUL byte";
  if (rel.front() == '/') return "is absolute: files a folder names are read inside it";
  if (rel.back() == '/') return "names a folder, not a file";
  for (const std::string& part : components(rel))
    if (part == "..") return "has a '..' component: files a folder names are read inside it";
  if (components(rel).empty()) return "names the folder itself, not a file";
  return "";
}

FolderFile::FolderFile(FolderFile&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), path_(std::move(other.path_)) {}

FolderFile::~FolderFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::string FolderFile::read_all(std::size_t max_bytes) const {
  std::string out;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::pread(fd_, buffer, sizeof buffer, static_cast<off_t>(out.size()));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError(path_, "", std::string("cannot be read: ") + std::strerror(errno));
    }
    if (n == 0) return out;
    if (out.size() + static_cast<size_t>(n) > max_bytes)
      throw InputError(path_, "", "is larger than " + std::to_string(max_bytes) + " bytes");
    out.append(buffer, static_cast<size_t>(n));
  }
}

std::optional<FolderFile> open_in_folder(const std::string& folder, std::string_view rel) {
  std::string shown(rel);  // a NUL would end the message
  for (size_t at = shown.find('\0'); at != std::string::npos; at = shown.find('\0', at))
    shown.replace(at, 1, "\\0");
  const std::string path = (fs::path(folder) / fs::path(shown)).string();
  if (const std::string why = folder_path_problem(rel); !why.empty())
    throw InputError(path, "", "names a file outside its folder: the path " + why);
  Fd dir(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (dir.get() < 0) {
    if (errno == ENOENT) return std::nullopt;
    throw InputError(folder, "", std::string("cannot be opened: ") + std::strerror(errno));
  }
  const std::vector<std::string> parts = components(rel);
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    const int next =
        ::openat(dir.get(), parts[i].c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (next < 0) {
      const int err = errno;
      if (err == ENOENT) return std::nullopt;
      throw InputError(path, "", what_is_there(dir.get(), parts[i], err));
    }
    dir.reset(next);
  }
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below.
  const int fd = ::openat(dir.get(), parts.back().c_str(),
                          O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    if (err == ENOENT) return std::nullopt;
    if (err == ELOOP)
      throw InputError(path, "",
                       "is a symbolic link: files a folder names are read inside it, and "
                       "shadowbench writes no link");
    throw InputError(path, "", what_is_there(dir.get(), parts.back(), err));
  }
  Fd file(fd);
  struct stat st {};
  if (::fstat(fd, &st) != 0)
    throw InputError(path, "", std::string("cannot be read: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw InputError(path, "", "is not a regular file");
  return FolderFile(file.release(), path);
}

}  // namespace sb::core

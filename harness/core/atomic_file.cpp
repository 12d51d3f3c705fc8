#include "core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>

#include "core/error.h"

namespace sb::core {

namespace {

constexpr std::string_view kTempMarker = ".tmp-";

// Names tried before giving up when every one is taken (something planted
// them, or a folder full of killed writers' files).
constexpr int kTempNameTries = 64;

// The rest of a name after a run of digits at `pos`, or npos if none is there.
size_t after_digits(std::string_view s, size_t pos) {
  const size_t end = s.find_first_not_of("0123456789", pos);
  const size_t stop = end == std::string_view::npos ? s.size() : end;
  return stop > pos ? stop : std::string_view::npos;
}

// The next counter: per process, then random once a name was found taken,
// so that names planted ahead of it cannot all be guessed.
uint64_t next_counter(bool collided) {
  static std::atomic<uint64_t> counter{0};
  if (!collided) return counter++;
  static thread_local std::mt19937_64 rng{std::random_device{}()};
  return rng() >> 1;
}

}  // namespace

AtomicFile::AtomicFile(std::string path, std::string context)
    : path_(std::move(path)), context_(std::move(context)) {
  bool collided = false;
  for (int i = 0; i < kTempNameTries; ++i) {
    temp_ = path_ + std::string(kTempMarker) + std::to_string(::getpid()) + "-" +
            std::to_string(next_counter(collided));
    // O_EXCL: a new file or nothing; whatever is at the name already (a
    // symlink planted to redirect the write, a killed writer's file) makes
    // it fail, and O_NOFOLLOW says so for a symlink even if dangling.
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd_ >= 0) return;
    if (errno != EEXIST && errno != ELOOP) break;
    collided = true;
  }
  const int err = errno;
  const std::string temp = temp_;
  temp_.clear();  // nothing of ours to remove
  if (err == EEXIST || err == ELOOP)
    throw JobError(context_ + "cannot write " + path_ + ": " + std::to_string(kTempNameTries) +
                   " temporary names next to it are taken (the last " + temp + ")");
  throw JobError(context_ + "cannot write " + temp + ": " + std::strerror(err));
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (committed_ || temp_.empty()) return;
  ::unlink(temp_.c_str());
}

void AtomicFile::write(std::string_view bytes) {
  const char* p = bytes.data();
  size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw JobError(context_ + "cannot write " + temp_ + ": " + std::strerror(errno));
    p += n;
    left -= size_t(n);
  }
}

void AtomicFile::commit() {
  if (fd_ >= 0) {
    const int fd = fd_;
    fd_ = -1;
    // close() is where some file systems (NFS) say that the data did not fit.
    if (::close(fd) != 0 && errno != EINTR)
      throw JobError(context_ + "cannot write " + temp_ + ": " + std::strerror(errno));
  }
  // rename() replaces whatever is at path_, a symlink included, and never
  // writes through it. On failure the destructor removes the temporary file.
  if (::rename(temp_.c_str(), path_.c_str()) != 0)
    throw JobError(context_ + "cannot rename " + temp_ + " to " + path_ + ": " +
                   std::strerror(errno));
  committed_ = true;
}

void write_file_atomically(const std::string& path, std::string_view bytes,
                           const std::string& context) {
  AtomicFile file(path, context);
  file.write(bytes);
  file.commit();
}

void make_own_folder(const std::string& root, const std::string& rel, const std::string& context) {
  std::error_code ec;
  std::filesystem::create_directories(root, ec);
  if (ec) throw JobError(context + "cannot create " + root + ": " + ec.message());
  std::filesystem::path at(root);
  for (const std::filesystem::path& part : std::filesystem::path(rel)) {
    at /= part;
    if (::mkdir(at.c_str(), 0777) != 0 && errno != EEXIST)
      throw JobError(context + "cannot create " + at.string() + ": " + std::strerror(errno));
    struct stat st {};
    if (::lstat(at.c_str(), &st) != 0)
      throw JobError(context + "cannot create " + at.string() + ": " + std::strerror(errno));
    if (!S_ISDIR(st.st_mode))
      throw JobError(context + at.string() +
                     (S_ISLNK(st.st_mode) ? " is a symlink" : " is not a folder") +
                     " where shadowbench makes a folder of its own: it does not write through it "
                     "(remove it)");
  }
}

bool is_atomic_temp_name(std::string_view name) {
  const size_t marker = name.rfind(kTempMarker);
  if (marker == std::string_view::npos || marker == 0) return false;
  size_t pos = after_digits(name, marker + kTempMarker.size());  // the pid
  if (pos == std::string_view::npos) return false;
  if (pos < name.size() && name[pos] == '-') pos = after_digits(name, pos + 1);  // the counter
  return pos == name.size();
}

}  // namespace sb::core

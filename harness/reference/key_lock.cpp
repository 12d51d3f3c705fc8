#include "reference/key_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace sb::reference::detail {

using core::JobError;

KeyLock::KeyLock(const std::filesystem::path& file)
    : fd_(::open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644)) {
  if (fd_ < 0)
    throw JobError("reference cache: cannot open " + file.string() + ": " + std::strerror(errno));
  while (::flock(fd_, LOCK_EX) != 0)
    if (errno != EINTR) {
      const int err = errno;
      ::close(fd_);
      throw JobError("reference cache: cannot lock " + file.string() + ": " + std::strerror(err));
    }
}

KeyLock::~KeyLock() { ::close(fd_); }

}  // namespace sb::reference::detail

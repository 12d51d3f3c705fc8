#include "run/phase_board.h"

#include <sys/mman.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace sb::run {

namespace {

constexpr size_t kBytes = 256;  // one phase's name, with a frame's

}  // namespace

PhaseBoard::PhaseBoard() {
  void* page = ::mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (page == MAP_FAILED)
    throw std::runtime_error(std::string("cannot map memory shared with a child process: ") +
                             std::strerror(errno));
  text_ = static_cast<char*>(page);
  text_[0] = '\0';
}

PhaseBoard::~PhaseBoard() {
  if (text_ != nullptr) ::munmap(text_, kBytes);
}

void PhaseBoard::set(std::string_view phase) {
  // The parent reads only after the child has gone; one killed mid-copy
  // leaves mixed text, still bounded by read().
  const size_t n = std::min(phase.size(), kBytes - 1);
  std::memcpy(text_, phase.data(), n);
  text_[n] = '\0';
}

std::string PhaseBoard::read() const { return std::string(text_, ::strnlen(text_, kBytes)); }

}  // namespace sb::run

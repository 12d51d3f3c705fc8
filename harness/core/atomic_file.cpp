#include "core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/error.h"

namespace sb::core {

namespace {

constexpr std::string_view kTempMarker = ".tmp-";

// The rest of a name after a run of digits at `pos`, or npos if none is there.
size_t after_digits(std::string_view s, size_t pos) {
  const size_t end = s.find_first_not_of("0123456789", pos);
  const size_t stop = end == std::string_view::npos ? s.size() : end;
  return stop > pos ? stop : std::string_view::npos;
}

}  // namespace

AtomicFile::AtomicFile(std::string path, std::string context)
    : path_(std::move(path)), context_(std::move(context)) {
  static std::atomic<uint64_t> counter{0};
  temp_ = path_ + std::string(kTempMarker) + std::to_string(::getpid()) + "-" +
          std::to_string(counter++);
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  std::error_code ignored;
  std::filesystem::remove(temp_, ignored);
}

void AtomicFile::commit() {
  std::error_code ec;
  std::filesystem::rename(temp_, path_, ec);
  // On failure the destructor removes the temporary file.
  if (ec)
    throw JobError(context_ + "cannot rename " + temp_ + " to " + path_ + ": " + ec.message());
  committed_ = true;
}

void write_file_atomically(const std::string& path, std::string_view bytes,
                           const std::string& context) {
  AtomicFile file(path, context);
  {
    std::ofstream out(file.temp_path(), std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) throw JobError(context + "cannot write " + file.temp_path());
  }
  file.commit();
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

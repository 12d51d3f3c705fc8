#include "gl/allocation_meter.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <utility>

namespace sb::gl {

namespace {

struct Meter {
  bool open = false;
  std::map<std::pair<StorageKind, GLuint>, std::int64_t> bytes;  // of live objects
  std::int64_t live = 0, peak = 0;
};

Meter& meter() {
  static Meter m;
  return m;
}

}  // namespace

void meter_storage(StorageKind kind, GLuint id, std::int64_t bytes) {
  Meter& m = meter();
  if (!m.open) return;
  std::int64_t& held = m.bytes[{kind, id}];
  m.live += bytes - held;
  held = bytes;
  m.peak = std::max(m.peak, m.live);
}

void meter_restorage(StorageKind kind, GLuint id, std::int64_t bytes) {
  Meter& m = meter();
  if (m.bytes.count({kind, id}) != 0) meter_storage(kind, id, bytes);
}

void meter_release(StorageKind kind, GLuint id) {
  Meter& m = meter();
  const auto it = m.bytes.find({kind, id});
  if (it == m.bytes.end()) return;  // made outside the window, or not by a maker
  m.live -= it->second;
  m.bytes.erase(it);
}

AllocationWindow::AllocationWindow() {
  Meter& m = meter();
  if (m.open) throw std::logic_error("an allocation window is already open");
  m = Meter{};
  m.open = true;
}

AllocationWindow::~AllocationWindow() { meter() = Meter{}; }

std::int64_t AllocationWindow::peak_bytes() const { return meter().peak; }

std::int64_t AllocationWindow::live_bytes() const { return meter().live; }

}  // namespace sb::gl

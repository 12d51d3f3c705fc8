#include "gl/allocation_meter.h"

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

namespace sb::gl {

// What one window saw: the objects made while it was open and still live.
struct AllocationWindow::Tally {
  std::map<std::pair<StorageKind, GLuint>, std::int64_t> bytes;  // of live objects
  std::int64_t live = 0, peak = 0;

  void store(StorageKind kind, GLuint id, std::int64_t size) {
    std::int64_t& held = bytes[{kind, id}];
    live += size - held;
    held = size;
    peak = std::max(peak, live);
  }
};

namespace {

// The open windows, outermost first.
std::vector<AllocationWindow::Tally*>& open_windows() {
  static std::vector<AllocationWindow::Tally*> open;
  return open;
}

}  // namespace

void meter_storage(StorageKind kind, GLuint id, std::int64_t bytes) {
  for (AllocationWindow::Tally* t : open_windows()) t->store(kind, id, bytes);
}

void meter_restorage(StorageKind kind, GLuint id, std::int64_t bytes) {
  for (AllocationWindow::Tally* t : open_windows())
    if (t->bytes.count({kind, id}) != 0) t->store(kind, id, bytes);
}

void meter_release(StorageKind kind, GLuint id) {
  for (AllocationWindow::Tally* t : open_windows()) {
    const auto it = t->bytes.find({kind, id});
    if (it == t->bytes.end()) continue;  // made outside the window, or not by a maker
    t->live -= it->second;
    t->bytes.erase(it);
  }
}

AllocationWindow::AllocationWindow() : tally_(std::make_unique<Tally>()) {
  open_windows().push_back(tally_.get());
}

AllocationWindow::~AllocationWindow() {
  auto& open = open_windows();
  open.erase(std::remove(open.begin(), open.end(), tally_.get()), open.end());
}

std::int64_t AllocationWindow::peak_bytes() const { return tally_->peak; }

std::int64_t AllocationWindow::live_bytes() const { return tally_->live; }

}  // namespace sb::gl

#pragma once
// The GPU memory a technique asks for (docs/results.md, technique.gpu_bytes):
// every texture, renderbuffer and buffer storage made through the gl::make_*
// helpers (gl/objects.h) is metered while a window is open, and its bytes
// (gl/storage_bytes.h) stay counted until the object is deleted or its
// storage replaced. The run opens the window around one technique's
// prepare() and frames, so that the G-buffer, reference and control, made
// outside it, are not counted; and one around each upload the harness makes
// for a need (run/scene_upload.h, GpuScene's adjacency), which a technique
// that declares the need is charged. GL objects a plugin makes with raw GL
// calls are not seen. One meter per process, used from the GL thread only.
#include <cstdint>
#include <memory>

#include "gl/gl.h"

namespace sb::gl {

// GL names are per kind of object: texture 3 and buffer 3 are two objects.
enum class StorageKind { TextureName, BufferName, RenderbufferName };

// Called by the makers: new object `id` has `bytes` of storage. Nothing
// when no window is open.
void meter_storage(StorageKind kind, GLuint id, std::int64_t bytes);
// Object `id`'s storage was replaced by `bytes`: counted only when the
// object was made in the window (a control's stream, made before it, is not).
void meter_restorage(StorageKind kind, GLuint id, std::int64_t bytes);
// Called when an object is deleted: its bytes are no longer live.
void meter_release(StorageKind kind, GLuint id);

// An open window of the meter. Windows nest: each counts what is made
// while it is open, so a window around a scene's upload inside a job's
// counts in both. Closes on destruction, forgetting what it saw.
class AllocationWindow {
 public:
  struct Tally;

  AllocationWindow();
  ~AllocationWindow();
  AllocationWindow(const AllocationWindow&) = delete;
  AllocationWindow& operator=(const AllocationWindow&) = delete;

  // The most bytes live at once since the window opened.
  std::int64_t peak_bytes() const;
  // The bytes live now.
  std::int64_t live_bytes() const;

 private:
  std::unique_ptr<Tally> tally_;
};

}  // namespace sb::gl

#pragma once
// The reference every job of one (scene, resolution) is measured against,
// with what measuring costs of it alone made once, on first use, and kept:
// FLIP's half of its V and of its shaded image as FLIP's tool reads it from
// shaded.png (FlipReference). The first job measured pays for it, in its
// `measure` phase; the others reuse it, and their figures keep their bits.
// It holds 68 bytes a pixel (the two images' FLIP halves, 40, and the copies):
// 141 MB at 1920x1080, kept while the (scene, resolution)'s jobs run.
#include <memory>
#include <mutex>

#include "core/image.h"
#include "metrics/flip.h"

namespace sb::metrics {

// The image as an 8-bit PNG written from it (io::write_png) holds it,
// decoded from sRGB: what FLIP's own tool reads from the file. A 4th
// channel (alpha) is not sRGB-encoded and stays v / 255.
core::ImageF as_flip_reads_png(const core::ImageF& image);

class PreparedReference {
 public:
  PreparedReference(core::ImageF visibility, core::ImageF shaded, double flip_pixels_per_degree);

  const core::ImageF& visibility() const { return visibility_; }
  const core::ImageF& shaded() const { return shaded_; }
  double flip_pixels_per_degree() const { return flip_pixels_per_degree_; }

  // Made on the first call of any of them (thread-safe), then kept.
  const FlipReference& flip_visibility() const;
  const core::ImageF& shaded_png() const;  // as_flip_reads_png(shaded())
  const FlipReference& flip_shaded_png() const;

 private:
  struct Made {
    FlipReference visibility;
    core::ImageF shaded_png;
    FlipReference shaded_png_flip;
  };
  const Made& made() const;

  core::ImageF visibility_, shaded_;
  double flip_pixels_per_degree_;
  mutable std::once_flag once_;
  mutable std::unique_ptr<Made> made_;
};

}  // namespace sb::metrics

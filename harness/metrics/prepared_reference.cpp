#include "metrics/prepared_reference.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "metrics/image_io.h"

namespace sb::metrics {

using core::ImageF;

ImageF as_flip_reads_png(const ImageF& image) {
  // A byte has 256 values: linear_from_srgb's own result for each, looked up.
  static const std::array<float, 256> decoded = [] {
    ImageF bytes(256, 1, 1);
    for (int b = 0; b < 256; ++b)
      bytes.data[static_cast<std::size_t>(b)] = static_cast<float>(b) / 255.0f;
    const ImageF linear = linear_from_srgb(bytes);
    std::array<float, 256> table{};
    std::copy(linear.data.begin(), linear.data.end(), table.begin());
    return table;
  }();
  ImageF q = image;
  const std::size_t nc = static_cast<std::size_t>(q.channels);
  for (std::size_t i = 0; i < q.data.size(); ++i) {
    const uint8_t byte = io::png_byte(q.data[i]);
    q.data[i] = nc == 4 && i % 4 == 3 ? static_cast<float>(byte) / 255.0f : decoded[byte];
  }
  return q;
}

PreparedReference::PreparedReference(ImageF visibility, ImageF shaded,
                                     double flip_pixels_per_degree)
    : visibility_(std::move(visibility)),
      shaded_(std::move(shaded)),
      flip_pixels_per_degree_(flip_pixels_per_degree) {}

const PreparedReference::Made& PreparedReference::made() const {
  std::call_once(once_, [this] {
    ImageF png = as_flip_reads_png(shaded_);
    FlipReference png_flip(png, flip_pixels_per_degree_);
    made_ = std::make_unique<Made>(Made{FlipReference(visibility_, flip_pixels_per_degree_),
                                        std::move(png), std::move(png_flip)});
  });
  return *made_;
}

const FlipReference& PreparedReference::flip_visibility() const { return made().visibility; }

const ImageF& PreparedReference::shaded_png() const { return made().shaded_png; }

const FlipReference& PreparedReference::flip_shaded_png() const { return made().shaded_png_flip; }

}  // namespace sb::metrics

#include "metrics/flip_reuse.h"

#include <cstddef>
#include <cstring>
#include <stdexcept>

#include "metrics/flip.h"
#include "metrics/regions.h"

namespace sb::metrics {

using core::ImageF;

namespace {

// 1 where the two images' values differ (bitwise, every channel).
std::vector<uint8_t> differing_pixels(const ImageF& a, const ImageF& b) {
  const std::size_t nc = static_cast<std::size_t>(a.channels);
  std::vector<uint8_t> out(a.pixel_count());
  for (std::size_t p = 0; p < out.size(); ++p)
    out[p] = std::memcmp(&a.data[p * nc], &b.data[p * nc], nc * sizeof(float)) != 0 ? 1 : 0;
  return out;
}

}  // namespace

ImageF flip_map_reusing(const ImageF& reference, const ImageF& test,
                        const std::vector<uint8_t>* mask, const std::vector<KnownFlipMap>& known,
                        double pixels_per_degree) {
  const std::vector<uint8_t> every(mask ? 0 : test.pixel_count(), 1);
  const std::vector<uint8_t>& wanted = mask ? *mask : every;
  if (wanted.size() != test.pixel_count())
    throw std::invalid_argument("flip_map_reusing: the mask is not the image's size");
  const int radius = flip_radius(pixels_per_degree);
  // The wanted pixels to compute, and the map the others come from.
  std::vector<uint8_t> needed = wanted;
  const ImageF* from = nullptr;
  std::int64_t fewest = count_ones(wanted);
  for (const KnownFlipMap& k : known) {
    if (k.image->channels != test.channels || k.image->pixel_count() != test.pixel_count())
      continue;
    std::vector<uint8_t> near = mask_and(
        dilated(differing_pixels(test, *k.image), test.width, test.height, radius), wanted);
    const std::int64_t n = count_ones(near);
    if (n < fewest) fewest = n, needed = std::move(near), from = k.map;
  }
  if (from == nullptr && mask == nullptr) return flip(reference, test, pixels_per_degree).error;
  ImageF map = fewest > 0 ? flip_map_within(reference, test, needed, pixels_per_degree)
                          : ImageF(test.width, test.height, 1);
  if (from != nullptr)
    for (std::size_t p = 0; p < wanted.size(); ++p)
      if (wanted[p] && !needed[p]) map.data[p] = from->data[p];
  return map;
}

}  // namespace sb::metrics

#include "metrics/flip_reuse.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
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
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, out.size(), 16384),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t p = r.begin(); p != r.end(); ++p)
          out[p] = std::memcmp(&a.data[p * nc], &b.data[p * nc], nc * sizeof(float)) != 0 ? 1 : 0;
      });
  return out;
}

// `near` kept only where `wanted` is 1; returns how many 1s are left.
std::int64_t keep_wanted(std::vector<uint8_t>& near, const std::vector<uint8_t>& wanted) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, near.size(), 16384), std::int64_t{0},
      [&](const tbb::blocked_range<std::size_t>& r, std::int64_t ones) {
        for (std::size_t p = r.begin(); p != r.end(); ++p) {
          near[p] = near[p] && wanted[p] ? 1 : 0;
          ones += near[p];
        }
        return ones;
      },
      std::plus<>());
}

}  // namespace

ImageF flip_map_reusing(const FlipReference& reference, const ImageF& test,
                        const std::vector<uint8_t>* mask, const std::vector<KnownFlipMap>& known) {
  const std::vector<uint8_t> every(mask ? 0 : test.pixel_count(), 1);
  const std::vector<uint8_t>& wanted = mask ? *mask : every;
  if (wanted.size() != test.pixel_count())
    throw std::invalid_argument("flip_map_reusing: the mask is not the image's size");
  const int radius = flip_radius(reference.pixels_per_degree());
  // The wanted pixels to compute, and the map the others come from.
  std::vector<uint8_t> needed = wanted;
  const ImageF* from = nullptr;
  std::int64_t fewest = count_ones(wanted);
  for (const KnownFlipMap& k : known) {
    if (k.image->channels != test.channels || k.image->pixel_count() != test.pixel_count())
      continue;
    std::vector<uint8_t> near =
        dilated(differing_pixels(test, *k.image), test.width, test.height, radius);
    const std::int64_t n = keep_wanted(near, wanted);
    if (n < fewest) fewest = n, needed = std::move(near), from = k.map;
  }
  if (from == nullptr && mask == nullptr) return flip(reference, test).error;
  ImageF map =
      fewest > 0 ? flip_map_within(reference, test, needed) : ImageF(test.width, test.height, 1);
  if (from != nullptr)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, wanted.size(), 16384),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t p = r.begin(); p != r.end(); ++p)
                          if (wanted[p] && !needed[p]) map.data[p] = from->data[p];
                      });
  return map;
}

}  // namespace sb::metrics

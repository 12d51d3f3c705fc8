#include "metrics/regions.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <glm/vec3.hpp>
#include <optional>
#include <stdexcept>

#include "metrics/distance_thirds.h"
#include "metrics/geometry_region.h"
#include "metrics/metrics.h"
#include "record/figures.h"

namespace sb::metrics {

using core::ImageF;

namespace {

using Mask = std::vector<uint8_t>;

// How one region of the catalogue is made: its pixels from the inputs and
// the measured pixels (nullopt: the view does not have it), and how it is
// measured.
struct RegionMaker {
  const char* key;
  std::optional<Mask> (*make)(const RegionInputs& in, const Mask& measured);
  Surround surround = Surround::Technique;
  bool visibility_only = false;
  bool per_job = false;
};

template <std::size_t Third>
std::optional<Mask> distance_third(const RegionInputs& in, const Mask& measured) {
  if (!in.distance_thirds) return std::nullopt;
  const glm::vec3 eye(in.eye[0], in.eye[1], in.eye[2]);
  return distance_thirds(*in.positions, eye, measured, in.distance_scale)[Third];
}

// Every region's pixels. The pixels whose tangent plane cuts the light are
// left out of every region but their own (`terminator`).
const std::vector<RegionMaker>& makers() {
  static const std::vector<RegionMaker> list = {
      {"all", [](const RegionInputs&, const Mask& measured) { return std::optional(measured); }},
      // The surface outside attached shadow (metrics/geometry_region.h): its
      // SSIM windows see the reference's values everywhere outside it.
      {"geometry",
       [](const RegionInputs& in, const Mask&) { return std::optional(geometry_mask(in.horizon)); },
       Surround::Reference},
      {"penumbra",
       [](const RegionInputs& in, const Mask& measured) {
         return std::optional(mask_and(in.reference_penumbra, measured));
       }},
      {"soft_union", [](const RegionInputs&, const Mask&) { return std::optional(Mask{}); },
       Surround::Technique, false, true},
      // Absent when the view holds no such pixel.
      {"receivers",
       [](const RegionInputs& in, const Mask& measured) -> std::optional<Mask> {
         Mask m(in.receiver.size());
         for (size_t i = 0; i < m.size(); ++i) m[i] = in.receiver[i] && measured[i] ? 1 : 0;
         if (std::find(m.begin(), m.end(), 1) == m.end()) return std::nullopt;
         return m;
       }},
      // Outside the measured pixels: the technique's own values there, the
      // reference's outside.
      {"terminator",
       [](const RegionInputs& in, const Mask&) {
         return std::optional(horizon_mask(in.horizon, LightHorizon::Cuts));
       },
       Surround::Reference},
      {"near_third", distance_third<0>, Surround::Technique, true},
      {"middle_third", distance_third<1>, Surround::Technique, true},
      {"far_third", distance_third<2>, Surround::Technique, true},
  };
  return list;
}

}  // namespace

const RegionMask* Regions::find(std::string_view key) const {
  for (const RegionMask& r : masks)
    if (r.key == key) return &r;
  return nullptr;
}

const std::vector<uint8_t>& Regions::mask(std::string_view key) const {
  if (const RegionMask* r = find(key)) return r->mask;
  throw std::out_of_range("no region \"" + std::string(key) + "\" here");
}

Regions make_regions(const RegionInputs& in) {
  Regions regions;
  regions.attached = horizon_mask(in.horizon, LightHorizon::Below);
  regions.measured = horizon_mask(in.horizon, LightHorizon::Cuts);
  for (auto& m : regions.measured) m = m ? 0 : 1;
  for (const record::Region& region : record::regions()) {
    const auto maker = std::find_if(makers().begin(), makers().end(),
                                    [&](const RegionMaker& m) { return region.key == m.key; });
    if (maker == makers().end())
      throw std::logic_error("region \"" + region.key + "\" has no mask (metrics/regions.cpp)");
    std::optional<Mask> mask = maker->make(in, regions.measured);
    if (!mask) continue;
    regions.masks.push_back(
        {region.key, std::move(*mask), maker->surround, maker->visibility_only, maker->per_job});
  }
  return regions;
}

std::vector<uint8_t> job_mask(const RegionMask& region, const ImageF& visibility,
                              const Regions& regions) {
  if (!region.per_job) return region.mask;
  return soft_union_of(visibility, regions);
}

std::vector<uint8_t> mask_and(std::vector<uint8_t> a, const std::vector<uint8_t>& b) {
  for (size_t i = 0; i < a.size(); ++i) a[i] = a[i] && b[i] ? 1 : 0;
  return a;
}

std::int64_t count_ones(const std::vector<uint8_t>& mask) {
  return std::count(mask.begin(), mask.end(), uint8_t(1));
}

std::vector<uint8_t> dilated(const std::vector<uint8_t>& mask, int width, int height, int radius) {
  const auto at = [width](int x, int y) {
    return static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
  };
  // Along x, then along y: a running count of the 1s in the window; rows,
  // then bands of columns, in parallel.
  std::vector<uint8_t> rows(mask.size()), out(mask.size());
  tbb::parallel_for(tbb::blocked_range<int>(0, height, 16), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y) {
      int ones = 0;
      for (int x = 0; x < std::min(radius, width); ++x) ones += mask[at(x, y)] != 0;
      for (int x = 0; x < width; ++x) {
        if (x + radius < width) ones += mask[at(x + radius, y)] != 0;
        if (x - radius - 1 >= 0) ones -= mask[at(x - radius - 1, y)] != 0;
        rows[at(x, y)] = ones > 0 ? 1 : 0;
      }
    }
  });
  constexpr int kBand = 64;
  tbb::parallel_for(tbb::blocked_range<int>(0, (width + kBand - 1) / kBand, 1),
                    [&](const tbb::blocked_range<int>& bands) {
                      for (int b = bands.begin(); b != bands.end(); ++b) {
                        const int x0 = b * kBand, x1 = std::min(width, x0 + kBand);
                        // per column, rows y - radius ... y + radius
                        std::array<int, kBand> ones{};
                        const auto add_row = [&](int y, int sign) {
                          for (int x = x0; x < x1; ++x) ones[x - x0] += sign * rows[at(x, y)];
                        };
                        for (int y = 0; y < std::min(radius, height); ++y) add_row(y, 1);
                        for (int y = 0; y < height; ++y) {
                          if (y + radius < height) add_row(y + radius, 1);
                          if (y - radius - 1 >= 0) add_row(y - radius - 1, -1);
                          for (int x = x0; x < x1; ++x) out[at(x, y)] = ones[x - x0] > 0 ? 1 : 0;
                        }
                      }
                    });
  return out;
}

bool mask_within(const std::vector<uint8_t>& inner, const std::vector<uint8_t>& outer) {
  for (size_t i = 0; i < inner.size(); ++i)
    if (inner[i] && !outer[i]) return false;
  return true;
}

void apply_attached_shadow(const std::vector<uint8_t>& attached, ImageF& visibility) {
  for (size_t i = 0; i < attached.size(); ++i)
    if (attached[i]) visibility.data[i] = 0.0f;
}

ImageF with_unmeasured_from(const ImageF& test, const ImageF& ref,
                            const std::vector<uint8_t>& measured) {
  ImageF out = test;
  const size_t nc = static_cast<size_t>(out.channels);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, measured.size(), 16384),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i != r.end(); ++i)
                        if (!measured[i])
                          for (size_t c = 0; c < nc; ++c)
                            out.data[i * nc + c] = ref.data[i * nc + c];
                    });
  return out;
}

std::vector<uint8_t> soft_union_of(const ImageF& visibility, const Regions& regions) {
  std::vector<uint8_t> mask = penumbra_mask(visibility);
  const std::vector<uint8_t>& penumbra = regions.mask("penumbra");
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = uint8_t(mask[i] | penumbra[i]);
  return mask_and(std::move(mask), regions.measured);
}

}  // namespace sb::metrics

#include "reference/uniform_trace.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <glm/glm.hpp>

#include "reference/embree_scene.h"
#include "reference/exact_visibility.h"
#include "reference/pixel_rays.h"

namespace sb::reference::detail {

using core::ImageF;

namespace {

// The pixels [x0, x1) × [y0, y1) that one proof tries to settle at once.
struct Tile {
  int x0, x1, y0, y1;
  int area() const { return (x1 - x0) * (y1 - y0); }
};
constexpr int kTile = 8;

// Whether one walk proves every covered pixel of the tile lit (`lit`) or
// dark (ExactVisibility::sees_whole_light_from_all,
// hides_whole_light_from_all): then they are set as proven pixels are, and
// none traces a ray.
bool tile_proven(const Tile& tile, bool lit, const RaySetup& setup,
                 const ExactVisibility& whole_light, PixelRays& rays, UniformImages& out) {
  const ImageF& positions = setup.positions;
  const size_t width = size_t(positions.width);
  std::vector<ExactVisibility::ProofPoint> points;
  std::vector<size_t> pixels;
  points.reserve(size_t(tile.area()));
  pixels.reserve(size_t(tile.area()));
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x) {
      const size_t pix = size_t(y) * width + size_t(x);
      if (!covered(positions, pix)) continue;
      rays.start(pix);
      const float* p = &positions.data[pix * 4];
      points.push_back(
          {glm::dvec3(p[0], p[1], p[2]), glm::dvec3(rays.origin()), glm::dvec3(rays.normal())});
      pixels.push_back(pix);
    }
  if (!(lit ? whole_light.sees_whole_light_from_all(points)
            : whole_light.hides_whole_light_from_all(points)))
    return false;
  const float stop_bound = float(stop_rms_bound(setup.layout.spp));
  for (size_t pix : pixels) {
    out.visibility.data[pix] = lit ? 1.0f : 0.0f;
    out.stop_bound.data[pix] = stop_bound;
    out.settled[pix] = Settled::Proven;
  }
  return true;
}

}  // namespace

UniformImages trace_uniform(const RaySetup& setup, const ExactVisibility* whole_light) {
  const Layout& layout = setup.layout;
  const ImageF& positions = setup.positions;
  const int width = positions.width, height = positions.height;
  const size_t spp = size_t(layout.spp);
  // The first packet: as PixelRays::trace splits the samples, so the rays
  // traced are the same whether or not the rest follow.
  const size_t first = std::min(spp, size_t(ShadowPacket::kLanes));
  std::vector<uint32_t> all(spp);
  for (size_t i = 0; i < spp; ++i) all[i] = uint32_t(i);
  const float stop_bound = float(stop_rms_bound(layout.spp));

  UniformImages out{ImageF(width, height, 1, 1.0f), ImageF(width, height, 1, 0.0f),
                    ImageF(width, height, 1, 0.0f),
                    std::vector<Settled>(positions.pixel_count(), Settled::Unknown)};
  tbb::parallel_for(
      tbb::blocked_range2d<int>(0, height, 8, 0, width, 8),
      [&](const tbb::blocked_range2d<int>& tile) {
        FtzDazScope ftz;
        PixelRays rays(setup);
        std::vector<uint8_t> reached(spp), visible(spp);
        const auto trace_tile = [&](const Tile& t) {
          // Whether the last pixel was proven lit: then this one likely is
          // too, and the proof alone, before any ray, settles it.
          bool lit_before = false;
          for (int y = t.y0; y < t.y1; ++y)
            for (int x = t.x0; x < t.x1; ++x) {
              const size_t pix = size_t(y) * size_t(width) + size_t(x);
              if (!covered(positions, pix)) continue;  // V = 1, error 0 preset
              rays.start(pix);
              const float* p = &positions.data[pix * 4];
              const glm::dvec3 surface(p[0], p[1], p[2]);
              const glm::dvec3 origin(rays.origin()), normal(rays.normal());
              const auto proven = [&](bool lit) {
                out.visibility.data[pix] = lit ? 1.0f : 0.0f;
                out.stop_bound.data[pix] = stop_bound;
                out.settled[pix] = Settled::Proven;
                lit_before = lit;
              };
              bool sees_failed = false;
              if (whole_light != nullptr && lit_before) {
                if (whole_light->sees_whole_light(surface, origin, normal)) {
                  proven(true);
                  continue;
                }
                sees_failed = true;
              }
              lit_before = false;
              rays.trace(all.data(), first, reached.data());
              size_t count = 0;
              for (size_t i = 0; i < first; ++i) count += reached[i];
              if (whole_light != nullptr && (count == 0 || count == first)) {
                const bool lit = count == first;
                if (lit ? !sees_failed && whole_light->sees_whole_light(surface, origin, normal)
                        : whole_light->hides_whole_light(surface, origin, normal)) {
                  proven(lit);
                  continue;
                }
                out.settled[pix] = Settled::Unproven;
              }
              rays.trace(all.data() + first, spp - first, reached.data() + first);
              count = 0;
              for (size_t i = 0; i < spp; ++i) {
                visible[layout.order[i].cell] = reached[i];
                count += reached[i];
              }
              out.visibility.data[pix] = float(double(count) / double(spp));
              out.std_error.data[pix] = float(standard_error(visible.data(), layout));
              if (count == 0 || count == spp) out.stop_bound.data[pix] = stop_bound;
            }
        };
        // A tile whose first covered pixel's first packet agrees tries the
        // proof that packet allows on all of it at once (one walk for 64
        // pixels); a tile not settled so traces and proves its pixels one by
        // one. (Smaller tiles, tried after a failure, cost more than they
        // saved on the sphere grid: their proofs failed 70-80 % of the time.)
        const auto settle = [&](const Tile& t) {
          if (whole_light != nullptr)
            for (int y = t.y0; y < t.y1; ++y)
              for (int x = t.x0; x < t.x1; ++x) {
                const size_t pix = size_t(y) * size_t(width) + size_t(x);
                if (!covered(positions, pix)) continue;
                rays.start(pix);
                rays.trace(all.data(), first, reached.data());
                size_t count = 0;
                for (size_t i = 0; i < first; ++i) count += reached[i];
                if ((count == first || count == 0) &&
                    tile_proven(t, count == first, setup, *whole_light, rays, out))
                  return;
                y = t.y1;  // only the first covered pixel
                break;
              }
          trace_tile(t);
        };
        // Tiles of kTile × kTile pixels on a grid of the image's.
        for (int ty = tile.rows().begin(); ty < tile.rows().end();
             ty = std::min(tile.rows().end(), (ty / kTile + 1) * kTile))
          for (int tx = tile.cols().begin(); tx < tile.cols().end();
               tx = std::min(tile.cols().end(), (tx / kTile + 1) * kTile))
            settle(Tile{tx, std::min(tile.cols().end(), (tx / kTile + 1) * kTile), ty,
                        std::min(tile.rows().end(), (ty / kTile + 1) * kTile)});
      });
  return out;
}

}  // namespace sb::reference::detail

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

// Pixels a side of a proof tile. On the 800×600 sphere grid 4 took fewer
// instructions than 8 (9.84 G against 10.10 G for BM_Reference/spp:64,
// under callgrind): the smaller shaft is proven whole more often and keeps
// shorter candidate lists; 8 with 4 inside it (lists filtered from the
// larger tile's) took 10.28 G.
constexpr int kTile = 4;

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
      [&](const tbb::blocked_range2d<int>& range) {
        FtzDazScope ftz;
        PixelRays rays(setup);
        std::vector<uint8_t> reached(spp), visible(spp);
        std::vector<size_t> pixels;
        std::vector<ExactVisibility::ProofPoint> points;
        ExactVisibility::TileCandidates lit_candidates, dark_candidates;
        bool lit_walked = false, dark_walked = false;
        // The tile's candidates for each proof (exact_visibility.h), found
        // when a pixel first asks for them.
        const auto lit_of_tile = [&]() -> const ExactVisibility::TileCandidates& {
          if (!lit_walked) whole_light->sees_candidates(points, lit_candidates);
          lit_walked = true;
          return lit_candidates;
        };
        const auto dark_of_tile = [&]() -> const ExactVisibility::TileCandidates& {
          if (!dark_walked) whole_light->hides_candidates(points, dark_candidates);
          dark_walked = true;
          return dark_candidates;
        };
        const auto set_proven = [&](size_t pix, bool lit) {
          out.visibility.data[pix] = lit ? 1.0f : 0.0f;
          out.stop_bound.data[pix] = stop_bound;
          out.settled[pix] = Settled::Proven;
        };
        // A tile of kTile × kTile pixels on a grid of the image's.
        const auto settle = [&](int x0, int x1, int y0, int y1) {
          pixels.clear();
          points.clear();
          lit_walked = dark_walked = false;
          for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
              const size_t pix = size_t(y) * size_t(width) + size_t(x);
              if (!covered(positions, pix)) continue;  // V = 1, error 0 preset
              pixels.push_back(pix);
              if (whole_light == nullptr) continue;
              rays.start(pix);
              const float* p = &positions.data[pix * 4];
              points.push_back({glm::dvec3(p[0], p[1], p[2]), glm::dvec3(rays.origin()),
                                glm::dvec3(rays.normal())});
            }
          // The first pixel's first packet agreeing, the proof it allows is
          // tried on the whole tile at once.
          if (whole_light != nullptr && !pixels.empty()) {
            rays.start(pixels[0]);
            rays.trace(all.data(), first, reached.data());
            size_t count = 0;
            for (size_t i = 0; i < first; ++i) count += reached[i];
            if ((count == first && lit_of_tile().whole) || (count == 0 && dark_of_tile().whole)) {
              for (size_t pix : pixels) set_proven(pix, count == first);
              return;
            }
          }
          // Whether the last pixel was proven lit: then this one likely is
          // too, and the proof alone, before any ray, settles it.
          bool lit_before = false;
          for (size_t k = 0; k < pixels.size(); ++k) {
            const size_t pix = pixels[k];
            rays.start(pix);
            bool sees_failed = false;
            if (whole_light != nullptr && lit_before) {
              if (whole_light->sees_whole_light(points[k], lit_of_tile())) {
                set_proven(pix, true);
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
              if (lit ? !sees_failed && whole_light->sees_whole_light(points[k], lit_of_tile())
                      : whole_light->hides_whole_light(points[k], dark_of_tile())) {
                set_proven(pix, lit);
                lit_before = lit;
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
        const auto next = [](int i, int end) { return std::min(end, (i / kTile + 1) * kTile); };
        for (int y = range.rows().begin(); y < range.rows().end(); y = next(y, range.rows().end()))
          for (int x = range.cols().begin(); x < range.cols().end();
               x = next(x, range.cols().end()))
            settle(x, next(x, range.cols().end()), y, next(y, range.rows().end()));
      });
  return out;
}

}  // namespace sb::reference::detail

#include "cascaded/virtual_pages.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numeric>

#include "cascaded/cascade_fit.h"

namespace sb::techniques::cascaded {

glm::mat4 Clipmap::pages_view_projection(int level, int row, int col0, int cols) const {
  const ClipLevel& l = levels[size_t(level)];
  const float page = float(page_size) * l.texel;
  const float x0 = l.lo.x + float(col0) * page, y0 = l.lo.y + float(row) * page;
  return glm::ortho(x0, x0 + float(cols) * page, y0, y0 + page, near_depth, far_depth) * view;
}

Clipmap plan_clipmap(const glm::vec3& eye, float view_radius, float pixel_angle,
                     const glm::vec3& direction, const std::array<glm::vec3, 8>& caster_corners,
                     const std::array<glm::vec3, 8>& scene_corners, int virtual_size, int page_size,
                     int levels) {
  Clipmap c;
  c.view = light_rotation(direction);
  c.eye = eye;
  c.pixel_angle = pixel_angle;
  c.page_size = page_size;
  c.pages_per_side = virtual_size / page_size;
  c.virtual_size = c.pages_per_side * page_size;
  const auto depth = [&](const glm::vec3& p) { return -(c.view * glm::vec4(p, 1.0f)).z; };
  float lo = 1e30f, hi = -1e30f;
  for (const glm::vec3& p : caster_corners) lo = std::min(lo, depth(p));
  for (const glm::vec3& p : scene_corners) hi = std::max(hi, depth(p));
  const float margin = 1e-3f * std::max(hi - lo, 1e-3f);
  c.near_depth = lo - margin;
  c.far_depth = hi + margin;
  // A power of two: the extents change only by whole factors of 2 as the
  // view's depth range changes, never by a little each frame.
  const double cover =
      std::max(double(view_radius), double(view_radius) * pixel_angle * c.virtual_size * 0.5);
  const double coarsest = std::exp2(std::ceil(std::log2(std::max(cover, 1e-6))));
  const glm::vec2 e = glm::vec2(c.view * glm::vec4(eye, 1.0f));
  for (int l = 0; l < levels; ++l) {
    const double half = coarsest * std::exp2(double(l - (levels - 1)));
    ClipLevel level;
    level.texel = float(2.0 * half / c.virtual_size);
    const double page = double(page_size) * level.texel;
    const glm::dvec2 centre = glm::round(glm::dvec2(e) / page) * page;
    level.lo = glm::vec2(centre - half);
    c.levels.push_back(level);
  }
  return c;
}

Clipmap view_clipmap(const glm::mat4& view, const glm::mat4& projection, int height,
                     const glm::vec3& direction, const std::array<glm::vec3, 8>& caster_corners,
                     const std::array<glm::vec3, 8>& scene_corners, int virtual_size, int page_size,
                     int levels) {
  const float tan_y = 1.0f / projection[1][1], aspect = projection[1][1] / projection[0][0];
  const float far_plane = projection[3][2] / (projection[2][2] + 1.0f);
  float far_depth = 0.0f;
  for (const glm::vec3& c : scene_corners)
    far_depth = std::max(far_depth, -(view * glm::vec4(c, 1.0f)).z);
  far_depth = std::min(far_depth, far_plane);
  const float radius = far_depth * std::sqrt(1.0f + tan_y * tan_y * (1.0f + aspect * aspect));
  const glm::vec3 eye = glm::vec3(glm::inverse(view)[3]);
  return plan_clipmap(eye, radius, 2.0f * tan_y / float(height), direction, caster_corners,
                      scene_corners, virtual_size, page_size, levels);
}

glm::vec2 level_texel(const Clipmap& c, int l, const glm::vec3& world) {
  const ClipLevel& level = c.levels[size_t(l)];
  return (glm::vec2(c.view * glm::vec4(world, 1.0f)) - level.lo) / level.texel;
}

int pixel_level(const Clipmap& c, const glm::vec3& world, int margin) {
  const int last = int(c.levels.size()) - 1;
  const float footprint = glm::distance(world, c.eye) * c.pixel_angle;
  int l = int(std::clamp(std::floor(std::log2(footprint / c.levels[0].texel)), 0.0f, float(last)));
  for (; l < last; ++l) {
    const glm::vec2 t = level_texel(c, l, world);
    if (t.x >= float(margin) && t.y >= float(margin) && t.x < float(c.virtual_size - margin) &&
        t.y < float(c.virtual_size - margin))
      break;
  }
  return l;
}

PageAllocation allocate_pages(const std::vector<std::uint32_t>& marks, int levels,
                              int pages_per_side, int pool_side) {
  PageAllocation a;
  const int per_level = pages_per_side * pages_per_side;
  const int capacity = pool_side * pool_side;
  a.table.assign(marks.size(), kNoPage);
  std::vector<int> marked;
  for (int i = 0; i < int(marks.size()); ++i)
    if (marks[size_t(i)] != kUnmarked) marked.push_back(i);
  a.marked = int(marked.size());
  if (a.marked > capacity) {
    const int coarsest_start = (levels - 1) * per_level;
    std::stable_sort(marked.begin(), marked.end(), [&](int x, int y) {
      const bool cx = x >= coarsest_start, cy = y >= coarsest_start;
      if (cx != cy) return cx;
      return marks[size_t(x)] < marks[size_t(y)];
    });
    for (size_t i = size_t(capacity); i < marked.size(); ++i)
      a.table[size_t(marked[i])] = kDroppedPage;
    marked.resize(size_t(capacity));
    std::sort(marked.begin(), marked.end());
  }
  a.allocated = int(marked.size());
  a.dropped = a.marked - a.allocated;
  for (int slot = 0; slot < a.allocated; ++slot) {
    const int page = marked[size_t(slot)];
    a.table[size_t(page)] = slot;
    const int level = page / per_level, row = (page % per_level) / pages_per_side,
              col = page % pages_per_side;
    PageRun* last = a.runs.empty() ? nullptr : &a.runs.back();
    // Extends the last run when the page is its next column and the slot
    // its next one in the same pool row.
    if (last && last->level == level && last->row == row && last->col0 + last->count == col &&
        last->slot0 + last->count == slot && slot % pool_side != 0)
      ++last->count;
    else
      a.runs.push_back({level, row, col, 1, slot});
  }
  return a;
}

}  // namespace sb::techniques::cascaded

#pragma once
// The CPU side of virtual_shadow_map: the clipmap levels of the virtual map
// (orthographic views from the sun, each twice the extent of the one
// before, centred on the camera), and the allocation of the pages a frame
// marked to slots of the physical pool, with the overflow rule.
//
// Plain CPU code, no GL; called in render(), every frame, inside the timed
// pass. units: world units; texels and pages are counted from the level's
// low corner (x right, y up in the sun's frame, cascade_fit's
// light_rotation).
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace sb::techniques::cascaded {

// One clipmap level: a square of virtual_size² texels in the sun's frame.
struct ClipLevel {
  glm::vec2 lo{0.0f};  // the level's low corner (light frame x, y)
  float texel = 0.0f;  // world units per texel
};

// All the levels of a frame. Every level shares the light's frame (`view`)
// and one depth range along the light, so a window depth means the same
// distance in every level and every page.
struct Clipmap {
  glm::mat4 view{1.0f};  // light_rotation(direction)
  float near_depth = 0.0f, far_depth = 1.0f;
  int virtual_size = 0;  // texels per level side: pages_per_side × page_size
  int page_size = 0;
  int pages_per_side = 0;
  std::vector<ClipLevel> levels;
  glm::vec3 eye{0.0f};       // the camera's position
  float pixel_angle = 0.0f;  // a pixel's footprint per unit distance from the eye
  // The orthographic view-projection of the rectangle of pages
  // [col0, col0 + cols) × [row, row + 1) of `level` (window depths in [0, 1]
  // over near..far, as every page).
  glm::mat4 pages_view_projection(int level, int row, int col0, int cols) const;
};

// The levels for a camera at `eye` whose visible scene lies within
// `view_radius` of it, under the sun travelling along `direction`. The
// coarsest level (levels − 1) has a half extent of at least `view_radius`
// and of `view_radius × pixel_angle × virtual_size / 2` (its texels no
// smaller than the farthest pixel's footprint), rounded up to a power of
// two; each finer level halves it. Each level's centre is snapped to whole
// pages in the sun's frame (the page grid stays put in the world while the
// camera moves within a page). The depth range runs from the nearest of
// `caster_corners` along the light to the farthest of `scene_corners`.
Clipmap plan_clipmap(const glm::vec3& eye, float view_radius, float pixel_angle,
                     const glm::vec3& direction, const std::array<glm::vec3, 8>& caster_corners,
                     const std::array<glm::vec3, 8>& scene_corners, int virtual_size, int page_size,
                     int levels);

// The same for a camera given as the harness gives it (a world-to-view
// matrix, a glm::perspective projection, the image's height in pixels): the
// eye, pixel_angle = 2·tan(fov_y / 2) / height, and the view radius, the
// eye's distance to the corners of the view frustum cut at the scene's
// farthest depth along the view (no farther than the far plane).
Clipmap view_clipmap(const glm::mat4& view, const glm::mat4& projection, int height,
                     const glm::vec3& direction, const std::array<glm::vec3, 8>& caster_corners,
                     const std::array<glm::vec3, 8>& scene_corners, int virtual_size, int page_size,
                     int levels);

// The level a pixel at `world` looks up, as the shaders choose it (GLSL
// pixel_level): the coarsest whose texel is no larger than the pixel's
// footprint (distance × pixel_angle), or the first coarser one whose square
// holds the pixel `margin` texels in from its sides.
int pixel_level(const Clipmap& c, const glm::vec3& world, int margin);
// A point's texel coordinates in level l.
glm::vec2 level_texel(const Clipmap& c, int l, const glm::vec3& world);

// The mark buffer's value for an unmarked page; a marked page holds the
// smallest camera distance (as float bits: non-negative floats order as
// their bits) among the pixels that marked it.
inline constexpr std::uint32_t kUnmarked = 0xffffffffu;
// Page-table entries besides a slot (>= 0).
inline constexpr int kNoPage = -1;       // not marked
inline constexpr int kDroppedPage = -2;  // marked, but the pool had no slot for it

// One draw into the pool: `count` pages of one level's row, consecutive
// there and in the pool (slots slot0 … slot0 + count − 1, in one pool row).
struct PageRun {
  int level = 0, row = 0, col0 = 0, count = 0, slot0 = 0;
};

struct PageAllocation {
  // Per page (level-major, then row, then column): its slot, kNoPage or kDroppedPage.
  std::vector<int> table;
  std::vector<PageRun> runs;
  int marked = 0;
  int allocated = 0;
  int dropped = 0;
};

// Allocates slots of a pool of `pool_side`² pages to the marked pages
// (`marks`: per page as in `table`, kUnmarked or the smallest distance).
// The overflow rule, when more pages are marked than the pool holds: the
// coarsest level's pages first (every pixel also marks its page there: they
// are the fallback), then the others nearest first by their smallest camera
// distance (ties: lower page index); the rest are dropped. Slots are given
// in page order (level, row, column), so that pages consecutive in a row
// get consecutive slots and draw as one run.
PageAllocation allocate_pages(const std::vector<std::uint32_t>& marks, int levels,
                              int pages_per_side, int pool_side);

}  // namespace sb::techniques::cascaded

#pragma once
// CPU-side scene description shared by the rasteriser, the techniques and the
// ray-traced reference. Units are arbitrary but consistent; +y is up.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sb::core {

// An 8-bit RGBA image. Row 0 is texture coordinate v = 0 (glTF's top row);
// every sampler in the project reads it nearest-texel with wrap-around, so
// the rasteriser and the ray tracer see the same holes.
struct TextureImage {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4
};

enum class AlphaMode { Opaque, Mask };

// The smooth surface a mesh tessellates, for the ray-traced reference only:
// the rasteriser, the G-buffer and every technique use the triangles, and the
// reference, when a mesh has a shape, occludes with the shape instead (so its
// error measures the distance to the smooth surface). Only convex shapes: the
// reference's self-shadowing rule relies on it (reference/reference.h).
struct AnalyticShape {
  enum class Kind : uint8_t { None, Sphere };
  Kind kind = Kind::None;
  glm::vec3 center{0.0f};  // Sphere
  float radius = 0.0f;     // Sphere

  static AnalyticShape sphere(glm::vec3 center, float radius) {
    return {Kind::Sphere, center, radius};
  }
  bool has() const { return kind != Kind::None; }
};
const char* to_string(AnalyticShape::Kind kind);  // "none", "sphere"

// The texel alpha (0..1) at `uv`, nearest texel, wrapping: texel index
// floor(u * width) mod width, as GL_NEAREST + GL_REPEAT computes it.
float sample_alpha(const TextureImage& texture, glm::vec2 uv);

struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // per vertex, for shading only
  std::vector<glm::vec2> uvs;      // per vertex, or empty when untextured
  std::vector<uint32_t> indices;   // triangle list, counter-clockwise = front
  glm::vec3 albedo{0.8f};
  int base_color_texture = -1;  // into Scene::textures; rgb multiplies albedo, a is coverage
  // Mask: texels whose alpha is below alpha_cutoff are holes, for the camera,
  // for every shadow pass that honours masks, and for the reference.
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;
  // Receivers that never occlude the light (a ground plane under everything)
  // are left out of every caster pass and of the reference's ray tracing.
  bool casts_shadow = true;
  // Thin surfaces seen and casting from both sides (leaves): never culled.
  bool double_sided = false;
  // For the reference: the smooth shape these triangles approximate, or none.
  AnalyticShape analytic;

  size_t triangle_count() const { return indices.size() / 3; }
  bool alpha_tested() const { return alpha_mode == AlphaMode::Mask && base_color_texture >= 0; }
};

// The scene's one light: a rectangle, a segment or a point at a place (a
// local light), or the sun.
//
// A local light is a rectangle facing `target`. A point on it is
// center + (2s-1)*half_u + (2t-1)*half_v for (s,t) in [0,1]^2.
//
// The sun (`sun` true) is a directional light at infinity: a disk of
// `angular_diameter` radians, seen from every point in the direction
// to_sun(). Its V at a point is the visible fraction of that disk as
// projected onto a plane perpendicular to to_sun() (the gnomonic
// projection, which both references and every sun technique use; it
// weighs directions by 1/cos³ of their angle from the axis, so it differs
// from the fraction of solid angle by under 3r²/2 for a disk of angular
// radius r: 3e-5 for the real sun). `center` is then only a place
// on the sun's side for code that wants one (a light frustum's eye), and
// `target` where the light looks; half_u and half_v span the disk's
// circumscribed square as seen at `center`'s distance, so that width()
// is the disk's diameter there.
struct AreaLight {
  glm::vec3 center{0.0f, 10.0f, 0.0f};
  glm::vec3 half_u{0.5f, 0.0f, 0.0f};
  glm::vec3 half_v{0.0f, 0.0f, 0.5f};
  glm::vec3 target{0.0f};  // where the light looks; used by shadow-map projections
  float intensity = 1.0f;
  bool sun = false;
  float angular_diameter = 0.0f;  // radians; the sun's only

  glm::vec3 point(float s, float t) const {
    return center + (2.0f * s - 1.0f) * half_u + (2.0f * t - 1.0f) * half_v;
  }
  // The way the light travels: from center towards target (for the sun,
  // the same everywhere).
  glm::vec3 direction() const { return glm::normalize(target - center); }
  // Unit, from any point towards the sun.
  glm::vec3 to_sun() const { return -direction(); }
  float width() const { return 2.0f * glm::length(half_u); }
  float height() const { return 2.0f * glm::length(half_v); }
  bool is_sun() const { return sun; }
  // A linear light: a segment, one of the two sizes zero (`light.size:
  // [w, 0]` or `[0, h]`). A point light has both zero. Neither is the sun.
  bool is_segment() const { return !sun && (width() > 0.0f) != (height() > 0.0f); }
  bool is_point() const { return !sun && !(width() > 0.0f) && !(height() > 0.0f); }
  // A segment's end points (s = 0 and s = 1 along its non-zero axis).
  glm::vec3 segment_end(float s) const {
    const glm::vec3 half = width() > 0.0f ? half_u : half_v;
    return center + (2.0f * s - 1.0f) * half;
  }
};

// The sun against the plane through the origin with normal n: 1 when every
// direction of its disk points to n's side (n·d > 0), -1 when every one
// points away, 0 when the plane cuts the disk. For the sun only.
int sun_side(const AreaLight& sun, const glm::dvec3& n);

struct Camera {
  glm::vec3 eye{0.0f, 5.0f, 10.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_degrees = 45.0f;
  float near_plane = 0.1f;
  float far_plane = 100.0f;

  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
};

struct Bounds {
  glm::vec3 lo{1e30f};
  glm::vec3 hi{-1e30f};
  void extend(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void extend(const Bounds& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return lo.x > hi.x; }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
  float radius() const { return 0.5f * glm::length(hi - lo); }
};

// A file a scene was built from, as its builder read it (a glTF file, its
// buffers and images): what a job's identity holds instead of the path that
// named it, so that an edited file reruns and a moved one resumes.
struct InputFile {
  std::string path;  // as opened, for messages
  // Its place relative to the file a parameter named: "" for that file
  // itself, else the URI it was read by, relative to that file's folder.
  std::string name;
  std::string sha256;  // of its bytes
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<TextureImage> textures;
  AreaLight light;
  Camera camera;
  glm::vec3 ambient{0.15f};
  // The files it was built from, in the order first read (none for a
  // generated scene).
  std::vector<InputFile> inputs;

  size_t triangle_count() const;
  size_t caster_triangle_count() const;
  // Casters the reference traces as their analytic shape.
  size_t analytic_caster_count() const;
  // Of the vertices some triangle references (unreferenced ones are ignored).
  Bounds bounds() const;
  Bounds caster_bounds() const;
};

// Near and far planes that hold `bounds` seen from the camera's eye: far just
// past the farthest corner, near half way to the box (or far / 10^4 from
// inside it). For a camera moved by a config, whose file's planes were
// fitted to another eye.
void fit_clip_planes(Camera& camera, const Bounds& bounds);

}  // namespace sb::core

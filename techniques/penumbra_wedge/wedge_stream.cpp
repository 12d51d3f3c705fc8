#include "penumbra_wedge/wedge_stream.h"

#include <cstddef>

namespace sb::techniques::penumbra_wedge {

void WedgeStream::create() {
  vertices_ = gl::make_stream_buffer();
  indices_ = gl::make_stream_buffer();
  records_ = gl::make_stream_buffer();
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  vao_ = gl::VertexArray(vao);
  glVertexArrayVertexBuffer(vao, 0, vertices_.get(), 0, sizeof(WedgeVertex));
  glVertexArrayElementBuffer(vao, indices_.get());
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(WedgeVertex, position));
  glVertexArrayAttribBinding(vao, 0, 0);
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayAttribIFormat(vao, 1, 1, GL_UNSIGNED_INT, offsetof(WedgeVertex, wedge));
  glVertexArrayAttribBinding(vao, 1, 0);
}

void WedgeStream::upload(const WedgeBatch& batch) {
  gl::set_buffer_data(vertices_, GLsizeiptr(batch.vertices.size() * sizeof(WedgeVertex)),
                      batch.vertices.data(), GL_STREAM_DRAW);
  gl::set_buffer_data(indices_, GLsizeiptr(batch.indices.size() * sizeof(uint32_t)),
                      batch.indices.data(), GL_STREAM_DRAW);
  gl::set_buffer_data(records_, GLsizeiptr(batch.wedges.size() * sizeof(WedgeRecord)),
                      batch.wedges.data(), GL_STREAM_DRAW);
}

void WedgeStream::bind() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, records_.get());
  glBindVertexArray(vao_.get());
}

void WedgeStream::draw(const IndexRange& range) {
  if (range.count == 0) return;
  glDrawElements(GL_TRIANGLES, GLsizei(range.count), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(size_t(range.first) * sizeof(uint32_t)));
}

void set_wedge_uniforms(const gl::Program& program, const LightFrame& frame,
                        const glm::mat4& view_projection) {
  program.set("view_projection", view_projection);
  program.set("light_center", frame.center);
  program.set("light_u", frame.u);
  program.set("light_v", frame.v);
  program.set("light_n", frame.n);
  program.set("half_size", glm::vec2(frame.half_width, frame.half_height));
  program.set("orientation", kLoopOrientation);
  program.set("half_wedge_tolerance", kHalfWedgeTolerance);
}

const char* const kWedgeVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in uint wedge;
uniform mat4 view_projection;
flat out uint v_wedge;
void main() {
  v_wedge = wedge;
  gl_Position = view_projection * vec4(position, 1.0);
}
)";

const char* const kWedgeGlsl = R"(
flat in uint v_wedge;
struct Wedge {
  vec4 a, b;  // the edge's ends in the light's frame
  vec4 centre_plane, first_bound, second_bound;
};
layout(std430, binding = 0) readonly buffer Wedges { Wedge wedges[]; };
uniform vec3 light_center;
uniform vec3 light_u;
uniform vec3 light_v;
uniform vec3 light_n;
uniform vec2 half_size;
uniform float orientation;  // +1 or −1: how silhouette loops wind seen from a shadowed point
uniform float half_wedge_tolerance;

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

void swap_ends(inout vec2 a, inout vec2 b, inout float s) {
  vec2 t = a;
  a = b;
  b = t;
  s = -s;
}

// The wedge's edge projected from the world point `world` onto the light's
// plane (light frame, centre at the origin), cut at a local near plane just
// in front of the point: only the edge's part between the point and the
// light can cut its view (and beyond, the projection would flip). False when
// Lengyel's half-wedge test or the cut leaves nothing, or the projected edge
// misses the light (then it adds nothing).
bool project_edge(vec3 world, out vec2 a, out vec2 b) {
  Wedge w = wedges[v_wedge];
  vec4 p4 = vec4(world, 1.0);
  vec3 d = world - light_center;
  // Lengyel: one plane decides the half, one more whether p is inside it.
  float bound = dot(w.centre_plane, p4) < 0.0 ? dot(w.first_bound, p4) : dot(w.second_bound, p4);
  if (bound < -half_wedge_tolerance * length(d)) return false;
  vec3 p = vec3(dot(d, light_u), dot(d, light_v), dot(d, light_n));
  float z_near = p.z * (1.0 - 1e-4);
  vec3 A = w.a.xyz, B = w.b.xyz;
  if (A.z >= z_near && B.z >= z_near) return false;
  if (A.z > z_near) A = mix(A, B, (A.z - z_near) / (A.z - B.z));
  if (B.z > z_near) B = mix(B, A, (B.z - z_near) / (B.z - A.z));
  a = p.xy + (A.xy - p.xy) * (p.z / (p.z - A.z));
  b = p.xy + (B.xy - p.xy) * (p.z / (p.z - B.z));
  return !(max(a.x, b.x) <= -half_size.x || min(a.x, b.x) >= half_size.x ||
           max(a.y, b.y) <= -half_size.y || min(a.y, b.y) >= half_size.y);
}

// The fragment's edge, projected (project_edge), as a counter-clockwise pair
// about the centre, with the sign s of its fan term. False: it adds nothing.
bool fan_edge(vec3 world, out vec2 a, out vec2 b, out float s) {
  if (!project_edge(world, a, b)) return false;
  s = orientation;
  if (cross2(a, b) < 0.0) swap_ends(a, b, s);
  return true;
}

// The light's centre on the projected edge, between its ends (within 1e-2
// of the light's half-size): the sector is a half-plane on either side, and
// rounding decides which; swap_ends gives the other. The band is that wide
// because the stencil's own test (depth-buffer precision and the volumes'
// polygon offset, magnified by the projection) was measured to disagree
// with the shader's this far on the sphere grid.
bool centre_on_edge(vec2 a, vec2 b) {
  vec2 e = b - a;
  float t = -dot(a, e) / max(dot(e, e), 1e-30);
  return t > 0.0 && t < 1.0 && length(a + t * e) <= 1e-2 * max(half_size.x, half_size.y);
}

// The piece of segment a b inside the box [lo, hi] (Liang–Barsky).
bool clip_segment(vec2 a, vec2 b, vec2 lo, vec2 hi, out vec2 p, out vec2 q) {
  float t0 = 0.0, t1 = 1.0;
  vec2 d = b - a;
  for (int k = 0; k < 2; ++k) {
    if (abs(d[k]) < 1e-30) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    float ta = (lo[k] - a[k]) / d[k], tb = (hi[k] - a[k]) / d[k];
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  p = a + t0 * d;
  q = a + t1 * d;
  return t0 <= t1;
}

// The light's corners in counter-clockwise order, each after the side of the
// same number: right (x = +w), top, left, bottom.
const vec2 kCorner[4] = vec2[4](vec2(1, 1), vec2(-1, 1), vec2(-1, -1), vec2(1, -1));

// Where the ray from the centre through p leaves the light, and on which side.
vec2 boundary_exit(vec2 p, out int side) {
  vec2 ap = max(abs(p), vec2(1e-30));
  if (half_size.x * ap.y <= half_size.y * ap.x) {
    side = p.x > 0.0 ? 0 : 2;
    return p * (half_size.x / ap.x);
  }
  side = p.y > 0.0 ? 1 : 3;
  return p * (half_size.y / ap.y);
}

// The fan term's region: the light in the sector from the centre through a,
// counter-clockwise to b (cross(a, b) >= 0), beyond the segment a b. Only
// the segment's piece p0 p1 inside the light matters (elsewhere the light
// ends before the segment), so the region is the light within the cone of
// that piece, the boundary walked from its exit e0 to e1 counter-clockwise,
// less the triangle (centre, p0, p1): in fan form about the centre,
//   area = ½ [cross(e0, k1) + ... + cross(k_last, e1) − cross(p0, p1)],
// with no clipping of polygons.
float beyond_area(vec2 a, vec2 b) {
  vec2 p0, p1;
  if (!clip_segment(a, b, -half_size, half_size, p0, p1)) return 0.0;
  int s0, s1;
  vec2 cur = boundary_exit(p0, s0), end = boundary_exit(p1, s1);
  float twice = -cross2(p0, p1);
  for (int step = 0; step < 4; ++step)
    if (s0 != s1) {
      vec2 k = kCorner[s0] * half_size;
      twice += cross2(cur, k);
      cur = k;
      s0 = (s0 + 1) % 4;
    }
  return 0.5 * (twice + cross2(cur, end));
}
)";

}  // namespace sb::techniques::penumbra_wedge

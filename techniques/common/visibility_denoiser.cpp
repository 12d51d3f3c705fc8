#include "common/visibility_denoiser.h"

#include <algorithm>
#include <array>
#include <glm/gtc/matrix_inverse.hpp>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "gl/debug.h"

namespace sb::techniques {

using core::JobError;
using core::ParamSpec;

namespace {

// The clamp's window along rows: (Σv, Σv², count) over the geometry pixels
// within `radius` in x; the temporal pass sums these along y.
const char* const kWindowRowsFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D noisy;
layout(binding = 1) uniform sampler2D position;
uniform int radius;
out vec4 sums;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int last = textureSize(noisy, 0).x - 1;
  vec3 s = vec3(0.0);
  for (int i = -radius; i <= radius; ++i) {
    ivec2 q = ivec2(p.x + i, p.y);
    if (q.x < 0 || q.x > last || texelFetch(position, q, 0).w == 0.0) continue;
    float v = texelFetch(noisy, q, 0).r;
    s += vec3(v, v * v, 1.0);
  }
  sums = vec4(s, 0.0);
}
)";

const char* const kTemporalFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D noisy;
layout(binding = 1) uniform sampler2D position;
layout(binding = 2) uniform sampler2D normal;
layout(binding = 3) uniform sampler2D prev_color;
layout(binding = 4) uniform sampler2D prev_moments;
layout(binding = 5) uniform sampler2D prev_position;
layout(binding = 6) uniform sampler2D prev_normal;
layout(binding = 7) uniform sampler2D window_rows;
uniform mat4 prev_view_projection;
uniform vec3 eye;
uniform bool has_history;
uniform float alpha;
uniform float max_history;
uniform float reprojection_tolerance;
uniform bool clamp_history;
uniform int clamp_radius;
uniform float clamp_gamma;
uniform float clamp_reset;
layout(location = 0) out vec4 moments_out;
layout(location = 1) out vec4 color_out;
layout(location = 2) out vec4 position_out;
layout(location = 3) out vec4 normal_out;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(noisy, 0);
  vec4 x = texelFetch(position, p, 0);
  vec3 n = texelFetch(normal, p, 0).xyz;
  position_out = x;
  normal_out = vec4(n, 0.0);
  if (x.w == 0.0) {
    moments_out = vec4(1.0, 1.0, 1.0, 0.0);
    color_out = vec4(1.0);
    return;
  }
  float c = texelFetch(noisy, p, 0).r;

  // Reprojection: the bilinear 2x2 around where this point was, each texel
  // kept if its surface lies on this pixel's plane and faces its way.
  float kept = 0.0, h_color = 0.0;
  vec3 h_moments = vec3(0.0);  // m1, m2, length
  if (has_history) {
    vec4 clip = prev_view_projection * vec4(x.xyz, 1.0);
    if (clip.w > 0.0) {
      vec2 q = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size) - 0.5;
      ivec2 q0 = ivec2(floor(q));
      vec2 f = q - vec2(q0);
      float tolerance = reprojection_tolerance * distance(x.xyz, eye);
      for (int j = 0; j < 4; ++j) {
        ivec2 o = ivec2(j & 1, j >> 1);
        ivec2 t = q0 + o;
        if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size))) continue;
        vec4 xp = texelFetch(prev_position, t, 0);
        if (xp.w == 0.0 || abs(dot(n, xp.xyz - x.xyz)) > tolerance) continue;
        if (dot(n, texelFetch(prev_normal, t, 0).xyz) < 0.9) continue;
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        kept += w;
        h_color += w * texelFetch(prev_color, t, 0).r;
        h_moments += w * texelFetch(prev_moments, t, 0).gba;
      }
    }
  }
  float history_length = 0.0;
  if (kept > 1e-3) {
    h_color /= kept;
    h_moments /= kept;
    history_length = h_moments.z;
  }

  // The clamp: the history into this frame's local mean ± gamma·sigma; a
  // history it moves far is another shadow's (a light moved): restart.
  if (history_length > 0.0 && clamp_history) {
    vec3 s = vec3(0.0);
    for (int i = -clamp_radius; i <= clamp_radius; ++i) {
      int y = p.y + i;
      if (y >= 0 && y < size.y) s += texelFetch(window_rows, ivec2(p.x, y), 0).xyz;
    }
    float mean = s.x / s.z;
    float sigma = sqrt(max(s.y / s.z - mean * mean, 0.0));
    float clamped = clamp(h_color, mean - clamp_gamma * sigma, mean + clamp_gamma * sigma);
    float moved = clamped - h_color;
    if (abs(moved) > clamp_reset) {
      history_length = 0.0;
    } else {
      // The moments' mean moves with it; their variance stays.
      float variance = h_moments.y - h_moments.x * h_moments.x;
      h_color = clamped;
      h_moments.x += moved;
      h_moments.y = variance + h_moments.x * h_moments.x;
    }
  }

  float length = min(history_length + 1.0, max_history);
  vec2 m = vec2(c, c * c);
  float accumulated = c;
  if (history_length > 0.0) {
    float a = max(1.0 / length, alpha);
    accumulated = mix(h_color, c, a);
    m = mix(h_moments.xy, m, a);
  }
  moments_out = vec4(accumulated, m, length);
  color_out = vec4(accumulated);
}
)";

// Shared by the variance and à-trous passes: the normal weight. The
// transcendentals are what costs on llvmpipe.
const char* const kFacing = R"(
uniform float sigma_normal;

// pow(c, sigma_normal): by squarings when sigma_normal is a power of two
// (the paper's 128: 7 multiplies), else by exp2 and log2.
float facing_weight(float c) {
#ifdef NORMAL_SQUARINGS
  c = max(c, 0.0);
  for (int i = 0; i < NORMAL_SQUARINGS; ++i) c *= c;
  return c;
#else
  return exp2(sigma_normal * log2(max(c, 1e-30)));
#endif
}
)";

// The variance pass's edge-stopping weight, from the G-buffer.
const char* const kEdgeStopping = R"(
layout(binding = 1) uniform sampler2D position;
layout(binding = 2) uniform sampler2D normal;
layout(binding = 3) uniform sampler2D shading_normal;
uniform float sigma_plane;

// How much tap q's surface is this pixel's: exp(-plane distance / (sigma_plane
// × tap distance)) · pow(n·n', sigma_normal); 0 on background. Branch-free.
float geometry_weight(vec3 x, vec3 n, vec3 ns, ivec2 q) {
  vec4 xq = texelFetch(position, q, 0);
  vec3 d = xq.xyz - x;
  float plane = abs(dot(n, d)) * inversesqrt(dot(d, d) + 1e-12);
  float w = exp2(-1.442695 / sigma_plane * plane) *
            facing_weight(dot(ns, texelFetch(shading_normal, q, 0).xyz));
  return xq.w == 0.0 ? 0.0 : w;
}
)";

// The guide the à-trous passes read, one RGBA32F texel per pixel so that a
// tap is one fetch: V and its variance, the view depth (-1 on background;
// the tap's position is rebuilt along its pixel's ray, a perspective
// camera's) and the shading normal, octahedral in 2 × 12 bits.
const char* const kGuide = R"(
uniform vec3 eye;
uniform vec3 view_forward;
// The ray through pixel q's centre, reaching view depth 1 at
// ray_origin + q.x * ray_dx + q.y * ray_dy (affine in q: no matrix per tap).
uniform vec3 ray_origin;
uniform vec3 ray_dx;
uniform vec3 ray_dy;

vec2 sign_not_zero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }
// Octahedral, 12 bits a coordinate, as one float holding an integer below
// 2^24 (exact in fp32; integer targets are a slow path on llvmpipe).
float pack_normal(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 e = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * sign_not_zero(n.xy);
  vec2 i = floor(clamp(e * 0.5 + 0.5, 0.0, 1.0) * 4095.0 + 0.5);
  return i.x * 4096.0 + i.y;
}
vec3 unpack_normal(float bits) {
  float ix = floor(bits / 4096.0);
  vec2 e = vec2(ix, bits - ix * 4096.0) / 4095.0 * 2.0 - 1.0;
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * sign_not_zero(n.xy);
  return normalize(n);
}
// The world point at view depth `depth` through pixel q's centre.
vec3 along_ray(ivec2 q, float depth) {
  return eye + (ray_origin + float(q.x) * ray_dx + float(q.y) * ray_dy) * depth;
}
)";

const char* const kVarianceFragment = R"(
layout(binding = 0) uniform sampler2D source;
uniform bool spatial_only;
out vec4 guide;

// (V, m1, m2, history length) at q.
vec4 moments_at(ivec2 q) {
  if (!spatial_only) return texelFetch(source, q, 0);
  float c = texelFetch(source, q, 0).r;
  return vec4(c, c, c * c, 1.0);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(source, 0);
  vec4 x = texelFetch(position, p, 0);
  if (x.w == 0.0) {
    guide = vec4(1.0, 0.0, -1.0, 0.0);
    return;
  }
  vec4 centre = moments_at(p);
  vec3 ns = texelFetch(shading_normal, p, 0).xyz;
  float variance;
  if (centre.w >= 4.0) {
    variance = max(centre.z - centre.y * centre.y, 0.0);
  } else {
    // Short history: the moments of a 7x7 edge-stopped window.
    vec3 n = texelFetch(normal, p, 0).xyz;
    vec3 s = vec3(0.0);
    for (int dy = -3; dy <= 3; ++dy)
      for (int dx = -3; dx <= 3; ++dx) {
        ivec2 q = p + ivec2(dx, dy);
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        float w = geometry_weight(x.xyz, n, ns, q);
        s += w * vec3(moments_at(q).yz, 1.0);
      }
    float m1 = s.x / s.z;
    variance = max(s.y / s.z - m1 * m1, 0.0) * 4.0 / max(centre.w, 1.0);
  }
  guide = vec4(centre.x, variance, dot(x.xyz - eye, view_forward), pack_normal(ns));
}
)";

// FINAL: the last iteration, writing V into the technique's R32F target.
const char* const kAtrousFragment = R"(
layout(binding = 0) uniform sampler2D source;  // the guide
layout(binding = 2) uniform sampler2D normal;   // geometric, for the plane
uniform int step_size;
uniform float sigma_plane;
uniform float sigma_variance;
uniform bool copy_only;
#ifdef FINAL
layout(location = 0) out vec4 result;
#else
layout(location = 0) out vec4 result;
layout(location = 1) out vec4 history;
#endif

// The 1D B3 spline and 3-tap Gaussian weights, by arithmetic: llvmpipe
// indexes an array per pixel slowly.
float b3(int d) { return d == 0 ? 0.375 : (abs(d) == 1 ? 0.25 : 0.0625); }
float gauss(int d) { return d == 0 ? 0.5 : 0.25; }

void write(float v, float variance, vec4 centre) {
#ifdef FINAL
  result = vec4(v);
#else
  result = vec4(v, variance, centre.zw);
  history = vec4(v);
#endif
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(source, 0);
  vec4 g = texelFetch(source, p, 0);
  float v = g.x, dist = g.z;
  if (dist < 0.0 || copy_only) {
    write(dist < 0.0 ? 1.0 : v, g.y, g);
    return;
  }
  // The variance, 3x3 Gaussian-blurred over geometry pixels (the paper's
  // prefilter: one pixel's estimate is noisy).
  float blurred = 0.0, blur_weight = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      vec4 t = texelFetch(source, clamp(p + ivec2(dx, dy), ivec2(0), size - 1), 0);
      float k = t.z < 0.0 ? 0.0 : gauss(dx) * gauss(dy);
      blurred += k * t.y;
      blur_weight += k;
    }
  float luminance = 1.442695 / (sigma_variance * sqrt(max(blurred / blur_weight, 0.0)) + 1e-6);

  // Positions rebuilt the same way at the centre and the taps: the
  // centre's plane distance is 0.
  vec3 x = along_ray(p, dist);
  vec3 n = texelFetch(normal, p, 0).xyz;
  vec3 ns = unpack_normal(g.w);
  float plane_scale = 1.442695 / sigma_plane;
  float sum = 0.0, variance = 0.0, weights = 0.0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      // Taps off the image or on background weigh 0. The weight:
      // exp(-plane / sigma_plane) · pow(n·n', sigma_normal) · exp(-|ΔV| / scale),
      // the exponentials as one exp2 (transcendentals are what costs here).
      ivec2 q = p + step_size * ivec2(dx, dy);
      bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
      q = clamp(q, ivec2(0), size - 1);
      vec4 t = texelFetch(source, q, 0);
      float vq = t.x, dq = t.z;
      vec3 d = along_ray(q, dq) - x;
      float plane = abs(dot(n, d)) * inversesqrt(dot(d, d) + 1e-12);
      float cost = plane_scale * plane + luminance * abs(vq - v);
      float facing = facing_weight(dot(ns, unpack_normal(t.w)));
      float w = inside && dq >= 0.0 ? b3(dx) * b3(dy) * facing * exp2(-cost) : 0.0;
      sum += w * vq;
      variance += w * w * t.y;
      weights += w;
    }
  write(sum / weights, variance / (weights * weights), g);
}
)";

// The sources' head: the version, `extra` defines, and NORMAL_SQUARINGS
// when sigma_normal is a power of two (kFacing).
std::string head(float sigma_normal, const std::string& extra) {
  std::string out = "#version 450 core\n" + extra;
  for (int k = 0; k <= 10; ++k)
    if (sigma_normal == float(1 << k))
      out += "#define NORMAL_SQUARINGS " + std::to_string(k) + "\n";
  return out + kFacing;
}
std::string variance_source(float sigma_normal) {
  return head(sigma_normal, "") + kEdgeStopping + kGuide + kVarianceFragment;
}
std::string atrous_source(bool final_iteration, float sigma_normal) {
  return head(sigma_normal, final_iteration ? "#define FINAL\n" : "") + kGuide + kAtrousFragment;
}

void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("denoiser: " + what);
}

// What a full-screen pass needs, whatever the technique left: no depth,
// stencil, blending, scissor or culling, every colour written.
void set_pass_state(int width, int height) {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glViewport(0, 0, width, height);
}

glm::vec3 eye_of(const plugin::FrameInputs& in) { return glm::vec3(glm::inverse(in.view)[3]); }

// kGuide's camera: the eye, the view direction and the affine ray of a
// perspective projection (view-space x at depth 1 is (ndc.x + P[2][0]) /
// P[0][0], likewise y).
void set_camera(const gl::Program& program, const plugin::FrameInputs& in) {
  const glm::mat3 to_world = glm::mat3(glm::inverse(in.view));
  const glm::mat4& P = in.projection;
  const auto ray = [&](float px, float py) {
    const float ndc_x = (px + 0.5f) / float(in.width) * 2.0f - 1.0f;
    const float ndc_y = (py + 0.5f) / float(in.height) * 2.0f - 1.0f;
    return to_world * glm::vec3((ndc_x + P[2][0]) / P[0][0], (ndc_y + P[2][1]) / P[1][1], -1.0f);
  };
  program.set("eye", eye_of(in));
  program.set_if_active("view_forward", to_world * glm::vec3(0.0f, 0.0f, -1.0f));
  program.set_if_active("ray_origin", ray(0.0f, 0.0f));
  program.set_if_active("ray_dx", ray(1.0f, 0.0f) - ray(0.0f, 0.0f));
  program.set_if_active("ray_dy", ray(0.0f, 1.0f) - ray(0.0f, 0.0f));
}

// A texture's every texel set to `value` (the histories start defined).
void clear_texture(const gl::Texture& t, float value) {
  const std::array<float, 4> v{value, value, value, value};
  glClearTexImage(t.get(), 0, GL_RGBA, GL_FLOAT, v.data());
}

}  // namespace

HistoryRejection history_rejection_from_string(const std::string& s) {
  if (s == "none") return HistoryRejection::None;
  if (s == "clamp") return HistoryRejection::Clamp;
  throw std::invalid_argument("history rejection \"" + s + "\" is not none or clamp");
}

std::vector<ParamSpec> denoiser_params(const std::string& default_denoiser) {
  std::vector<ParamSpec> out = {
      core::choice_param("denoiser", default_denoiser, {"none", "svgf"},
                         "the noisy V denoised: none, or svgf (spatiotemporal "
                         "variance-guided filtering, Schied 2017; common/visibility_denoiser.h)"),
      core::bool_param("denoiser_temporal", true,
                       "svgf: accumulate reprojected history (off: the spatial a-trous only)"),
      core::choice_param("denoiser_rejection", "clamp", {"clamp", "none"},
                         "svgf: history rejection beyond disocclusion: clamp to the local "
                         "mean +- gamma sigma (a moving light's old shadows), or none (the "
                         "paper's)"),
      core::int_param("denoiser_iterations", 4, 0, 6, "svgf: a-trous iterations (step 2^i)"),
      core::float_param("denoiser_alpha", 0.2, 0.01, 1.0,
                        "svgf: the temporal blend's floor (1 keeps no history)"),
      core::float_param("denoiser_clamp_gamma", 1.0, 0.0, 16.0,
                        "svgf: the clamp's half-width in local standard deviations")};
  // With no denoiser the rest change nothing (no sensitivity to them).
  for (size_t i = 1; i < out.size(); ++i) out[i].enabled_by = "denoiser";
  return out;
}

std::optional<DenoiserSettings> denoiser_settings(const core::Params& p) {
  DenoiserSettings s;
  const bool on = p.get_string("denoiser") == "svgf";
  s.temporal = p.get_bool("denoiser_temporal");
  s.rejection = history_rejection_from_string(p.get_string("denoiser_rejection"));
  s.atrous_iterations = p.get_int("denoiser_iterations");
  s.alpha = p.get_float("denoiser_alpha");
  s.clamp_gamma = p.get_float("denoiser_clamp_gamma");
  if (!on) return std::nullopt;
  return s;
}

VisibilityDenoiser::VisibilityDenoiser(DenoiserSettings settings) : settings_(settings) {
  const DenoiserSettings& s = settings_;
  check(s.atrous_iterations >= 0 && s.atrous_iterations <= 6, "atrous_iterations not in 0..6");
  check(s.alpha > 0.0f && s.alpha <= 1.0f, "alpha not in (0, 1]");
  check(s.max_history >= 1, "max_history below 1");
  check(s.clamp_gamma >= 0.0f && s.clamp_reset >= 0.0f, "a negative clamp setting");
  check(s.clamp_radius >= 1 && s.clamp_radius <= 8, "clamp_radius not in 1..8");
  check(s.reprojection_tolerance > 0.0f && s.sigma_plane > 0.0f && s.sigma_normal >= 0.0f &&
            s.sigma_variance > 0.0f,
        "a tolerance or sigma not positive");
}

void VisibilityDenoiser::prepare(int width, int height) {
  width_ = width;
  height_ = height;
  has_history_ = false;
  parity_ = 0;
  previous_view_projection_ = glm::mat4(1.0f);
  const bool clamp = settings_.temporal && settings_.rejection == HistoryRejection::Clamp;
  for (int k = 0; k < 2; ++k) {
    if (settings_.temporal) {
      moments_[k] = gl::make_texture_2d(GL_RGBA32F, width, height);
      color_[k] = gl::make_texture_2d(GL_R32F, width, height);
      position_[k] = gl::make_texture_2d(GL_RGBA32F, width, height);
      normal_[k] = gl::make_texture_2d(GL_RGBA16F, width, height);
      for (const gl::Texture* t : {&moments_[k], &color_[k], &position_[k], &normal_[k]})
        clear_texture(*t, 0.0f);
    } else {
      moments_[k] = {};
      color_[k] = {};
      position_[k] = {};
      normal_[k] = {};
    }
  }
  ping_ = gl::make_texture_2d(GL_RGBA32F, width, height);
  pong_ = gl::make_texture_2d(GL_RGBA32F, width, height);
  clear_texture(ping_, 0.0f);
  clear_texture(pong_, 0.0f);
  ping_fb_ = gl::make_framebuffer({ping_.get()}, 0);
  pong_fb_ = gl::make_framebuffer({pong_.get()}, 0);
  for (int k = 0; k < 2; ++k) {
    if (settings_.temporal) {
      temporal_fb_[k] = gl::make_framebuffer(
          {moments_[k].get(), color_[k].get(), position_[k].get(), normal_[k].get()}, 0);
      history_fb_[k] = gl::make_framebuffer({pong_.get(), color_[k].get()}, 0);
    } else {
      temporal_fb_[k] = {};
      history_fb_[k] = {};
    }
  }
  if (clamp) {
    window_rows_ = gl::make_texture_2d(GL_RGBA32F, width, height);
    clear_texture(window_rows_, 0.0f);
    window_rows_fb_ = gl::make_framebuffer({window_rows_.get()}, 0);
  } else {
    window_rows_ = {};
    window_rows_fb_ = {};
  }

  const std::string vertex = gl::kFullscreenVertexShader;
  if (settings_.temporal) {
    temporal_program_ = gl::Program("denoiser_temporal", {vertex, "", kTemporalFragment});
    temporal_program_.set("alpha", settings_.alpha);
    temporal_program_.set("max_history", float(settings_.max_history));
    temporal_program_.set("reprojection_tolerance", settings_.reprojection_tolerance);
    temporal_program_.set("clamp_history", clamp ? 1 : 0);
    temporal_program_.set_if_active("clamp_radius", settings_.clamp_radius);
    temporal_program_.set_if_active("clamp_gamma", settings_.clamp_gamma);
    temporal_program_.set_if_active("clamp_reset", settings_.clamp_reset);
  }
  if (clamp) {
    window_program_ = gl::Program("denoiser_window", {vertex, "", kWindowRowsFragment});
    window_program_.set("radius", settings_.clamp_radius);
  }
  variance_program_ =
      gl::Program("denoiser_variance", {vertex, "", variance_source(settings_.sigma_normal)});
  variance_program_.set("sigma_plane", settings_.sigma_plane);
  variance_program_.set_if_active("sigma_normal", settings_.sigma_normal);
  variance_program_.set("spatial_only", settings_.temporal ? 0 : 1);
  atrous_program_ =
      gl::Program("denoiser_atrous", {vertex, "", atrous_source(false, settings_.sigma_normal)});
  atrous_final_program_ = gl::Program("denoiser_atrous_final",
                                      {vertex, "", atrous_source(true, settings_.sigma_normal)});
  for (const gl::Program* program : {&atrous_program_, &atrous_final_program_}) {
    program->set("sigma_plane", settings_.sigma_plane);
    program->set_if_active("sigma_normal", settings_.sigma_normal);
    program->set("sigma_variance", settings_.sigma_variance);
    program->set("copy_only", settings_.atrous_iterations == 0 ? 1 : 0);
  }
  gl::throw_if_errors("preparing the visibility denoiser");
}

void VisibilityDenoiser::denoise(const plugin::FrameInputs& in, GLuint noisy,
                                 gl::PassTimer& timer) {
  if (in.width != width_ || in.height != height_)
    throw JobError("denoiser: a frame of " + std::to_string(in.width) + "x" +
                   std::to_string(in.height) + " after prepare(" + std::to_string(width_) + ", " +
                   std::to_string(height_) + ")");
  const int current = parity_, previous = 1 - parity_;
  if (settings_.temporal) {
    auto pass = timer.scope("temporal");
    temporal_pass(in, noisy, current, previous);
  }
  {
    auto pass = timer.scope("variance");
    variance_pass(in, noisy, current);
  }
  {
    auto pass = timer.scope("atrous");
    atrous_passes(in, current);
  }
  previous_view_projection_ = in.view_projection;
  has_history_ = settings_.temporal;
  parity_ = previous;
}

void VisibilityDenoiser::temporal_pass(const plugin::FrameInputs& in, GLuint noisy, int current,
                                       int previous) {
  set_pass_state(width_, height_);
  glBindTextureUnit(0, noisy);
  glBindTextureUnit(1, in.gbuffer_position);
  if (window_program_.id() != 0) {
    window_program_.use();
    glBindFramebuffer(GL_FRAMEBUFFER, window_rows_fb_.get());
    gl::draw_fullscreen_triangle();
  }
  temporal_program_.use();
  temporal_program_.set("prev_view_projection", previous_view_projection_);
  temporal_program_.set("eye", eye_of(in));
  temporal_program_.set("has_history", has_history_ ? 1 : 0);
  glBindTextureUnit(2, in.gbuffer_normal);
  glBindTextureUnit(3, color_[previous].get());
  glBindTextureUnit(4, moments_[previous].get());
  glBindTextureUnit(5, position_[previous].get());
  glBindTextureUnit(6, normal_[previous].get());
  glBindTextureUnit(7, window_rows_.get());
  glBindFramebuffer(GL_FRAMEBUFFER, temporal_fb_[current].get());
  gl::draw_fullscreen_triangle();
}

void VisibilityDenoiser::variance_pass(const plugin::FrameInputs& in, GLuint noisy, int current) {
  set_pass_state(width_, height_);
  variance_program_.use();
  set_camera(variance_program_, in);
  glBindTextureUnit(0, settings_.temporal ? moments_[current].get() : noisy);
  glBindTextureUnit(1, in.gbuffer_position);
  glBindTextureUnit(2, in.gbuffer_normal);
  glBindTextureUnit(3, in.gbuffer_shading_normal);
  glBindFramebuffer(GL_FRAMEBUFFER, ping_fb_.get());
  gl::draw_fullscreen_triangle();
}

void VisibilityDenoiser::atrous_passes(const plugin::FrameInputs& in, int current) {
  glBindTextureUnit(2, in.gbuffer_normal);
  const int n = settings_.atrous_iterations;
  // Iteration i reads ping (even i) or pong (odd i); the last one writes V.
  for (int i = 0; i < std::max(n, 1); ++i) {
    const bool last = i == std::max(n, 1) - 1;
    const gl::Program& program = last ? atrous_final_program_ : atrous_program_;
    GLuint target = i % 2 == 0 ? pong_fb_.get() : ping_fb_.get();
    if (i == 0 && settings_.temporal) target = history_fb_[current].get();
    if (last) target = in.visibility_framebuffer;
    program.use();
    set_camera(program, in);
    program.set("step_size", 1 << i);
    glBindTextureUnit(0, i % 2 == 0 ? ping_.get() : pong_.get());
    glBindFramebuffer(GL_FRAMEBUFFER, target);
    gl::draw_fullscreen_triangle();
  }
  // One iteration wrote V straight into the target: its output is the
  // history too. (With none, the history is the temporal pass's V.)
  if (n == 1 && settings_.temporal)
    glCopyImageSubData(in.visibility_texture, GL_TEXTURE_2D, 0, 0, 0, 0, color_[current].get(),
                       GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
}

}  // namespace sb::techniques

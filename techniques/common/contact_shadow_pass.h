#pragma once
// Screen-space contact shadows: a short ray march towards the light through
// the camera's G-buffer, the pattern engines add on top of their shadow maps
// to catch the small occlusions where an object touches its receiver, which
// a map's resolution and bias miss (Sousa et al. at Crytek; Unreal Engine's
// "contact shadows", whose world-space length and jittered start this
// follows; Aldridge 2023, "Bend Studio's screen space shadows", SIGGRAPH,
// which marches pixel by pixel from the light's screen position instead).
//
// Per G-buffer pixel p with surface point P (position w = 1) and geometric
// normal n, towards the light's centre (a local light) or along to_sun()
// (the sun), direction d:
//   start  S0 = P + n·(a quarter of a pixel's world size at P's view depth):
//          off the surface, against rounding;
//   march  `steps` points S_i = S0 + d·(i + j)·length/steps, i = 0..steps-1,
//          with j in [0,1) a fixed interleaved-gradient noise of the pixel
//          (Jimenez 2014): the same every frame, so frames are deterministic;
//          towards a local light the march stops at its centre;
//   test   each S_i projected with FrameInputs::view_projection to pixel q
//          (q ≠ p); the surface seen there (gbuffer_position, exact, no depth
//          reconstruction) hides S_i when S_i lies behind it by less than
//          `thickness` in view depth: 0 < z(S_i) − z(seen) < thickness, the
//          seen depth taken on the seen triangle's plane (gbuffer_normal)
//          where the camera ray through S_i meets it, not at q's centre, so
//          that a step a fraction of a pixel off a steep or curved surface is
//          not behind it (a grazing plane falls back to q's centre);
//   V      0 at the first hidden step, else 1 (no fade). 0 also where d is
//          below P's tangent plane (as the map lookup's above_horizon());
//          1 on the background.
// Skipped steps: off screen or behind the camera (the march ends: nothing is
// known there), on the background or on a mesh that casts no shadow
// (normal w = 0: a ground under everything occludes nothing).
//
// Limits (the depth buffer is all it knows): an occluder off screen, or
// hidden behind another surface from the camera, casts nothing; every
// occluder is assumed `thickness` deep behind its visible surface, so a
// thin one is too thick (shadows leak past its far side) and a thick one
// too thin (rays pass behind it), and a ray that grazes an occluder's far
// side within `thickness` of its visible surface counts as blocked (a dark
// fringe where the sphere grid's spheres meet the ground); the light is its
// centre only (V is 0 or 1, hard, where an area light's penumbra is soft);
// and it reaches `length` from the surface and no farther.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     FrameInputs' G-buffer (position, geometric normal), view,
//          projection, view_projection and scene light;
//   out    V_contact in every pixel of in.visibility_framebuffer, written as
//          is (ContactCombine::Replace) or as min(V there, V_contact)
//          (ContactCombine::Min: glBlendEquation(GL_MIN), no extra target);
//   GL     ContactShadowPass(settings) compiles a program: call it in
//          prepare(). draw() leaves in.visibility_framebuffer bound, the
//          viewport at in.width×in.height, depth, stencil and scissor tests
//          off, blending off with the default equation, its program in use
//          and the G-buffer on units 0 and 2;
//   cost   one full-screen triangle: per pixel two G-buffer fetches and at
//          most `steps` × (one matrix-vector product and two fetches).
#include <string>
#include <vector>

#include "core/params.h"
#include "gl/program.h"
#include "plugin/technique.h"

namespace sb::techniques {

// The march's parameters (their defaults: contact_shadow_params()).
// units: length and thickness in world units; steps a count.
struct ContactShadowSettings {
  float length = 0.0f;     // world units, from the surface towards the light
  int steps = 0;           // points along it
  float thickness = 0.0f;  // how deep behind its visible surface an occluder is assumed
};

// The march's parameters as declared, names prefixed by `prefix` ("" for the
// standalone technique: length, steps, thickness; "contact_" for the option
// with_contact_option() adds): length > 0, steps ≥ 1, thickness > 0.
std::vector<core::ParamSpec> contact_shadow_params(const std::string& prefix);
// Reads the parameters of contact_shadow_params(prefix).
ContactShadowSettings contact_shadow_settings(const core::Params& p, const std::string& prefix);

// How the pass writes V_contact into the visibility target.
enum class ContactCombine {
  Replace,  // V = V_contact
  Min,      // V = min(V already there, V_contact): after a map technique's pass
};

// The full-screen contact-shadow pass (the rule at the top of this header):
// made in prepare(), drawn in every frame.
// cost: one full-screen triangle; per pixel at most `steps` projections and
// 2·steps + 2 G-buffer fetches.
class ContactShadowPass {
 public:
  ContactShadowPass() = default;
  explicit ContactShadowPass(const ContactShadowSettings& settings);

  // Writes V_contact into in.visibility_framebuffer, every pixel.
  void draw(const plugin::FrameInputs& in, ContactCombine combine) const;

 private:
  ContactShadowSettings settings_;
  gl::Program program_;
};

}  // namespace sb::techniques

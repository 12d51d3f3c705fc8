#pragma once
// The cascades' lookup pass (cascade_lookup_glsl.h), shared by
// cascaded_shadow_map and sdsm: each box's matrix and extent, the splits'
// ends and the blend bands as uniforms, then one full-screen triangle into
// the visibility target, reading the depth array through a comparison
// sampler (unit 4) and a raw one (unit 5).
#include "cascaded/cascade_fit.h"
#include "core/scene.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "plugin/technique.h"

namespace sb::techniques::cascaded {

// units: the plan's, world units and view depths; cost: one full-screen
// pass, a few uniforms.
void draw_cascade_lookup(const gl::Program& lookup, const CascadePlan& plan,
                         const plugin::FrameInputs& in, const core::AreaLight& light, GLuint maps,
                         GLuint compare_sampler, GLuint raw_sampler);

}  // namespace sb::techniques::cascaded

#include "cascaded/cascade_lookup_pass.h"

#include <cmath>
#include <vector>

#include "gl/objects.h"

namespace sb::techniques::cascaded {

void draw_cascade_lookup(const gl::Program& lookup, const CascadePlan& plan,
                         const plugin::FrameInputs& in, const core::AreaLight& light, GLuint maps,
                         GLuint compare_sampler, GLuint raw_sampler) {
  const auto count = GLsizei(plan.boxes.size());
  std::vector<glm::mat4> vp;
  std::vector<glm::vec4> box;
  for (const CascadeBox& b : plan.boxes) {
    vp.push_back(b.view_projection);
    box.emplace_back(b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.near_depth, b.far_depth);
  }
  glProgramUniformMatrix4fv(lookup.id(), lookup.location("cascade_vp"), count, GL_FALSE,
                            &vp[0][0][0]);
  glProgramUniform4fv(lookup.id(), lookup.location("cascade_box"), count, &box[0][0]);
  lookup.set("cascade_end", std::vector<float>(plan.splits.begin() + 1, plan.splits.end()));
  lookup.set("cascade_band", plan.bands);
  lookup.set("camera_view", in.view);
  lookup.set_if_active("to_sun", light.to_sun());
  lookup.set_if_active("sun_spread", 2.0f * std::tan(0.5f * light.angular_diameter));
  glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
  glViewport(0, 0, in.width, in.height);
  glDisable(GL_DEPTH_TEST);
  lookup.use();
  glBindTextureUnit(0, in.gbuffer_position);
  glBindTextureUnit(2, in.gbuffer_normal);
  glBindTextureUnit(4, maps);
  glBindSampler(4, compare_sampler);
  glBindTextureUnit(5, maps);
  glBindSampler(5, raw_sampler);
  gl::draw_fullscreen_triangle();
  glBindSampler(4, 0);
  glBindSampler(5, 0);
}

}  // namespace sb::techniques::cascaded

#include "common/silhouette_band.h"

#include "plugin/silhouette_edges.h"

namespace sb::techniques {

using plugin::FrameInputs;
using plugin::SilhouetteEdges;

void set_fragment_image_uniforms(const gl::Program& program, const LightFrustum& frustum,
                                 int size) {
  const glm::mat4& p = frustum.projection;  // ndc.x = p[0][0]·image.x − p[2][0] (off axis)
  program.set_if_active("image_from_ndc", glm::vec4(p[0][0], p[1][1], p[2][0], p[2][1]));
  program.set_if_active("map_size", float(size));
}

void draw_silhouette_bands(const FrameInputs& in) {
  const auto& edges = in.derived->get<SilhouetteEdges>(plugin::need::kSilhouetteEdges);
  if (edges.edge_count == 0) return;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, edges.buffer());
  glBindVertexArray(gl::empty_vertex_array());
  glDrawArrays(GL_TRIANGLES, 0, 6 * edges.edge_count);
}

}  // namespace sb::techniques

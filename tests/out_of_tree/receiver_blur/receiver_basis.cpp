#include "receiver_basis.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "plugin/need_data.h"

namespace blurred {

sb::plugin::NeedProvider receiver_basis_provider() {
  sb::plugin::NeedProvider p;
  p.name = kReceiverBasis;
  p.summary = "an orthonormal frame over the planar receiver (receiver_blur)";
  p.requires_needs = {sb::plugin::need::kPlanarReceiver};
  // Run: only when a technique that asked will run. A scene without a
  // planar receiver already skipped it through planar_receiver.
  p.when = sb::plugin::NeedProvider::When::Run;
  p.derive = [](const sb::core::Scene& scene, sb::plugin::DerivedData& data,
                std::vector<std::string>& log) {
    const auto* receiver = data.find<sb::plugin::PlanarReceiver>(sb::plugin::need::kPlanarReceiver);
    if (receiver == nullptr) return;
    const sb::core::Mesh* mesh = nullptr;
    for (const auto& m : scene.meshes)
      if (m.name == receiver->mesh) mesh = &m;
    if (mesh == nullptr || mesh->positions.empty()) return;
    auto basis = std::make_shared<ReceiverBasis>();
    basis->plane = receiver->plane;
    const glm::vec3 n(receiver->plane);
    // Any direction not along n starts the frame.
    const glm::vec3 seed = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    basis->u = glm::normalize(glm::cross(n, seed));
    basis->v = glm::cross(n, basis->u);
    glm::vec2 lo(1e30f), hi(-1e30f);
    const glm::vec3 on_plane = -receiver->plane.w * n;
    for (const auto& q : mesh->positions) {
      const glm::vec2 c(glm::dot(q - on_plane, basis->u), glm::dot(q - on_plane, basis->v));
      lo = glm::min(lo, c);
      hi = glm::max(hi, c);
    }
    const glm::vec2 mid = 0.5f * (lo + hi);
    basis->origin = on_plane + mid.x * basis->u + mid.y * basis->v;
    basis->half_extent = glm::max(0.5f * (hi - lo), glm::vec2(1e-6f));
    data.put<ReceiverBasis>(kReceiverBasis, std::move(basis));
    log.push_back("receiver basis over mesh '" + receiver->mesh + "'");
  };
  return p;
}

}  // namespace blurred

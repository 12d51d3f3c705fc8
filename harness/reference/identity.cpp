// What identifies a reference (declared in reference.h): the method id that
// each job's spec hash holds, and the key of its cache file. Both carry the
// version constants below, so that bumping one reruns old jobs and misses
// old cache files.
#include <embree3/rtcore.h>

#include <glm/glm.hpp>

#include "core/hash.h"
#include "reference/method.h"
#include "reference/reference.h"

namespace sb::reference {

using core::Hasher;
using core::ImageF;
using core::Mesh;
using core::Scene;
using core::TextureImage;

namespace {

using detail::embree_config_of;
using detail::method_of;

// Bump whenever the estimate changes for the same inputs (sampling, offsets,
// error estimate): it is part of every cache key.
// 2: horizon test, viewer-facing normals; 3: alpha masks; 4: ray offsets from
// the point and its own triangles, not the scene's radius (ray_offset.h);
// 5: analytic shapes (Mesh::analytic) occlude instead of their meshes and
// join the key; 6: the triangles a point lies on are those within the
// offset's radius of their own bounds (ray_offset.h), not whatever Embree's
// leaves visited, so that the exact reference applies the same test; and
// Embree's robust mode (rays through shared edges no longer slip between the
// triangles, embree_scene.h); 7: no σ of 0 for a soft estimate (the binomial
// error where every pair agrees), the stop bound of agreeing samples beside
// σ, and the penumbra decided exactly where the scene has an exact form.
constexpr uint32_t kMethodVersion = 7;
// Bumped whenever the exact reference's answer may change. 2: a point inside
// a closed caster is in its umbra; 3: the same by a segment test, closed
// casters keeping their near side again; 4: the viewpoint offset by Monte
// Carlo's rule (the triangles the point lies on), not by the casters'
// largest coordinate; 5: each closed part (triangles connected through
// shared edges) oriented by its own volume, and a point inside one when it
// winds around the point more than around the light's centre, not by the
// mesh's total volume and the first crossing; 6: the edges two projected
// triangles share dropped before the union, so an umbra pixel reads 0, not
// a rounding residue of about 1e-8; 7: the area of a union that is only
// separate simple loops summed exactly (128-bit), not by Clipper in double
// (V moves by at most 1e-15, in umbra pixels that read about 8e-9).
constexpr uint32_t kExactMethodVersion = 7;
// Bumped whenever the adaptive reference's figures may change for the same
// settings. 2: where the proofs apply, an agreeing pilot stops only when
// proven to see the whole light or none of it (sample counts fall, and a
// soft pixel the 5×5 window let through is now refined); 3: the proof of an
// occluded pilot by kExactMethodVersion 5's inside test, and its silhouette
// test over the part the centre's ray crosses, not the whole mesh; 4: the
// pilot only decides, from a stream of its own, and the estimate is fresh
// samples at the level decided (adaptive.h: unbiased), stops without proof
// report the error such stops can hide, and samples count the pilot's; 5:
// the proofs also with alpha-masked casters, each masked triangle whole; 6:
// the bound of a stop, or of an estimate whose samples all agree, reported
// as its stop bound, not as σ (kMethodVersion 7).
constexpr uint32_t kAdaptiveVersion = 6;

void hash_image(Hasher& h, const ImageF& img) {
  h.add(int32_t(img.width)).add(int32_t(img.height)).add(int32_t(img.channels));
  h.add(uint64_t(img.data.size()));
  h.add(img.data.data(), img.data.size() * sizeof(float));
}

void hash_vec3(Hasher& h, const glm::vec3& v) { h.add(v.x).add(v.y).add(v.z); }

}  // namespace

std::string method_id(const Settings& s) {
  std::string sampled = std::string(s.adaptive ? kAdaptiveMethod : kStratifiedMethod) + "/" +
                        std::to_string(kMethodVersion);
  if (s.adaptive) sampled += "." + std::to_string(kAdaptiveVersion);
  sampled += std::string(" on Embree ") + RTC_VERSION_STRING;
  if (!s.exact) return sampled;
  return std::string(kExactMethod) + "/" + std::to_string(kExactMethodVersion) + ", else " +
         sampled;
}

std::string cache_key(const Scene& scene, const ImageF& positions, const ImageF& geometric_normals,
                      const Settings& s) {
  Hasher h;
  h.add("shadowbench.reference").add(method_of(s)).add(kMethodVersion);
  if (s.exact) {
    h.add(kExactMethodVersion);
  } else {
    h.add(RTC_VERSION_STRING).add(resolve_isa(embree_config_of(s)));
    h.add(int32_t(s.spp)).add(s.seed);
    if (s.adaptive) h.add(int32_t(s.pilot_spp)).add(s.target_std_error).add(kAdaptiveVersion);
  }
  hash_vec3(h, scene.light.center);
  hash_vec3(h, scene.light.half_u);
  hash_vec3(h, scene.light.half_v);
  // Only a segment's key carries its layout, so that keys from before it was
  // stratified along its axis (and from before the exact reference did
  // segments) never match, while rectangles' and points' keys stay as they were.
  if (scene.light.is_segment()) h.add("light_strata:segment_1d");
  // The sun's key carries its kind and size (a rectangle's never has them).
  if (scene.light.is_sun()) h.add("light:sun").add(scene.light.angular_diameter);
  uint64_t casters = 0;
  for (const Mesh& m : scene.meshes) {
    if (!m.casts_shadow) continue;
    ++casters;
    h.add(uint64_t(m.positions.size()));
    h.add(m.positions.data(), m.positions.size() * sizeof(glm::vec3));
    h.add(uint64_t(m.indices.size()));
    h.add(m.indices.data(), m.indices.size() * sizeof(uint32_t));
    h.add(m.alpha_tested());
    if (m.alpha_tested()) {  // the mask decides which rays pass
      const TextureImage& t = scene.textures.at(size_t(m.base_color_texture));
      h.add(m.alpha_cutoff).add(int32_t(t.width)).add(int32_t(t.height));
      h.add(m.uvs.data(), m.uvs.size() * sizeof(glm::vec2));
      h.add(t.rgba.data(), t.rgba.size());
    }
    // The shape the reference traces instead of the triangles, if any.
    h.add(m.analytic.kind);
    if (m.analytic.has()) {
      hash_vec3(h, m.analytic.center);
      h.add(m.analytic.radius);
    }
  }
  h.add(casters);
  hash_image(h, positions);
  hash_image(h, geometric_normals);
  return h.hex();
}

}  // namespace sb::reference

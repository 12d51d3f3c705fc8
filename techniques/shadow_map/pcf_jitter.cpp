// pcf_jitter — percentage-closer filtering with N jittered taps over a disk
// (Shypula 2008: 32 random taps, an 8-tap early-out). The outermost taps go
// first: when all of them agree the pixel is far from any edge and their
// verdict stands; only pixels near an edge pay for every tap. A per-pixel
// rotation (interleaved gradient noise, Jimenez 2014) trades banding for
// noise.
//
// The default radius, 4.5 texels, is the reach of the 9×9 box.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>
#include <string>

#include "common/glsl_pcf.h"
#include "common/glsl_rotation_noise.h"
#include "common/map_lookup.h"
#include "common/sample_disks.h"
#include "shadow_map/shadow_map_variants.h"

namespace sb::techniques::shadow_map {
namespace {

// The pieces are the kit's (common/glsl_pcf.h, common/glsl_rotation_noise.h).
const char* const kJitteredLitFraction = R"(
uniform int taps;
uniform int early_out_taps;
uniform vec2 offsets[MAX_DISK_TAPS];
uniform float radius_texels;
uniform bool rotate;
float lit_fraction(vec3 t) {
  vec2 scale = radius_texels / vec2(textureSize(shadow_map, 0));
  mat2 r = rotation_by_turns(rotate ? interleaved_gradient_noise(gl_FragCoord.xy) : 0.0);
  float sum = pcf_disk_sum(t, offsets, 0, early_out_taps, r, scale);
  if (early_out_taps > 0 && (sum == 0.0 || sum == float(early_out_taps)))
    return sum / float(early_out_taps);
  sum += pcf_disk_sum(t, offsets, early_out_taps, taps, r, scale);
  return sum / float(taps);
}
)";

class JitteredPcf final : public SingleMapTechnique {
 public:
  explicit JitteredPcf(const Params& p)
      : SingleMapTechnique(p, "pcf_jitter", kJitteredLitFraction, /*linear_compare=*/false,
                           std::string(kPcfGlsl) + kRotationNoiseGlsl),
        offsets_(jittered_disk(p.get_int("taps"), unsigned(p.get_int("seed")))),
        early_out_(p.get_int("early_out_taps")),
        radius_(p.get_float("radius")),
        rotate_(p.get_bool("rotate")) {}

 protected:
  void set_uniforms(const gl::Program& lookup) const override {
    lookup.set("taps", int(offsets_.size()));
    lookup.set("early_out_taps", early_out_);
    lookup.set("offsets", offsets_);
    lookup.set("radius_texels", radius_);
    lookup.set("rotate", rotate_ ? 1 : 0);
  }

 private:
  std::vector<glm::vec2> offsets_;
  int early_out_;
  float radius_;
  bool rotate_;
};

}  // namespace

TechniqueInfo pcf_jitter_info() {
  std::vector<ParamSpec> params = {
      int_param("taps", 32, 2, kMaxDiskTaps, "tap COUNT: jittered taps on a disk"),
      int_param("early_out_taps", 8, 0, 63,
                "tap COUNT: outermost taps tried first; if they agree, the pixel is done (0: off)"),
      float_param("radius", 4.5, 0.0, 256.0, "disk radius (half its width) in texels"),
      bool_param("rotate", true, "rotate the tap pattern per pixel"),
      int_param("seed", 1, 0, 2147483647, "jitter of the tap positions"),
      receiver_plane_param()};
  for (auto& p : depth_map_params(2048)) params.push_back(std::move(p));
  return {.name = "pcf_jitter",
          .family = "shadow_map",
          .summary = "jittered-disk percentage-closer filtering with an early-out (Shypula 2008)",
          .needs = Needs{need::kSunOrLocalLight, need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<JitteredPcf>(p); },
          .check = [](const Params& p) -> std::pair<std::string, std::string> {
            const int taps = p.get_int("taps"), early = p.get_int("early_out_taps");
            if (early >= taps)
              return {"early_out_taps", "expected fewer early-out taps than taps (" +
                                            std::to_string(taps) + "), found " +
                                            std::to_string(early)};
            return {};
          }};
}

}  // namespace sb::techniques::shadow_map

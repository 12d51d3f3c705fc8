// The default template of `shadowbench new-technique` (--family
// shadow_map): the installed example docs/examples/my_pcf under a new name,
// a k×k PCF (the kit's pcf_grid) as a SingleMapTechnique of the shadow-map
// kit (shadowbench::shadow_kit), so that it starts with the built-ins' own
// light frustum, depth pass, biases, culling and map lookup, and equals
// pcf_box until its filter is changed. Its .cpp, CMakeLists.txt and config
// are the example's files themselves (generated/my_pcf_example.h, made by
// harness/cli/CMakeLists.txt); only the README is written here, with the
// commands for this shadowbench. tests/out_of_tree/scaffold_build_and_run.py
// builds it from an installed prefix and checks its RMSE against pcf_box's.
#include <string>

#include "cli/technique_template.h"
#include "my_pcf_example.h"

namespace sb::cli {

TechniqueTemplate shadow_map_template() {
  TechniqueTemplate t;
  t.family = "shadow_map";
  t.summary = "k×k PCF on the shadow-map kit, equal to pcf_box until you change its filter";
  t.files.push_back({"@NAME@.cpp", my_pcf_example::k_my_pcf_cpp});
  t.files.push_back({"CMakeLists.txt", my_pcf_example::k_CMakeLists_txt});
  t.files.push_back({"@NAME@.json", my_pcf_example::k_my_pcf_json});
  t.files.push_back(
      {"README.md", R"FILE(# @NAME@

A shadow technique plugin for shadowbench, written by
`shadowbench new-technique`: a hard shadow map from the light's centre
filtered by a k×k box of depth comparisons, on the shadow-map kit
(`shadowbench::shadow_kit`, headers `common/*.h`). It is a
`SingleMapTechnique` (`common/map_lookup.h`), which gives it the built-in
`pcf_box`'s `prepare()` and `render()`: light frustum, depth pass, biases,
culling and map lookup; only the filter, the GLSL `lit_fraction()` in
`@NAME@.cpp`, and its uniforms (`set_uniforms()`) are its own, and it calls
the kit's `pcf_grid` (`common/glsl_pcf.h`). The kit's other pieces to build
on: PCSS's blocker search and penumbra width (`common/glsl_pcss.h`), Poisson
and jittered tap disks (`common/sample_disks.h`) and per-pixel rotation
noise (`common/glsl_rotation_noise.h`). As written, its visibility and its
error equal `pcf_box`'s for the same parameters: change the filter, and the
difference you measure is the filter's alone.

)FILE" + std::string(kBuildLoadRun) +
                        R"FILE(`@NAME@.json` runs it beside `pcf_box` with the same parameters, and
`shadow_map` and `none` for scale. A rerun into the same folder resumes the
jobs it finished, except those of a plugin whose .so changed since: after a
rebuild, @NAME@'s jobs run again (records hold the plugin's SHA-256).

`shadowbench list @NAME@` shows its parameters: `k` and the depth map's
(`size`, `depth_format`, `constant_bias`, `slope_bias`, `cull`,
`normal_offset`). What a technique must do, what each kit header
guarantees, and how to compare fairly: the guide,
docs/writing_a_technique.md (installed under share/doc/shadowbench/).
)FILE"});
  return t;
}

}  // namespace sb::cli

// technique.gpu_bytes through a real run: the peak GPU storage each
// technique made through the gl::make_* helpers, against the sum of the
// textures its documentation names (docs/shadow_maps.md, docs/parameters.md),
// computed by hand from their formats' bytes per texel.
#include <gtest/gtest.h>

#include "e2e_util.h"
#include "record/job_record.h"

namespace sb::test {

using record::JobRecord;

namespace {

using json = nlohmann::json;

// The record of the technique called `name` whose params include `params`.
const json& record_of(const RunOutput& out, const std::string& name, const json& params) {
  for (const json& r : out.records) {
    if (r["technique"]["name"] != name) continue;
    bool match = true;
    for (const auto& [key, value] : params.items()) match &= r["technique"]["params"][key] == value;
    if (match) return r;
  }
  throw std::runtime_error("no record of " + name + " " + params.dump());
}

std::int64_t gpu_bytes(const RunOutput& out, const std::string& name, const json& params) {
  const json& r = record_of(out, name, params);
  EXPECT_EQ(r["status"], "ok") << r.dump();
  // What the record says is what its reader reads.
  const JobRecord back = JobRecord::from_json(r);
  EXPECT_EQ(back.technique.gpu_bytes, r["technique"]["gpu_bytes"].get<std::int64_t>());
  return r["technique"]["gpu_bytes"].get<std::int64_t>();
}

TEST(GpuBytes, AreTheSumOfTheDocumentedTexturesOfEachTechnique) {
  const json config = {
      {"name", "gpu_bytes"},
      {"scenes", json::array({small_scene(0.5)})},
      {"techniques",
       json::array({"none",
                    {{"name", "shadow_map"}, {"params", {{"size", 64}}}},
                    {{"name", "shadow_map"}, {"params", {{"size", 64}, {"depth_format", "16"}}}},
                    {{"name", "vsm"}, {"params", {{"size", 64}}}},
                    {{"name", "vsm"},
                     {"params", {{"size", 64}, {"format", "16f"}, {"prefilter", "box"}, {"k", 3}}}},
                    {{"name", "shadow_volume"}, {"params", {{"silhouettes", "cpu"}}}}})},
      {"resolutions", json::array({json::array({64, 48})})},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"spp", 4}}}};
  const RunOutput out = run_config(config, "gpu_bytes");
  ASSERT_EQ(out.summary.failed, 0);

  // none draws nothing of its own.
  EXPECT_EQ(gpu_bytes(out, "none", json::object()), 0);
  // shadow_map: one 64² depth map, GL_DEPTH_COMPONENT32F (4 bytes) or
  // GL_DEPTH_COMPONENT16 (2 bytes).
  EXPECT_EQ(gpu_bytes(out, "shadow_map", {{"size", 64}, {"depth_format", "32f"}}), 64 * 64 * 4);
  EXPECT_EQ(gpu_bytes(out, "shadow_map", {{"size", 64}, {"depth_format", "16"}}), 64 * 64 * 2);
  // vsm: the depth map and the moments z, z² (GL_RG32F, 8 bytes); with a
  // prefilter, the filter's scratch of the moments' format too (GL_RG16F, 4
  // bytes, for format 16f).
  EXPECT_EQ(gpu_bytes(out, "vsm", {{"size", 64}, {"prefilter", "none"}}),
            64 * 64 * 4 + 64 * 64 * 8);
  EXPECT_EQ(gpu_bytes(out, "vsm", {{"size", 64}, {"prefilter", "box"}}),
            64 * 64 * 4 + 64 * 64 * 4 + 64 * 64 * 4);
  // Shadow volumes from CPU silhouettes stream their vertices (vec4s, 16
  // bytes each): some, and whole ones.
  const std::int64_t volumes = gpu_bytes(out, "shadow_volume", {{"silhouettes", "cpu"}});
  EXPECT_GT(volumes, 0);
  EXPECT_EQ(volumes % 16, 0);
}

}  // namespace
}  // namespace sb::test

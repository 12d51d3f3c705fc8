// One frame renders bit-identically on OSMesa and on EGL (surfaceless here).
#include <gtest/gtest.h>

#include "e2e_util.h"

namespace sb::test {

using core::ImageF;

namespace {

using json = nlohmann::json;

TEST(Backends, OSMesaAndEglRenderIdenticalFrames) {
  if (!gl::backend_available(gl::Backend::EGL)) GTEST_FAIL() << "EGL backend not compiled in";
  const json config = {
      {"name", "backends"},
      {"scenes", json::array({small_scene(1.0)})},
      {"techniques", json::array({json{{"name", "pcf_box"}, {"params", {{"size", 512}}}}})},
      {"resolutions", json::array({json::array({128, 96})})},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"spp", 16}}}};
  const auto osmesa = run_config(config, "backend_osmesa", gl::Backend::OSMesa);
  const auto egl = run_config(config, "backend_egl", gl::Backend::EGL);
  ASSERT_EQ(osmesa.summary.failed, 0);
  ASSERT_EQ(egl.summary.failed, 0) << egl.records[0].dump();
  EXPECT_EQ(egl.records[0]["gl_platform"].get<std::string>().rfind("egl", 0), 0u);
  const ImageF a = osmesa.visibility("pcf_box/size=512");
  const ImageF b = egl.visibility("pcf_box/size=512");
  ASSERT_TRUE(a.same_shape(b));
  EXPECT_EQ(a.data, b.data);
}

}  // namespace
}  // namespace sb::test

// What the plugin contract gives a technique on the GPU: compute and
// tessellation programs, and read-only views of the scene's buffers, so a
// technique can build its own data from the scene without uploading it again.
#include <gtest/gtest.h>

#include <numeric>

#include "core/error.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plan/need_resolution.h"
#include "plugin/need_data.h"
#include "scenes/mesh_builders.h"

namespace sb::test {

using core::JobError;
using core::Scene;
using gl::GpuScene;
using plan::find_need_provider;
using plugin::DerivedData;
using plugin::NeedProvider;
using plugin::SilhouetteEdges;

namespace {

class GpuAccess : public ::testing::Test {
 protected:
  void SetUp() override { context_ = gl::create_context(gl::Backend::OSMesa); }
  std::unique_ptr<gl::Context> context_;
};

std::vector<float> read_buffer(GLuint buffer, size_t count) {
  std::vector<float> out(count);
  glGetNamedBufferSubData(buffer, 0, GLsizeiptr(count * sizeof(float)), out.data());
  return out;
}

TEST_F(GpuAccess, AComputeProgramRuns) {
  const gl::Program square = gl::Program::compute("square", R"(#version 450 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Out { float values[]; };
void main() { uint i = gl_GlobalInvocationID.x; values[i] = float(i * i); }
)");
  const std::vector<float> zeros(256, -1.0f);
  const gl::Buffer out = gl::make_buffer(GLsizeiptr(zeros.size() * sizeof(float)), zeros.data());
  square.use();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, out.get());
  glDispatchCompute(4, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  gl::throw_if_errors("compute test");
  const auto values = read_buffer(out.get(), zeros.size());
  for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(values[i], float(i * i)) << i;
}

// A technique reads the scene's vertices and indices where GpuScene keeps
// them: here, each caster triangle's area, summed against the CPU's.
TEST_F(GpuAccess, TheScenesBuffersAreReadableFromACompute) {
  Scene scene;
  scene.meshes.push_back(make_box("box", {0, 1, 0}, {0.5f, 1.0f, 1.5f}));
  scene.meshes.push_back(make_box("receiver", {0, -1, 0}, {5.0f, 0.1f, 5.0f}));
  scene.meshes.back().casts_shadow = false;
  const GpuScene gpu(scene, {});
  const auto ranges = gpu.mesh_ranges();
  ASSERT_EQ(ranges.size(), 2u);
  ASSERT_TRUE(ranges[0].casts_shadow);
  const gl::Program area = gl::Program::compute("area", R"(#version 450 core
layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer Vertices { float v[]; };
layout(std430, binding = 1) readonly buffer Indices { uint idx[]; };
layout(std430, binding = 2) buffer Out { float area[]; };
uniform uint first_index;
uniform int base_vertex;
uniform int floats_per_vertex;
vec3 position(uint i) {
  int k = (int(idx[first_index + i]) + base_vertex) * floats_per_vertex;
  return vec3(v[k], v[k + 1], v[k + 2]);
}
void main() {
  uint t = gl_GlobalInvocationID.x;
  vec3 a = position(3u * t), b = position(3u * t + 1u), c = position(3u * t + 2u);
  area[t] = 0.5 * length(cross(b - a, c - a));
}
)");
  const size_t triangles = size_t(ranges[0].index_count) / 3;
  const std::vector<float> zeros(triangles, 0.0f);
  const gl::Buffer out = gl::make_buffer(GLsizeiptr(zeros.size() * sizeof(float)), zeros.data());
  area.use();
  glProgramUniform1ui(area.id(), area.location("first_index"),
                      GLuint(ranges[0].first_index_byte / 4));
  area.set("base_vertex", ranges[0].base_vertex);
  area.set("floats_per_vertex", GpuScene::kFloatsPerVertex);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, gpu.vertex_buffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, gpu.index_buffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, out.get());
  glDispatchCompute(GLuint(triangles), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  gl::throw_if_errors("scene buffer test");
  const auto areas = read_buffer(out.get(), triangles);
  // A 1 × 2 × 3 box: surface 2·(2 + 3 + 6) = 22.
  EXPECT_NEAR(std::accumulate(areas.begin(), areas.end(), 0.0), 22.0, 1e-4);
}

// Meshes drawn alike one after another share one draw (a glTF placing one
// mesh 200,000 times paid 200,000 draws a pass, issue 65): a pass's setup
// runs once per draw. Meshes drawn differently keep their own.
TEST_F(GpuAccess, NeighboursDrawnAlikeShareOneDraw) {
  Scene scene;
  scene.meshes.push_back(make_box("receiver", {0, -1, 0}, {5.0f, 0.1f, 5.0f}));
  scene.meshes.back().casts_shadow = false;
  for (int i = 0; i < 1000; ++i)
    scene.meshes.push_back(make_box("copy", {0, 1, 0}, {0.5f, 1.0f, 1.5f}));
  const gl::Program depth("depth", {gl::kSceneVertexShader, "", ""});
  depth.use();
  int draws = 0;
  const GpuScene gpu(scene, {});
  gpu.draw_all([&](const gl::DrawInfo&) { ++draws; });
  EXPECT_EQ(draws, 2);
  draws = 0;
  gpu.draw_casters([&](const gl::DrawInfo& info) {
    EXPECT_TRUE(info.casts_shadow);
    ++draws;
  });
  EXPECT_EQ(draws, 1);
  ASSERT_EQ(gpu.mesh_ranges().size(), 1001u);  // the per-mesh view stays

  for (size_t i = 1; i < scene.meshes.size(); i += 2) scene.meshes[i].albedo = glm::vec3(0.2f);
  const GpuScene mixed(scene, {});
  draws = 0;
  mixed.draw_all([&](const gl::DrawInfo&) { ++draws; });
  EXPECT_EQ(draws, 1001);
  gl::throw_if_errors("batched draws");
}

TEST_F(GpuAccess, TessellatedProgramsLinkAndCompileErrorsNameTheStage) {
  const char* vertex =
      "#version 450 core\nlayout(location = 0) in vec3 p;\n"
      "void main() { gl_Position = vec4(p, 1.0); }\n";
  const char* control =
      "#version 450 core\nlayout(vertices = 3) out;\nvoid main() {\n"
      "  gl_out[gl_InvocationID].gl_Position = gl_in[gl_InvocationID].gl_Position;\n"
      "  gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = 4.0;\n"
      "  gl_TessLevelInner[0] = 4.0;\n}\n";
  const char* evaluation =
      "#version 450 core\nlayout(triangles) in;\nvoid main() {\n"
      "  gl_Position = gl_TessCoord.x * gl_in[0].gl_Position +\n"
      "    gl_TessCoord.y * gl_in[1].gl_Position + gl_TessCoord.z * gl_in[2].gl_Position;\n}\n";
  const char* fragment = "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
  const gl::Program ok =
      gl::Program::tessellated("tess", {vertex, "", fragment}, control, evaluation);
  EXPECT_NE(ok.id(), 0u);
  try {
    (void)gl::Program::tessellated("broken", {vertex, "", fragment}, "#version 450 core\nnonsense;",
                                   evaluation);
    ADD_FAILURE() << "no error";
  } catch (const JobError& e) {
    EXPECT_NE(std::string(e.what()).find("'broken' (tessellation control)"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW((void)gl::Program::compute("bad", "#version 450 core\nvoid main() { x; }"),
               JobError);
  // The compile errors were reported once, by the throws above: nothing is
  // left queued to fail the next GL check (another technique's job).
  EXPECT_NO_THROW(gl::throw_if_errors("after the broken programs"));
}

// need::kSilhouetteEdges: the provider's buffer, read by a compute shader
// that finds silhouettes by the sign of the two face planes, as a technique
// would. A box seen from a point outside all three of its slabs shows three
// faces, so its outline is a hexagon: 6 edges. From straight above (inside
// two slabs) only the top face is lit: its 4 edges.
TEST_F(GpuAccess, SilhouetteEdgesOfABoxFromAPointAreItsOutline) {
  Scene scene;
  scene.meshes.push_back(make_box("box", {0, 1, 0}, {0.5f, 1.0f, 1.5f}));
  const GpuScene gpu(scene, {});
  const NeedProvider* provider = find_need_provider(plugin::need::kSilhouetteEdges, nullptr);
  ASSERT_NE(provider, nullptr);
  ASSERT_TRUE(provider->upload);
  DerivedData data;
  provider->upload(scene, gpu, data);
  const auto& edges = data.get<SilhouetteEdges>(plugin::need::kSilhouetteEdges);
  ASSERT_EQ(edges.edge_count, 18);
  ASSERT_EQ(edges.meshes.size(), 1u);
  EXPECT_EQ(edges.meshes[0].edge_count, 18);

  const gl::Program count = gl::Program::compute("count silhouettes", R"(#version 450 core
layout(local_size_x = 1) in;
struct Edge { vec4 p0; vec4 p1; vec4 plane_a; vec4 plane_b; };
layout(std430, binding = 0) readonly buffer Edges { Edge edges[]; };
layout(std430, binding = 1) buffer Count { uint silhouettes; };
uniform vec3 light;
void main() {
  Edge e = edges[gl_GlobalInvocationID.x];
  float a = dot(e.plane_a, vec4(light, 1.0)), b = dot(e.plane_b, vec4(light, 1.0));
  if (e.p1.w == 0.0 || (a > 0.0) != (b > 0.0)) atomicAdd(silhouettes, 1u);
}
)");
  const auto silhouettes_from = [&](glm::vec3 light) {
    const uint32_t zero = 0;
    const gl::Buffer counter = gl::make_buffer(sizeof zero, &zero);
    count.use();
    count.set("light", light);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, edges.buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counter.get());
    glDispatchCompute(GLuint(edges.edge_count), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl::throw_if_errors("silhouette count");
    uint32_t n = 0;
    glGetNamedBufferSubData(counter.get(), 0, sizeof n, &n);
    return n;
  };
  EXPECT_EQ(silhouettes_from({3.0f, 5.0f, 4.0f}), 6u);
  EXPECT_EQ(silhouettes_from({0.1f, 5.0f, 0.2f}), 4u);
}

}  // namespace
}  // namespace sb::test

// The GPU memory meter (gl/allocation_meter.h): the bytes of what the makers
// allocate while a window is open, against sizes computed by hand from each
// format's bits per texel (OpenGL 4.5, table 8.12), and nothing outside a
// window (drives Mesa).
#include <gtest/gtest.h>

#include <memory>

#include "core/error.h"
#include "gl/allocation_meter.h"
#include "gl/context.h"
#include "gl/objects.h"
#include "gl/storage_bytes.h"

namespace sb::test {

using core::JobError;

namespace {

constexpr std::int64_t kMiB = 1024 * 1024;

class GpuMemory : public ::testing::Test {
 protected:
  void SetUp() override { context_ = gl::create_context(gl::Backend::OSMesa); }
  std::unique_ptr<gl::Context> context_;
};

TEST(BytesPerTexel, TheFormatsTechniquesUse) {
  EXPECT_EQ(gl::bytes_per_texel(GL_DEPTH_COMPONENT32F), 4);
  EXPECT_EQ(gl::bytes_per_texel(GL_DEPTH_COMPONENT24), 3);  // requested, not padded
  EXPECT_EQ(gl::bytes_per_texel(GL_DEPTH_COMPONENT16), 2);
  EXPECT_EQ(gl::bytes_per_texel(GL_DEPTH24_STENCIL8), 4);
  EXPECT_EQ(gl::bytes_per_texel(GL_DEPTH32F_STENCIL8), 5);
  EXPECT_EQ(gl::bytes_per_texel(GL_R16F), 2);
  EXPECT_EQ(gl::bytes_per_texel(GL_R32F), 4);
  EXPECT_EQ(gl::bytes_per_texel(GL_RG16F), 4);
  EXPECT_EQ(gl::bytes_per_texel(GL_RG32F), 8);
  EXPECT_EQ(gl::bytes_per_texel(GL_RGBA8), 4);
  EXPECT_EQ(gl::bytes_per_texel(GL_RGBA16F), 8);
  EXPECT_EQ(gl::bytes_per_texel(GL_RGBA32F), 16);
  EXPECT_EQ(gl::bytes_per_texel(GL_RGB32F), 12);
}

TEST(BytesPerTexel, AnUnsizedFormatHasNoSize) {
  EXPECT_THROW(gl::bytes_per_texel(GL_RGBA), JobError);
  EXPECT_THROW(gl::bytes_per_texel(GL_DEPTH_COMPONENT), JobError);
}

TEST_F(GpuMemory, ADepthMapOf1024SquaredIs4MiB) {
  gl::AllocationWindow window;
  const gl::Texture t = gl::make_depth_texture(GL_DEPTH_COMPONENT32F, 1024, 1024, true);
  EXPECT_EQ(window.peak_bytes(), 4 * kMiB);
  EXPECT_EQ(window.live_bytes(), 4 * kMiB);
}

TEST_F(GpuMemory, AFullMipChainCountsEveryLevelRoundedDown) {
  gl::AllocationWindow window;
  const gl::Texture t = gl::make_mipmapped_texture_2d(GL_RG32F, 512, 512, 10);
  GLint levels = 0;
  glGetTextureParameteriv(t.get(), GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
  EXPECT_EQ(levels, 10);
  // 512², 256², ..., 1²: 349525 texels of 8 bytes (not 512²·8·4/3).
  EXPECT_EQ(window.peak_bytes(),
            8 * (262144 + 65536 + 16384 + 4096 + 1024 + 256 + 64 + 16 + 4 + 1));
}

TEST_F(GpuMemory, ANonSquareChainEndsAtOneTexelPerSide) {
  gl::AllocationWindow window;
  // 8x2, 4x1, 2x1, 1x1 of R32F.
  const gl::Texture t = gl::make_mipmapped_texture_2d(GL_R32F, 8, 2, 4);
  EXPECT_EQ(window.peak_bytes(), 4 * (16 + 4 + 2 + 1));
}

TEST_F(GpuMemory, ArrayLayersStayAndA3dDepthHalves) {
  gl::AllocationWindow window;
  const gl::Texture array = gl::make_texture_2d_array(GL_RGBA16F, 64, 64, 5, 2);
  EXPECT_EQ(window.live_bytes(), 8 * 5 * (64 * 64 + 32 * 32));
  const gl::Texture volume = gl::make_texture_3d(GL_RGBA8, 8, 8, 8, 4);
  EXPECT_EQ(window.live_bytes(), 8 * 5 * (64 * 64 + 32 * 32) + 4 * (512 + 64 + 8 + 1));
}

TEST_F(GpuMemory, ARenderbufferCountsItsSamples) {
  gl::AllocationWindow window;
  const gl::Renderbuffer single = gl::make_renderbuffer(GL_DEPTH24_STENCIL8, 100, 50);
  EXPECT_EQ(window.live_bytes(), 100 * 50 * 4);
  const gl::Renderbuffer multi = gl::make_renderbuffer(GL_RGBA8, 100, 50, 4);
  GLint samples = 0;
  glGetNamedRenderbufferParameteriv(multi.get(), GL_RENDERBUFFER_SAMPLES, &samples);
  ASSERT_EQ(samples, 4);
  EXPECT_EQ(window.live_bytes(), 100 * 50 * 4 + 100 * 50 * 4 * 4);
}

TEST_F(GpuMemory, ABufferOfNBytesIsN) {
  gl::AllocationWindow window;
  const gl::Buffer b = gl::make_buffer(1000, nullptr);
  EXPECT_EQ(window.peak_bytes(), 1000);
}

TEST_F(GpuMemory, AStreamCountsItsLatestSizeAndThePeakItsLargest) {
  gl::AllocationWindow window;
  const gl::Buffer s = gl::make_stream_buffer();
  EXPECT_EQ(window.live_bytes(), 0);
  gl::set_buffer_data(s, 300, nullptr, GL_STREAM_DRAW);
  gl::set_buffer_data(s, 120, nullptr, GL_STREAM_DRAW);
  EXPECT_EQ(window.live_bytes(), 120);
  EXPECT_EQ(window.peak_bytes(), 300);
}

TEST_F(GpuMemory, DeletingReleasesButThePeakStays) {
  gl::AllocationWindow window;
  gl::Texture a = gl::make_texture_2d(GL_R32F, 16, 16);
  a.reset();
  const gl::Texture b = gl::make_texture_2d(GL_R16F, 16, 16);
  EXPECT_EQ(window.live_bytes(), 512);
  EXPECT_EQ(window.peak_bytes(), 1024);
}

TEST_F(GpuMemory, NothingOutsideAWindowCounts) {
  gl::Texture before = gl::make_texture_2d(GL_RGBA32F, 64, 64);
  {
    gl::AllocationWindow window;
    const gl::Buffer inside = gl::make_buffer(64, nullptr);
    before.reset();  // made outside: its release takes nothing off
    EXPECT_EQ(window.live_bytes(), 64);
  }
  const gl::Texture between = gl::make_texture_2d(GL_RGBA32F, 64, 64);
  const gl::Buffer stream = gl::make_stream_buffer();
  gl::AllocationWindow window;
  // A stream made before the window (a control's) is refilled in it.
  gl::set_buffer_data(stream, 256, nullptr, GL_STREAM_DRAW);
  EXPECT_EQ(window.peak_bytes(), 0);
}

TEST_F(GpuMemory, NestedWindowsEachCountWhatIsMadeWhileTheyAreOpen) {
  gl::AllocationWindow outer;
  const gl::Buffer first = gl::make_buffer(100, nullptr);
  {
    gl::AllocationWindow inner;
    const gl::Buffer second = gl::make_buffer(40, nullptr);
    gl::Buffer third = gl::make_buffer(10, nullptr);
    third.reset();
    EXPECT_EQ(inner.live_bytes(), 40);  // not `first`, made before it opened
    EXPECT_EQ(inner.peak_bytes(), 50);
    EXPECT_EQ(outer.live_bytes(), 140);
    EXPECT_EQ(outer.peak_bytes(), 150);
  }
  // `second` was deleted as the inner window closed; the outer one saw it.
  EXPECT_EQ(outer.live_bytes(), 100);
  EXPECT_EQ(outer.peak_bytes(), 150);
  const gl::Buffer fourth = gl::make_buffer(7, nullptr);
  EXPECT_EQ(outer.live_bytes(), 107);  // still counting once the inner one closed
}

}  // namespace
}  // namespace sb::test

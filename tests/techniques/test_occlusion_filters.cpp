// The filtered forms of an occlusion texture (techniques/occlusion_texture/
// filter_pyramid.h), built on the GPU from a random binary RGBA texture,
// against box filters computed on the CPU from the same texels: mip levels
// (2^k-aligned block means), N-buffer levels (the mean over the 2^k box that
// starts at each texel, 0 outside), and the summed-area table, exact in
// 32-bit floats and not in 16.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "gl/context.h"
#include "gl/debug.h"
#include "occlusion_texture/filter_pyramid.h"

namespace sb::techniques::occlusion_texture {
namespace {

class OcclusionFilters : public ::testing::Test {
 protected:
  void SetUp() override { context_ = gl::create_context(gl::Backend::OSMesa); }
  std::unique_ptr<gl::Context> context_;
};

// size² RGBA texels of 0 or 1 (about a third set), as bytes and as numbers.
std::vector<uint8_t> random_occlusion(int size, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<uint8_t> texels(size_t(size) * size_t(size) * 4);
  for (uint8_t& t : texels) t = rng() % 3 == 0 ? 255 : 0;
  return texels;
}

void upload(const FilterPyramid& p, const std::vector<uint8_t>& texels) {
  glTextureSubImage2D(p.source(), 0, 0, 0, p.size(), p.size(), GL_RGBA, GL_UNSIGNED_BYTE,
                      texels.data());
}

std::vector<float> read_level(GLuint texture, int level, int layer, int size) {
  std::vector<float> out(size_t(size) * size_t(size) * 4);
  glGetTextureSubImage(texture, level, 0, 0, layer, size, size, 1, GL_RGBA, GL_FLOAT,
                       GLsizei(out.size() * sizeof(float)), out.data());
  gl::throw_if_errors("read level");
  return out;
}

double texel(const std::vector<uint8_t>& t, int size, int x, int y, int c) {
  if (x >= size || y >= size) return 0.0;
  return t[(size_t(y) * size_t(size) + size_t(x)) * 4 + size_t(c)] / 255.0;
}

TEST_F(OcclusionFilters, MipLevelsAreBlockMeans) {
  constexpr int kSize = 64;
  FilterPyramid p(Filter::Mipmap, kSize);
  const auto texels = random_occlusion(kSize, 1);
  upload(p, texels);
  p.build();
  double worst = 0.0;
  for (int k = 1; k < p.levels(); ++k) {
    const int side = 1 << k, n = kSize >> k;
    const std::vector<float> level = read_level(p.filtered(), k, 0, n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        for (int c = 0; c < 4; ++c) {
          double sum = 0.0;
          for (int j = 0; j < side; ++j)
            for (int i = 0; i < side; ++i)
              sum += texel(texels, kSize, x * side + i, y * side + j, c);
          const double mean = sum / double(side * side);
          // RGBA8 levels: each is quantised from the one before, by up to a
          // step per level (llvmpipe's box filter does not round to nearest).
          const double error =
              std::abs(level[(size_t(y) * size_t(n) + size_t(x)) * 4 + size_t(c)] - mean);
          worst = std::max(worst, error / (double(k) / 255.0));
        }
  }
  std::printf("mip levels against block means: worst error %.2f of the quantisation bound\n",
              worst);
  EXPECT_LE(worst, 1.0);
}

TEST_F(OcclusionFilters, NBufferLevelsAreMeansOverTheBoxStartingAtEachTexel) {
  constexpr int kSize = 64;
  FilterPyramid p(Filter::NBuffers, kSize);
  const auto texels = random_occlusion(kSize, 2);
  upload(p, texels);
  p.build();
  double worst = 0.0;
  for (int k = 0; k < p.levels(); ++k) {
    const int side = 1 << k;
    const std::vector<float> level = read_level(p.filtered(), 0, k, kSize);
    for (int y = 0; y < kSize; y += 3)
      for (int x = 0; x < kSize; x += 3)
        for (int c = 0; c < 4; ++c) {
          double sum = 0.0;
          for (int j = 0; j < side; ++j)
            for (int i = 0; i < side; ++i) sum += texel(texels, kSize, x + i, y + j, c);
          const double mean = sum / double(side * side);
          worst = std::max(worst,
                           std::abs(level[(size_t(y) * kSize + size_t(x)) * 4 + size_t(c)] - mean));
        }
  }
  std::printf("N-buffer levels against box means: worst %.5f\n", worst);
  EXPECT_LT(worst, 2e-3);  // RGBA16F levels
}

// The SAT's entry at (x, y) against the integer count of set texels at or
// below and left of it, for 32- and 16-bit floats.
double sat_worst_error(int size, bool half, unsigned seed) {
  FilterPyramid p(Filter::Sat, size, half);
  const auto texels = random_occlusion(size, seed);
  upload(p, texels);
  p.build();
  const std::vector<float> sat = read_level(p.filtered(), 0, 0, size);
  std::vector<double> rows(size_t(size) * size_t(size) * 4), exact(rows.size());
  double worst = 0.0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int c = 0; c < 4; ++c) {
        const size_t i = (size_t(y) * size_t(size) + size_t(x)) * 4 + size_t(c);
        rows[i] = texel(texels, size, x, y, c) + (x > 0 ? rows[i - 4] : 0.0);
        exact[i] = rows[i] + (y > 0 ? exact[i - size_t(size) * 4] : 0.0);
        worst = std::max(worst, std::abs(double(sat[i]) - exact[i]));
      }
  return worst;
}

TEST_F(OcclusionFilters, ThirtyTwoBitSatIsExactAndSixteenBitIsNot) {
  const double f32 = sat_worst_error(256, false, 3);
  const double f16 = sat_worst_error(256, true, 3);
  std::printf("256² SAT, worst |error| in texels: 32-bit %.1f, 16-bit %.1f\n", f32, f16);
  EXPECT_EQ(f32, 0.0);
  // 256² binary texels sum to about 21,800; 16-bit floats space integers 16
  // apart above 16,384.
  EXPECT_GT(f16, 4.0);
}

}  // namespace
}  // namespace sb::techniques::occlusion_texture

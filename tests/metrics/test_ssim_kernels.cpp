// SSIM's kernels (metrics/ssim_kernels.h) on every vector width this CPU
// runs: each must give the baseline's bits, and the one picked must be the
// widest that /proc/cpuinfo lists. On a CPU without AVX-512 (or AVX2) those
// paths cannot run and are left out of the comparison, which says so.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "metrics/metrics.h"
#include "metrics/ssim_kernels.h"
#include "test_util.h"

namespace {

using sb::metrics::detail::SimdPath;

const SimdPath kPaths[] = {SimdPath::Baseline, SimdPath::Avx2, SimdPath::Avx512};

// The CPU's flags, as the kernel reports them.
bool cpuinfo_lists(const std::string& flag) {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("flags", 0) != 0) continue;
    std::istringstream words(line.substr(line.find(':') + 1));
    std::string w;
    while (words >> w)
      if (w == flag) return true;
    return false;
  }
  ADD_FAILURE() << "no flags line in /proc/cpuinfo";
  return false;
}

bool same_bits(const sb::core::ImageF& a, const sb::core::ImageF& b) {
  return a.data.size() == b.data.size() &&
         std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

TEST(SsimKernels, TheWidestPathIsTheWidestTheCpuListsInCpuinfo) {
  const bool avx512 = cpuinfo_lists("avx512f"), avx2 = cpuinfo_lists("avx2");
  EXPECT_EQ(sb::metrics::detail::runs_here(SimdPath::Avx512), avx512);
  EXPECT_EQ(sb::metrics::detail::runs_here(SimdPath::Avx2), avx2);
  const SimdPath expected = avx512 ? SimdPath::Avx512 : avx2 ? SimdPath::Avx2 : SimdPath::Baseline;
  EXPECT_EQ(sb::metrics::detail::widest_simd_path(), expected);
  std::printf("widest SSIM path here: %s\n",
              sb::metrics::detail::to_string(sb::metrics::detail::widest_simd_path()).c_str());
}

// Widths that leave partial chunks and vector tails (the kernels work in
// chunks of 256 values), one and three channels, with and without masks.
TEST(SsimKernels, EveryPathTheCpuRunsGivesTheBaselineBits) {
  int compared = 0;
  for (const auto& [w, h, c] : {std::tuple{300, 37, 1}, {173, 29, 3}, {11, 11, 1}, {97, 64, 3}}) {
    const sb::core::ImageF a = sb::test::pattern_image(w, h, c);
    const sb::core::ImageF b = sb::test::noise_image(w, h, c, uint32_t(w * h + c));
    std::vector<uint8_t> mask(size_t(w) * size_t(h));
    for (size_t i = 0; i < mask.size(); ++i) mask[i] = (i * 7919) % 5 != 0;
    const std::vector<const std::vector<uint8_t>*> masks = {nullptr, &mask};
    const sb::core::ImageF base_map =
        sb::metrics::detail::ssim_map_on(SimdPath::Baseline, a, b, 1.0);
    const std::vector<double> base =
        sb::metrics::detail::ssim_on(SimdPath::Baseline, a, b, 1.0, masks);
    for (const SimdPath path : kPaths) {
      const std::string name = sb::metrics::detail::to_string(path);
      if (!sb::metrics::detail::runs_here(path)) {
        std::printf("%s: not run, this CPU lacks it\n", name.c_str());
        continue;
      }
      SCOPED_TRACE(name + " " + std::to_string(w) + "x" + std::to_string(h) + "x" +
                   std::to_string(c));
      EXPECT_TRUE(same_bits(sb::metrics::detail::ssim_map_on(path, a, b, 1.0), base_map));
      const std::vector<double> got = sb::metrics::detail::ssim_on(path, a, b, 1.0, masks);
      ASSERT_EQ(got.size(), base.size());
      for (size_t m = 0; m < got.size(); ++m)  // bit for bit: NaN (no pixel) equals NaN
        EXPECT_EQ(std::bit_cast<uint64_t>(got[m]), std::bit_cast<uint64_t>(base[m]))
            << "mask " << m << ": " << got[m] << " against " << base[m];
      ++compared;
    }
  }
  // The public functions take the widest path.
  const sb::core::ImageF a = sb::test::pattern_image(64, 48, 3),
                         b = sb::test::noise_image(64, 48, 3, 5);
  const SimdPath widest = sb::metrics::detail::widest_simd_path();
  EXPECT_TRUE(
      same_bits(sb::metrics::ssim_map(a, b), sb::metrics::detail::ssim_map_on(widest, a, b, 1.0)));
  EXPECT_EQ(sb::metrics::ssim(a, b), sb::metrics::detail::ssim_on(widest, a, b, 1.0, {nullptr})[0]);
  EXPECT_GE(compared, 4);  // the baseline, at least, on each shape
}

}  // namespace

// The reference converges at the G-buffer's points: error at 16 spp is larger
// than at 256 spp, both measured against 4096 spp.
#include <gtest/gtest.h>

#include "e2e_util.h"
#include "metrics/metrics.h"

namespace sb::test {

using core::ImageF;

namespace {

using json = nlohmann::json;

ImageF reference_at(int spp) {
  const json config = {{"name", "conv"},
                       {"scenes", json::array({small_scene(2.0)})},
                       {"techniques", json::array({"none"})},
                       {"resolutions", json::array({json::array({96, 72})})},
                       {"frames", {{"warmup", 0}, {"timed", 1}}},
                       {"reference", {{"spp", spp}, {"cache", false}}}};
  return run_config(config, "convergence_" + std::to_string(spp)).reference_visibility();
}

TEST(Reference, ConvergesWithSampleCount) {
  const ImageF truth = reference_at(4096);
  const auto penumbra = metrics::penumbra_mask(truth);
  const double e16 = metrics::compare(reference_at(16), truth, &penumbra).rmse;
  const double e256 = metrics::compare(reference_at(256), truth, &penumbra).rmse;
  EXPECT_GT(e16, e256);
  // Stratified sampling: about N^-0.75, i.e. ~8× from 16 to 256; ask for 3×.
  EXPECT_GT(e16 / e256, 3.0) << e16 << " vs " << e256;
}

}  // namespace
}  // namespace sb::test

// The summary's lines: what the bench's means are measured against.
#include "saagen/report/summary.hpp"

#include <gtest/gtest.h>

namespace measure = saagen::measure;
namespace report = saagen::report;

// The bench's "errors against the ... ground truth" names the sample counts of the scenes measured
// at their own sizes (the presets' glTF scenes), not only the config's.
TEST(Summary, TheGroundTruthSamplesNameTheScenesWithTheirOwnSizes) {
  measure::TradeConfig config;
  config.strata = 16;
  config.scenes = {measure::SceneId::sphere, measure::SceneId::torus};
  EXPECT_EQ(report::ground_truth_samples(config), "256-spp ground truth");
  config.scene_sizes = {{measure::SceneId::torus, 64, 64, 64, 32, 32, 64}, {measure::SceneId::tubes, 64, 64, 8, 32, 32, 8}};
  EXPECT_EQ(report::ground_truth_samples(config), "256-spp ground truth (spp on the scenes of their own size: torus 4096)");
}

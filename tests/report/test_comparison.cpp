// The lag gate (report/comparison.hpp, lag_of): a result is late when its frames are closer to
// the ground truth's previous frames than to their own beyond the interval. The bias of the ground
// truth's samples (MetricDifference::sample_bias): a call it would change is a tie.
#include "saagen/report/comparison.hpp"
#include "saagen/report/trade_json.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace saagen;

namespace {

// One cell of 16 frames against two seeds: every frame's lag is `lag` plus a small alternating noise.
measure::SeedSeries lag_series(double lag) {
  measure::SeedSeries series;
  for (int t = 0; t < 16; ++t) {
    series[0].push_back(lag + (t % 2 ? 1e-6 : -1e-6));
    series[1].push_back(lag + (t % 2 ? -1e-6 : 1e-6));
  }
  return series;
}

// With |motion|^2 = 1e-4 per frame, E[lag] = (2 tau - 1) 1e-4 for a result tau frames late: on
// time -1e-4, a whole frame late +1e-4, a tenth of a frame -0.8e-4.
TEST(LagOf, AFrameLateIsLateAndATenthOfAFrameIsNot) {
  const std::vector<measure::SeedSeries> frame_late(3, lag_series(1e-4)), tenth_late(3, lag_series(-0.8e-4));
  const report::MetricDifference late = report::lag_of(frame_late);
  EXPECT_NEAR(late.difference.mean, 1e-4, 1e-9);
  EXPECT_EQ(report::outcome_of(late), report::MetricOutcome::worse);
  EXPECT_EQ(report::outcome_of(report::lag_of(tenth_late)), report::MetricOutcome::better);
  // A lag of 0 within its noise (a result as far from either frame, e.g. without its highlight) is not late.
  std::vector<measure::SeedSeries> spanning(3, lag_series(0.0));
  spanning[1] = lag_series(2e-6), spanning[2] = lag_series(-2e-6);
  EXPECT_EQ(report::outcome_of(report::lag_of(spanning)), report::MetricOutcome::tie);
}

// A table without the lag (older tables): nothing is late.
TEST(LagOf, WithoutTheSeriesItIsATie) {
  const std::vector<measure::SeedSeries> empty(2);
  const report::MetricDifference d = report::lag_of(empty);
  EXPECT_EQ(report::outcome_of(d), report::MetricOutcome::tie);
  EXPECT_EQ(d.difference.mean, 0.0);
}

// One cell's image series of 16 frames, `value` against both seeds with a small alternating noise.
measure::AnimationSeries image_cell(double value) {
  measure::AnimationSeries cell;
  cell.image = lag_series(value);
  return cell;
}

// Three cells where the configuration reads 0.002 worse than no SAA against the full ground truth.
// Against the quarter-sample one it reads `quarter_difference` worse; the bias of the full
// ground truth's samples is a third of the gap, (quarter - full) / 3 (Richardson extrapolation).
report::PairedComparison image_worse_by_0_002(double quarter_difference) {
  const measure::AnimationSeries configuration = image_cell(0.012), none = image_cell(0.010);
  const measure::AnimationSeries configuration_quarter = image_cell(0.010 + quarter_difference), none_quarter = image_cell(0.010);
  const std::vector<report::CellPair> cells(3, {&configuration, &none, &configuration_quarter, &none_quarter});
  return report::compare_cells("filter", "none", cells);
}

TEST(SampleBias, ACallTheBiasWouldChangeIsATie) {
  // Quarter 0.008 worse: the bias is 0.002, all of the difference.
  const report::PairedComparison biased = image_worse_by_0_002(0.008);
  EXPECT_NEAR(biased.image.sample_bias.value(), 0.002, 1e-9);
  EXPECT_TRUE(biased.image.bias_limited);
  EXPECT_EQ(report::outcome_of(biased.image), report::MetricOutcome::tie);
  EXPECT_NEAR(report::without_sample_bias(biased.image).difference.mean, 0.0, 1e-9);
  // The decision reads it as a tie too: its interval is widened to include 0.
  const decision::Comparison read = report::to_decision(biased);
  EXPECT_LE(read.image.low, 0.0);
  EXPECT_GE(read.image.high, 0.0);
  // The bench's JSON carries both, beside the outcome they give.
  const nlohmann::json written = report::difference_json(biased.image);
  EXPECT_NEAR(written.at("sample_bias").get<double>(), 0.002, 1e-9);
  EXPECT_TRUE(written.at("bias_limited").get<bool>());
  EXPECT_EQ(written.at("outcome"), "tie");
}

TEST(SampleBias, ACallThatHoldsWithoutTheBiasStands) {
  // Quarter 0.0035 worse: the bias is 0.0005 and the difference without it, 0.0015, is still worse.
  const report::PairedComparison held = image_worse_by_0_002(0.0035);
  EXPECT_NEAR(held.image.sample_bias.value(), 0.0005, 1e-9);
  EXPECT_FALSE(held.image.bias_limited);
  EXPECT_EQ(report::outcome_of(held.image), report::MetricOutcome::worse);
  EXPECT_GT(report::to_decision(held).image.low, 0.0);
}

// Cells without the quarter-sample readings (a TAA row, `saagen score` clips): no sample bias.
TEST(SampleBias, WithoutTheQuarterSampleReadingsThereIsNone) {
  const measure::AnimationSeries configuration = image_cell(0.012), none = image_cell(0.010);
  const std::vector<report::CellPair> cells(3, {&configuration, &none});
  const report::PairedComparison c = report::compare_cells("filter", "none", cells);
  EXPECT_FALSE(c.image.sample_bias.has_value());
  EXPECT_FALSE(c.image.bias_limited);
  EXPECT_EQ(report::outcome_of(c.image), report::MetricOutcome::worse);
  EXPECT_FALSE(report::difference_json(c.image).contains("sample_bias"));
}

// One cell whose configuration ties with no SAA in the image error as read (the same values) and
// beats it in the video error by 1 (one value per seed): it beats no SAA. Against the quarter-sample
// ground truth the image error reads 0.006 better, so the bias of the full ground truth's samples
// is -0.002 (comparison.hpp): taken out, the image error is 0.002 worse and the pair is mixed.
// Each metric's own call is a tie or holds, yet the pair's reverses (beats <-> mixed): more samples
// would change it, and the verdict reads it as a tie.
TEST(SampleBias, APairOfCallsTheBiasWouldReverseIsATie) {
  const auto cell = [](double image, double video) {
    measure::AnimationSeries series = image_cell(image);
    series.video = {std::vector<double>{video}, std::vector<double>{video}};
    return series;
  };
  const measure::AnimationSeries configuration = cell(0.010, 1.0), none = cell(0.010, 2.0);
  const measure::AnimationSeries configuration_quarter = cell(0.004, 1.0), none_quarter = cell(0.010, 2.0);
  const std::vector<report::CellPair> cells(3, {&configuration, &none, &configuration_quarter, &none_quarter});
  const report::PairedComparison c = report::compare_cells("filter", "none", cells);
  ASSERT_TRUE(c.video.has_value());
  EXPECT_EQ(report::standing(c.image, *c.video), report::Standing::beats);
  EXPECT_NEAR(report::without_sample_bias(c.image).difference.mean, 0.002, 1e-9);
  EXPECT_EQ(report::standing(report::without_sample_bias(c.image), report::without_sample_bias(*c.video)), report::Standing::against);
  EXPECT_TRUE(c.unconverged);
  EXPECT_EQ(report::comparison_outcome_name(c), "ties");
  const decision::Comparison read = report::to_decision(c);
  EXPECT_TRUE(read.unconverged);
  EXPECT_EQ(decision::outcome(read), decision::Outcome::ties);
  // Without the quarter-sample readings nothing is known of the bias: it beats.
  const std::vector<report::CellPair> unpaired(3, {&configuration, &none});
  const report::PairedComparison without = report::compare_cells("filter", "none", unpaired);
  EXPECT_FALSE(without.unconverged);
  EXPECT_EQ(report::comparison_outcome_name(without), "beats");
}

}  // namespace

// The verdict metrics' parts (animation_error.hpp) on hand-made frames whose values are worked
// out in the comments: the pooling, the flicker error's treatment of a displaced, a frozen and a
// missing highlight (the cases the temporal difference error got wrong), and the intervals.
#include "saagen/measure/animation_error.hpp"
#include "saagen/measure/image.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

using namespace saagen::measure;

namespace {

// A 32 x 32 frame, black but for a one-pixel highlight of `value` at (x, y).
Image highlight(int x, int y, float value = 1.0f) {
  Image image(32, 32, 0.0f);
  image.at(x, y) = value;
  return image;
}

double mean_of(const Image& image) {
  return std::accumulate(image.pixels.begin(), image.pixels.end(), 0.0) / static_cast<double>(image.size());
}

double flicker(const Image& result_previous, const Image& result, const Image& reference_previous, const Image& reference) {
  return flicker_error(pooled_change(result_previous, result), pooled_change(reference_previous, reference)).error;
}

TEST(GaussianPooled, KeepsTheMassOfAnInteriorPointAndItsValueOnAConstant) {
  // Normalised weights: an interior impulse keeps its sum (1/1024 mean over 32^2 pixels); a
  // constant image stays constant, at the borders too (renormalised there).
  const Image pooled = gaussian_pooled(highlight(16, 16), 1.5);
  EXPECT_NEAR(mean_of(pooled), 1.0 / 1024.0, 1e-9);
  EXPECT_LT(pooled.at(16, 16), 0.1);  // 1 / (2 pi 1.5^2) = 0.0707 before truncation
  EXPECT_GT(pooled.at(16, 16), 0.06);
  const Image constant = gaussian_pooled(Image(32, 32, 0.25f), 1.5);
  for (float v : constant.pixels) EXPECT_NEAR(v, 0.25, 1e-6);
}

// The ground truth's highlight moves one pixel right; the result's moves one pixel right too but
// one pixel lower (displaced). Per pixel (TDE) the result's two changed pixels and the
// reference's two are all counted: four units of change. Pooled, the two changes overlap almost
// entirely, so the flicker error is a fraction of the frozen result's, which misses all the motion.
TEST(FlickerError, CountsADisplacedHighlightLessThanAFrozenOne) {
  const Image r0 = highlight(10, 10), r1 = highlight(11, 10);
  const Image displaced0 = highlight(10, 11), displaced1 = highlight(11, 11);
  const double displaced = flicker(displaced0, displaced1, r0, r1);
  const double frozen = flicker(r0, r0, r0, r1);
  // Frozen: the result's change is 0, so the error is the reference's pooled change: its mass,
  // 2 (two pixels changed by 1) over 1024 pixels.
  EXPECT_NEAR(frozen, 2.0 / 1024.0, 1e-6);
  EXPECT_GT(displaced, 0.45 * frozen);
  EXPECT_LT(displaced, 0.56 * frozen);
  // TDE counts the displaced highlight twice the frozen one.
  const Image a[] = {displaced0, displaced1}, b[] = {r0, r1}, f[] = {r0, r0};
  EXPECT_NEAR(temporal_difference_error(a, b).tde, 2.0 * temporal_difference_error(f, b).tde, 1e-9);
}

// A missing highlight (black result) and a frozen one miss the same motion: equal errors, all of
// it "missing"; a result that flickers where the reference does not is all "excess".
TEST(FlickerError, SplitsExcessAndMissingChange) {
  const Image black(32, 32, 0.0f), r0 = highlight(10, 10), r1 = highlight(11, 10);
  const FlickerError missing = flicker_error(pooled_change(black, black), pooled_change(r0, r1));
  EXPECT_NEAR(missing.error, 2.0 / 1024.0, 1e-6);
  EXPECT_EQ(missing.excess, 0.0);
  EXPECT_NEAR(missing.missing, missing.error, 1e-12);
  const FlickerError popping = flicker_error(pooled_change(highlight(8, 8), highlight(20, 20)), pooled_change(black, black));
  EXPECT_NEAR(popping.error, 2.0 / 1024.0, 1e-6);
  EXPECT_EQ(popping.missing, 0.0);
}

TEST(FlickerError, IdenticalAnimationsScoreZero) {
  const Image r0 = highlight(10, 10, 0.3f), r1 = highlight(12, 9, 0.8f);
  EXPECT_EQ(flicker(r0, r1, r0, r1), 0.0);
}

// The ground truth's highlight moves from (10, 10) to (11, 10). A result on time scores the
// motion's energy below 0 (-2 pixels of unit change over 1024), one a frame late the same above;
// a result that shows no highlight scores 0 (as far from either frame).
TEST(LagError, IsMinusTheMotionOnTimeAndPlusItAFrameLate) {
  const Image previous = highlight(10, 10), current = highlight(11, 10);
  EXPECT_NEAR(lag_error(current, current, previous), -2.0 / 1024.0, 1e-12);
  EXPECT_NEAR(lag_error(previous, current, previous), 2.0 / 1024.0, 1e-12);
  EXPECT_NEAR(lag_error(Image(32, 32, 0.0f), current, previous), 0.0, 1e-12);
  // A dimmer highlight on time: (0.5 - 1)^2 on time against 1 + 0.5^2 a frame late.
  EXPECT_NEAR(lag_error(highlight(11, 10, 0.5f), current, previous), (0.25 - 1.25) / 1024.0, 1e-12);
}

TEST(Intervals, StudentQuantilesMatchTheTableAndTheNormalLimit) {
  EXPECT_DOUBLE_EQ(student_t_975(1), 12.706);
  EXPECT_DOUBLE_EQ(student_t_975(10), 2.228);
  EXPECT_NEAR(student_t_975(40), 2.021, 1e-3);   // tables: 2.021
  EXPECT_NEAR(student_t_975(120), 1.980, 1e-3);  // tables: 1.980
  EXPECT_NEAR(student_t_975(100000), 1.96, 1e-3);
}

TEST(Intervals, BlockMeansOfSixteenFramesAreFourBlocks) {
  std::vector<double> series(16);
  std::iota(series.begin(), series.end(), 0.0);  // 0 .. 15
  EXPECT_EQ(block_means(series), (std::vector<double>{1.5, 5.5, 9.5, 13.5}));
  // 15 values: three blocks of four, the last takes the remainder (8 .. 14: mean 11).
  series.pop_back();
  EXPECT_EQ(block_means(series), (std::vector<double>{1.5, 5.5, 11.0}));
  // Shorter than two blocks: one unit per value.
  EXPECT_EQ(block_means(std::vector<double>{1.0, 2.0, 4.0}).size(), 3u);
}

TEST(Intervals, MeanIntervalIsTheTIntervalWidenedByTheGroundTruth) {
  // Units 1, 2, 3: mean 2, sample sd 1, se 1/sqrt(3); t_{0.975,2} = 4.303.
  const std::vector<double> units{1.0, 2.0, 3.0};
  const Interval sampling = mean_interval(units, 0.0);
  EXPECT_DOUBLE_EQ(sampling.mean, 2.0);
  EXPECT_NEAR(sampling.half_width(), 4.303 / std::sqrt(3.0), 1e-12);
  // A ground-truth standard deviation of 1 adds 1.96 in quadrature.
  const Interval widened = mean_interval(units, 1.0);
  EXPECT_NEAR(widened.half_width(), std::hypot(4.303 / std::sqrt(3.0), 1.959964), 1e-9);
}

TEST(Intervals, GroundTruthSpreadIsHalfTheSeedDifferenceOverCells) {
  // Two cells whose seeds differ by 0.2 and 0.4: half-differences 0.1 and 0.2; the mean over the
  // two cells has sd sqrt(0.1^2 + 0.2^2) / 2.
  EXPECT_NEAR(ground_truth_spread(std::vector<double>{1.0, 2.0}, std::vector<double>{0.8, 2.4}), std::sqrt(0.05) / 2.0, 1e-12);
}

// The difference of two configurations, paired frame by frame: a constant offset of 0.01 on every
// frame has a zero-width sampling interval, whatever the frames' own variation.
TEST(Intervals, PairedDifferenceRemovesTheCommonVariation) {
  SeedSeries a, b;
  for (int t = 0; t < 16; ++t) {
    const double shared = 0.1 * std::sin(t);
    a[0].push_back(shared + 0.01);
    b[0].push_back(shared);
  }
  const SeedSeries d = paired_difference(a, b);
  const Interval interval = series_interval(std::span<const SeedSeries>(&d, 1));
  EXPECT_NEAR(interval.mean, 0.01, 1e-12);
  EXPECT_NEAR(interval.half_width(), 0.0, 1e-12);
}

}  // namespace

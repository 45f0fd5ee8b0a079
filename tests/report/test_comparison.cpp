// The lag gate (report/comparison.hpp, lag_of): a result is late when its frames are closer to
// the ground truth's previous frames than to their own beyond the interval.
#include "saagen/report/comparison.hpp"

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

}  // namespace

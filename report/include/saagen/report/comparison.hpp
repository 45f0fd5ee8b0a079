// Paired comparisons of two configurations of a trade table, with 95 % intervals: the numbers
// every verdict (beats / ties / loses) is read from.
//
// For each cell (a scene and material both configurations were measured on), the two rows' verdict
// series (trade.hpp, AnimationSeries) are differenced frame by frame against each ground-truth
// seed (paired: the same frames, pixels and references); the difference's mean over the cells
// gets the interval of measure::series_interval(): the variation over frame blocks, pixels and
// cells, widened by the ground truth's Monte-Carlo error (the spread between the two seeds).
#pragma once

#include "saagen/decision.hpp"
#include "saagen/measure/trade.hpp"

#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace saagen::report {

// One metric's difference (configuration - baseline; lower is better) and the ground truth's part
// of its uncertainty.
struct MetricDifference {
  measure::Interval difference;
  double ground_truth_sd = 0.0;  // standard deviation of the mean due to the ground truth alone
  // The ground truth's noise is larger than a quarter of the difference: too noisy to call, a tie
  // whatever the interval says (more ground-truth samples would settle it).
  bool ground_truth_limited = false;
  // The bias the ground truth's finite samples leave in the difference, where every cell was also
  // read against the quarter-sample ground truth (the sanity suite's; TradeRow::quarter_series):
  // by Richardson extrapolation (L. F. Richardson, 1911), a metric against an N-sample Monte Carlo
  // ground truth is biased by about c / N (for a squared error exactly the ground truth's variance),
  // so the quarter-sample reading is biased by 4 c / N and the bias is (quarter - difference) / 3.
  std::optional<double> sample_bias;
  // The call (better, tie, worse) and the call with that bias taken out (without_sample_bias)
  // differ: more ground-truth samples would change it, so it is a tie whatever the interval says.
  bool bias_limited = false;
};

// The difference moved by `shift` (its mean and interval), the ground truth's share of it
// (ground_truth_limited) judged anew at the moved mean.
MetricDifference shifted(MetricDifference difference, double shift);

// The difference with its sample_bias taken out (itself where it has none): what more ground-truth
// samples would read, with the same interval width.
MetricDifference without_sample_bias(const MetricDifference& difference);

enum class MetricOutcome { better, tie, worse };
// better: the interval lies below 0; worse: above; tie: it spans 0, or the ground truth limits
// (its noise, ground_truth_limited, or its samples' bias, bias_limited).
MetricOutcome outcome_of(const MetricDifference& difference);
std::string_view metric_outcome_name(MetricOutcome outcome);  // "better", "tie", "worse"

// How a comparison stands as the decision reads it, from its image and temporal differences:
// beats (better beyond the interval in one, worse in neither), against (worse in one: loses or
// mixed, never taken) or ties (neither).
enum class Standing { beats, ties, against };
Standing standing(const MetricDifference& image, const MetricDifference& temporal);
std::string_view standing_name(Standing standing);  // "beats", "ties", "against"

struct PairedComparison {
  std::string configuration;
  std::string baseline;
  int cells = 0;             // 0: no cell has both (the comparison is empty)
  MetricDifference image;    // image_error (LDR-FLIP per frame of the animation)
  MetricDifference flicker;  // flicker_error (pooled change)
  // video_error (10 - ColorVideoVDP's JOD of the clip), when every cell has it: the verdict's
  // temporal metric (to_decision); without it the flicker error is.
  std::optional<MetricDifference> video;
  // The configuration's own lag (lag_of; not a difference to the baseline): the decision's gate,
  // not a merit (decision::late). All 0 where the table has no lag.
  MetricDifference lag;
  // The call reverses once the bias of the ground truth's samples is taken out of both metrics
  // (standing of the metrics as read against their without_sample_bias): each metric's own call
  // can hold (bias_limited is per metric) while the pair's turns, e.g. beats on the video error with
  // the image error a tie that is worse without the bias. More samples would change the call, so
  // the verdict reads it as a tie (comparison_outcome_name, to_decision: decision::Comparison's
  // unconverged), not as a win or a loss.
  bool unconverged = false;
};
// The metric the verdict reads as temporal: the video metric where measured, else the flicker error.
const MetricDifference& temporal_metric(const PairedComparison& comparison);

using CellFilter = std::function<bool(const measure::TradeRow&)>;
// `configuration` against `baseline` over the non-Fresnel cells `keep` accepts (a row of the
// configuration and the baseline's row of the same scene and material). The ids tell TAA apart
// ("none+taa" is no SAA under TAA): "deferred-aniso+taa/tail" against "none+taa" compares under
// TAA, "none+taa" against "none" what TAA alone does.
PairedComparison compare_configurations(const measure::TradeTable& table, const std::string& configuration, const std::string& baseline,
                                        const CellFilter& keep);

// A table's non-Fresnel rows by configuration id (measure::configuration_id), in the table's
// order: built once where many comparisons read one table (a content's decision pairs every
// configuration with no SAA on every scene and cell), so that each reads two configurations' rows
// instead of the whole table.
class ConfigurationRows {
 public:
  explicit ConfigurationRows(const measure::TradeTable& table);
  std::span<const measure::TradeRow* const> of(const std::string& configuration) const;

 private:
  std::map<std::string, std::vector<const measure::TradeRow*>, std::less<>> rows_;
};
// compare_configurations on the index: the same comparison.
PairedComparison compare_configurations(const ConfigurationRows& rows, const std::string& configuration, const std::string& baseline,
                                        const CellFilter& keep);

// The same over given cells: per cell, the configuration's series and the baseline's (of the same
// content, frames and ground-truth seeds); what compare_configurations computes once it has
// paired a table's rows, and `saagen score` on clips rendered elsewhere.
// Where both also have their series against the quarter-sample ground truth, each metric's
// difference carries its sample_bias (and bias_limited) when every cell has them.
struct CellPair {
  const measure::AnimationSeries* configuration = nullptr;
  const measure::AnimationSeries* baseline = nullptr;
  const measure::AnimationSeries* configuration_quarter = nullptr;
  const measure::AnimationSeries* baseline_quarter = nullptr;
};
PairedComparison compare_cells(const std::string& configuration, const std::string& baseline, std::span<const CellPair> cells);

// The verdict's reading of a comparison (image and temporal_metric): "beats" (better beyond the interval in one metric, worse
// in none), "loses" (worse in one, better in none), "ties" (neither, or unconverged), "mixed"
// (better in one, worse in the other: not a win).
std::string_view comparison_outcome_name(const PairedComparison& comparison);

// The comparison as saagen's decision reads it (saagen/decision.hpp): image = image_error's
// difference, temporal = temporal_metric()'s, lag = the lag's. A difference the ground truth limits
// (MetricDifference::ground_truth_limited or bias_limited) is a tie whatever its interval: its
// interval is widened to include 0.
decision::Comparison to_decision(const PairedComparison& comparison);

// The same for two series of one cell (a sanity result against a row, two rows).
MetricDifference compare_series(std::span<const measure::SeedSeries> a, std::span<const measure::SeedSeries> b);

// A result's own lag over cells (animation_error.hpp, lag_error), with its interval: a result
// shown tau frames late, R_t = E I_{t - tau}, has E[lag] = (2 tau - 1) |motion|^2, so a lag above
// 0 beyond the interval says its frames follow the ground truth more than half a frame late,
// whatever the motion's size. The interval includes the ground truth's spread; the quarter rule
// (ground_truth_limited) does not apply to this gate.
MetricDifference lag_of(std::span<const measure::SeedSeries> cells);

}  // namespace saagen::report

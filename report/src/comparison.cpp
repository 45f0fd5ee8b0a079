// Paired comparisons with intervals (see comparison.hpp).
#include "saagen/report/comparison.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace saagen::report {

MetricOutcome outcome_of(const MetricDifference& d) {
  if (d.ground_truth_limited || d.bias_limited) return MetricOutcome::tie;
  if (d.difference.high < 0.0) return MetricOutcome::better;
  if (d.difference.low > 0.0) return MetricOutcome::worse;
  return MetricOutcome::tie;
}

std::string_view metric_outcome_name(MetricOutcome outcome) {
  switch (outcome) {
    case MetricOutcome::better:
      return "better";
    case MetricOutcome::worse:
      return "worse";
    case MetricOutcome::tie:
      break;
  }
  return "tie";
}

const MetricDifference& temporal_metric(const PairedComparison& c) { return c.video ? *c.video : c.flicker; }

Standing standing(const MetricDifference& image, const MetricDifference& temporal) {
  const MetricOutcome a = outcome_of(image), b = outcome_of(temporal);
  if (a == MetricOutcome::worse || b == MetricOutcome::worse) return Standing::against;
  return a == MetricOutcome::better || b == MetricOutcome::better ? Standing::beats : Standing::ties;
}

std::string_view standing_name(Standing s) { return s == Standing::beats ? "beats" : s == Standing::ties ? "ties" : "against"; }

namespace {

// Whether a call reverses between two readings (beats <-> against; a move to or from a tie does not).
bool reverses(Standing read, Standing other) { return read != other && read != Standing::ties && other != Standing::ties; }

}  // namespace

std::string_view comparison_outcome_name(const PairedComparison& c) {
  if (c.unconverged) return "ties";
  const MetricOutcome image = outcome_of(c.image), flicker = outcome_of(temporal_metric(c));
  const bool better = image == MetricOutcome::better || flicker == MetricOutcome::better;
  const bool worse = image == MetricOutcome::worse || flicker == MetricOutcome::worse;
  if (better && worse) return "mixed";
  if (better) return "beats";
  if (worse) return "loses";
  return "ties";
}

namespace {

decision::Difference decision_difference(const MetricDifference& d) {
  decision::Difference out{d.difference.mean, d.difference.low, d.difference.high};
  if (d.ground_truth_limited || d.bias_limited) out.low = std::min(out.low, 0.0), out.high = std::max(out.high, 0.0);
  return out;
}

}  // namespace

decision::Comparison to_decision(const PairedComparison& c) {
  return {decision_difference(c.image), decision_difference(temporal_metric(c)), decision_difference(c.lag), c.unconverged};
}

namespace {
// The ground truth's noise is larger than a quarter of the difference (MetricDifference).
bool limited_by_ground_truth(const MetricDifference& d) { return d.ground_truth_sd > 0.25 * std::fabs(d.difference.mean); }
}  // namespace

MetricDifference compare_series(std::span<const measure::SeedSeries> a, std::span<const measure::SeedSeries> b) {
  if (a.size() != b.size()) throw std::invalid_argument("compare_series: different cell counts");
  std::vector<measure::SeedSeries> differences;
  differences.reserve(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) differences.push_back(measure::paired_difference(a[i], b[i]));
  MetricDifference d;
  d.difference = measure::series_interval(differences);
  d.ground_truth_sd = measure::series_ground_truth_sd(differences);
  d.ground_truth_limited = limited_by_ground_truth(d);
  return d;
}

MetricDifference shifted(MetricDifference d, double shift) {
  d.difference.mean += shift;
  d.difference.low += shift;
  d.difference.high += shift;
  d.ground_truth_limited = limited_by_ground_truth(d);
  return d;
}

MetricDifference without_sample_bias(const MetricDifference& d) {
  MetricDifference unbiased = shifted(d, -d.sample_bias.value_or(0.0));
  unbiased.sample_bias.reset();
  unbiased.bias_limited = false;
  return unbiased;
}

namespace {

// `d` against the same cells' reading against the quarter-sample ground truth: its sample_bias,
// and whether the call holds once it is taken out.
void judge_sample_bias(MetricDifference& d, const MetricDifference& quarter) {
  d.sample_bias = (quarter.difference.mean - d.difference.mean) / 3.0;
  d.bias_limited = outcome_of(d) != outcome_of(without_sample_bias(d));
}

bool measured(const measure::SeedSeries& series) { return !series[0].empty(); }

// One metric of every cell (`metric` of the AnimationSeries): the configuration's and the
// baseline's, and their readings against the quarter-sample ground truth where every cell has them.
struct MetricCells {
  std::vector<measure::SeedSeries> a, b, quarter_a, quarter_b;
};

MetricCells metric_cells(std::span<const CellPair> cells, measure::SeedSeries measure::AnimationSeries::*metric) {
  MetricCells out;
  bool quarters = true;
  for (const CellPair& cell : cells) {
    out.a.push_back(cell.configuration->*metric);
    out.b.push_back(cell.baseline->*metric);
    quarters = quarters && cell.configuration_quarter && cell.baseline_quarter && measured(cell.configuration_quarter->*metric) &&
               measured(cell.baseline_quarter->*metric);
    if (quarters) out.quarter_a.push_back(cell.configuration_quarter->*metric), out.quarter_b.push_back(cell.baseline_quarter->*metric);
  }
  if (!quarters) out.quarter_a.clear(), out.quarter_b.clear();
  return out;
}

MetricDifference compare_metric(const MetricCells& cells) {
  MetricDifference d = compare_series(cells.a, cells.b);
  if (!cells.quarter_a.empty()) judge_sample_bias(d, compare_series(cells.quarter_a, cells.quarter_b));
  return d;
}

}  // namespace

MetricDifference lag_of(std::span<const measure::SeedSeries> cells) {
  if (cells.empty() || !std::all_of(cells.begin(), cells.end(), measured)) return {};
  MetricDifference d;
  d.difference = measure::series_interval(cells);
  d.ground_truth_sd = measure::series_ground_truth_sd(cells);
  return d;
}

PairedComparison compare_cells(const std::string& configuration, const std::string& baseline, std::span<const CellPair> cells) {
  PairedComparison c{configuration, baseline, static_cast<int>(cells.size()), {}, {}, std::nullopt, {}};
  if (c.cells == 0) return c;
  c.image = compare_metric(metric_cells(cells, &measure::AnimationSeries::image));
  c.flicker = compare_metric(metric_cells(cells, &measure::AnimationSeries::flicker));
  const MetricCells video = metric_cells(cells, &measure::AnimationSeries::video);
  if (std::all_of(video.a.begin(), video.a.end(), measured) && std::all_of(video.b.begin(), video.b.end(), measured))
    c.video = compare_metric(video);
  c.lag = lag_of(metric_cells(cells, &measure::AnimationSeries::lag).a);
  const MetricDifference& temporal = temporal_metric(c);
  c.unconverged = reverses(standing(c.image, temporal), standing(without_sample_bias(c.image), without_sample_bias(temporal)));
  return c;
}

ConfigurationRows::ConfigurationRows(const measure::TradeTable& table) {
  for (const measure::TradeRow& row : table.rows)
    if (!row.fresnel) rows_[measure::configuration_id(row)].push_back(&row);
}

std::span<const measure::TradeRow* const> ConfigurationRows::of(const std::string& configuration) const {
  const auto found = rows_.find(configuration);
  if (found == rows_.end()) return {};
  return found->second;
}

PairedComparison compare_configurations(const ConfigurationRows& rows, const std::string& configuration, const std::string& baseline,
                                        const CellFilter& keep) {
  using Cell = std::tuple<measure::SceneId, double>;
  std::map<Cell, const measure::TradeRow*> baseline_rows;
  for (const measure::TradeRow* row : rows.of(baseline)) baseline_rows[{row->scene, row->alpha}] = row;
  std::vector<CellPair> cells;
  for (const measure::TradeRow* row : rows.of(configuration)) {
    if (!keep(*row)) continue;
    const auto base = baseline_rows.find({row->scene, row->alpha});
    if (base == baseline_rows.end()) continue;
    const measure::TradeRow& baseline_row = *base->second;
    cells.push_back({&row->series, &baseline_row.series, &row->quarter_series, &baseline_row.quarter_series});
  }
  return compare_cells(configuration, baseline, cells);
}

PairedComparison compare_configurations(const measure::TradeTable& table, const std::string& configuration, const std::string& baseline,
                                        const CellFilter& keep) {
  return compare_configurations(ConfigurationRows(table), configuration, baseline, keep);
}

}  // namespace saagen::report

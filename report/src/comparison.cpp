// Paired comparisons with intervals (see comparison.hpp).
#include "saagen/report/comparison.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace saagen::report {

MetricOutcome outcome_of(const MetricDifference& d) {
  if (d.ground_truth_limited) return MetricOutcome::tie;
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

std::string_view comparison_outcome_name(const PairedComparison& c) {
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
  if (d.ground_truth_limited) out.low = std::min(out.low, 0.0), out.high = std::max(out.high, 0.0);
  return out;
}

}  // namespace

decision::Comparison to_decision(const PairedComparison& c) {
  return {decision_difference(c.image), decision_difference(temporal_metric(c)), decision_difference(c.lag)};
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

MetricDifference lag_of(std::span<const measure::SeedSeries> cells) {
  const bool measured =
      !cells.empty() && std::all_of(cells.begin(), cells.end(), [](const measure::SeedSeries& s) { return !s[0].empty(); });
  if (!measured) return {};
  MetricDifference d;
  d.difference = measure::series_interval(cells);
  d.ground_truth_sd = measure::series_ground_truth_sd(cells);
  return d;
}

PairedComparison compare_cells(const std::string& configuration, const std::string& baseline, std::span<const CellPair> cells) {
  std::vector<measure::SeedSeries> image_a, image_b, flicker_a, flicker_b, video_a, video_b, lag_a;
  for (const CellPair& cell : cells) {
    image_a.push_back(cell.configuration->image);
    image_b.push_back(cell.baseline->image);
    flicker_a.push_back(cell.configuration->flicker);
    flicker_b.push_back(cell.baseline->flicker);
    video_a.push_back(cell.configuration->video);
    video_b.push_back(cell.baseline->video);
    lag_a.push_back(cell.configuration->lag);
  }
  PairedComparison c{configuration, baseline, static_cast<int>(image_a.size()), {}, {}, std::nullopt, {}};
  if (c.cells == 0) return c;
  c.image = compare_series(image_a, image_b);
  c.flicker = compare_series(flicker_a, flicker_b);
  const auto measured = [](const measure::SeedSeries& series) { return !series[0].empty(); };
  if (std::all_of(video_a.begin(), video_a.end(), measured) && std::all_of(video_b.begin(), video_b.end(), measured))
    c.video = compare_series(video_a, video_b);
  c.lag = lag_of(lag_a);
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
    if (base != baseline_rows.end()) cells.push_back({&row->series, &base->second->series});
  }
  return compare_cells(configuration, baseline, cells);
}

PairedComparison compare_configurations(const measure::TradeTable& table, const std::string& configuration, const std::string& baseline,
                                        const CellFilter& keep) {
  return compare_configurations(ConfigurationRows(table), configuration, baseline, keep);
}

}  // namespace saagen::report

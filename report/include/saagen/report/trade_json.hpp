// The bench's JSON (`saagen bench --json`): the trade rows in the format bench_shading --json
// uses, each carrying "error" (mean LDR-FLIP), so that `saagen plan --trade-table` can choose by
// accuracy; the full trade rows; and saagen's decisions, for the scripts to read instead of
// deciding again.
#pragma once

#include "saagen/measure/trade.hpp"
#include "saagen/report/comparison.hpp"
#include "saagen/report/cost_table.hpp"
#include "saagen/report/summary.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace saagen::report {

// An interval as the JSON outputs write it ({mean, low, high}), and a paired difference's: the
// interval with the ground truth's part of it and its reading (better / tie / worse).
nlohmann::json interval_json(const measure::Interval& interval);
nlohmann::json difference_json(const MetricDifference& difference);

nlohmann::json trade_json(const measure::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs);

// Under TAA, per content type (findings.hpp, measured_taa_rows): every configuration's means and
// its pairing with none+taa in by_content's form, the JSON's "taa_by_content" that `saagen plan
// --trade-table` reads with taa = true; and saagen's decision on them per path, the JSON's
// decisions.taa_by_content.
nlohmann::json taa_by_content_json(const measure::TradeTable& table);
nlohmann::json taa_decisions_json(const measure::TradeTable& table);
// Every configuration under TAA against TAA alone (none+taa), in the form of the JSON's
// "comparisons" (baseline "none+taa"), from a table with +taa rows: the comparisons the verdict
// under TAA reads, with their intervals, sample_bias and bias_limited; `saagen bench --taa --json`
// appends them to "comparisons".
nlohmann::json taa_comparisons_json(const measure::TradeTable& table);

}  // namespace saagen::report

// The trade table summed up: per configuration, the means over its cases, and one line saying
// how the table was measured (its TradeConfig), for the terminal, the report and the JSON.
#pragma once

#include "saagen/measure/trade.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace saagen::report {

// Means over the table's scenes and alphas, without Fresnel (with Fresnel the radiance is ~25x
// dimmer and the orderings are the same).
// Means over the cases (scenes x alphas, no Fresnel) of one configuration: a variant, or a
// variant fed the geometric normal ("deferred-avg:geometric"), or an engine's shipped form.
// Its metrics are the trade rows' (measure::RowMetrics), max_error the largest over the cases.
struct VariantSummary : measure::RowMetrics {
  std::string variant;  // measure::configuration_id
  std::size_t cases = 0;
};

std::vector<VariantSummary> summarize(const measure::TradeTable& table);

// The table's configuration in one line: sizes, samples, animation, filter parameters, and the
// scenes measured at sizes of their own.
std::string config_line(const measure::TradeTable& table);
// "N-spp ground truth", and the sample counts of the scenes with their own sizes (the presets' glTF
// and asset scenes: TradeConfig::scene_sizes), e.g. "256-spp ground truth (... teapots 4096)".
std::string ground_truth_samples(const measure::TradeConfig& config);

}  // namespace saagen::report

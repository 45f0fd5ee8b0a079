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
struct VariantSummary {
  std::string variant;  // measure::configuration_id
  double rmse_linear = 0.0;
  double rmse_tonemapped = 0.0;
  double max_error = 0.0;  // the largest over the cases
  double tde = 0.0;        // temporal difference error (trade.hpp) and its two parts
  double tde_excess_flicker = 0.0;
  double tde_lost_motion = 0.0;
  double flicker = 0.0;
  double flicker_display = 0.0;  // secondary: tonemapped temporal std relative to the ground truth's
  double flip_ldr = 0.0;
  double flip_hdr = 0.0;
  std::size_t cases = 0;
};

std::vector<VariantSummary> summarize(const measure::TradeTable& table);

// The table's configuration in one line: sizes, samples, animation, filter parameters, and the
// scenes measured at sizes of their own.
std::string config_line(const measure::TradeTable& table);

}  // namespace saagen::report

// The trade under TAA (TradeConfig::taa): the +taa rows apart from the summaries, their per-scene
// comparison against none+taa and its table, for the terminal, the report's "With TAA" section
// (pages.hpp) and the JSON's "taa_cases".
#pragma once

#include "saagen/measure/trade.hpp"
#include "saagen/report/comparison.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace saagen::report {

// Under TAA (TradeConfig::taa): the table without its +taa rows, which the summaries, findings,
// verdicts and trade_json read (their flip_ldr is the animation's, not frame 0's at the main
// resolution); per scene, the comparison under TAA (taa_comparisons) as a terminal table (empty
// without +taa rows); and every row's figures, for trade_json's "taa_cases".
measure::TradeTable without_taa_rows(const measure::TradeTable& table);
std::string format_taa_summary(const measure::TradeTable& table);
nlohmann::json taa_cases_json(const measure::TradeTable& table);

// The per-scene comparison under TAA behind format_taa_summary and the report's "with TAA"
// section, read with the verdict's metrics and decision (comparison.hpp, saagen/decision.hpp):
// rows "no TAA" (none), "TAA" (none+taa), "saagen" (the configuration the decision takes among
// saagen's under TAA, any feed, prefilter or lobe, against none+taa; absent when none beats it)
// and "engine" (each engine form under TAA); each with its own figures (means over the scene's
// alphas without Fresnel, with 95 % intervals) and its paired comparison against none+taa.
struct TaaComparisonRow {
  std::string label;
  std::string configuration;                     // measure::configuration_id
  measure::Interval image_error;                 // LDR-FLIP per frame of the animation
  std::optional<measure::Interval> video_error;  // 10 - ColorVideoVDP's JOD; nullopt without the video metric
  double tde = 0.0;                              // the older temporal figure, for comparison with older tables
  std::optional<PairedComparison> against_taa;   // against none+taa; nullopt on none+taa's own row
};
struct TaaComparison {
  measure::SceneId scene = measure::SceneId::sphere;
  std::vector<TaaComparisonRow> rows;
  std::string best_saagen;  // the decision's choice under TAA ("" when none beats none+taa)
  std::string best_engine;  // the engine form under TAA with the lowest temporal error ("" when the table has none)
  std::string verdict;      // the decision's reason
};
std::vector<TaaComparison> taa_comparisons(const measure::TradeTable& table);
// A row's columns as the terminal table and the report print them, and their headers.
std::vector<std::string> taa_headers();
std::vector<std::string> taa_columns(const TaaComparisonRow& row);
// What the comparison's figures are (frames, warm-up, resolution, ground truth), for captions.
std::string taa_note(const measure::TradeTable& table);

}  // namespace saagen::report

// The bench's JSON (see trade_json.hpp).
#include "saagen/report/trade_json.hpp"

#include "saagen/io/output.hpp"
#include "saagen/report/findings.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <string_view>

namespace saagen::report {
namespace {

std::string id_of(measure::Variant variant) { return std::string(measure::variant_id(variant)); }

nlohmann::json difference_json(const decision::Difference& d) { return {{"mean", d.mean}, {"low", d.low}, {"high", d.high}}; }

nlohmann::json comparison_json(const decision::Comparison& c) {
  nlohmann::json json = {{"image", difference_json(c.image)}, {"temporal", difference_json(c.temporal)}, {"lag", difference_json(c.lag)}};
  if (c.unconverged) json["unconverged"] = true;
  return json;
}

// saagen's decision (findings.hpp, decide_on) as the JSON carries it, for the scripts to read
// instead of deciding again: the chosen configuration ("none": no filter), the reason, and every
// candidate's comparison with no SAA and outcome; per_scene adds the chosen configuration's
// outcome against each engine's form on that scene.
nlohmann::json decision_json(const MaterialDecision& made) {
  nlohmann::json candidates = nlohmann::json::array();
  for (std::size_t i = 0; i < made.candidates.size(); ++i) {
    const decision::Candidate& c = made.candidates[i];
    candidates.push_back({{"configuration", c.configuration},
                          {"usable", c.usable},
                          {"outcome", std::string(decision::name(made.decision.outcomes[i]))},
                          {"image", difference_json(c.against_none.image)},
                          {"temporal", difference_json(c.against_none.temporal)},
                          {"cost_ratio", c.cost_ratio ? nlohmann::json(*c.cost_ratio) : nlohmann::json()}});
  }
  return {{"chosen", made.decision.chosen ? made.candidates[*made.decision.chosen].configuration : "none"},
          {"reason", made.decision.reason},
          {"candidates", candidates}};
}

// The chosen configuration against an engine's form on a scene, paired with intervals.
nlohmann::json engine_comparison_json(const decision::Comparison& c) {
  return {{"outcome", std::string(decision::name(decision::outcome(c)))},
          {"image", difference_json(c.image)},
          {"temporal", difference_json(c.temporal)}};
}

// Per content type and path: saagen's decision on each content's rows (`rows_of`) against
// `baseline`, as the JSON carries it.
template <class RowsOf>
nlohmann::json content_decisions_json(const measure::TradeTable& table, RowsOf rows_of, std::string_view baseline) {
  nlohmann::json out = nlohmann::json::array();
  for (Content content : kContents) {
    const std::vector<ContentRow> rows = rows_of(content);
    if (rows.empty()) continue;
    for (Path path : {Path::forward, Path::deferred}) {
      nlohmann::json entry = decision_json(decide_on(table, rows, path, content, false, baseline));
      entry["content"] = std::string(content_name(content)), entry["path"] = std::string(path_name(path));
      out.push_back(entry);
    }
  }
  return out;
}

nlohmann::json decisions_json(const measure::TradeTable& table) {
  const nlohmann::json by_content = content_decisions_json(
      table,
      [&](Content content) {
        const RowFilter keep = [content](const measure::TradeRow& row) { return !row.taa && content_of(row.scene) == content; };
        return measured_rows(table, keep, content_name(content));
      },
      "no SAA");
  nlohmann::json per_scene = nlohmann::json::array();
  for (measure::SceneId scene : table.config.scenes) {
    const RowFilter keep = [scene](const measure::TradeRow& row) { return !row.taa && row.scene == scene; };
    const std::vector<ContentRow> rows = measured_rows(table, keep, measure::scene_name(scene));
    for (Path path : {Path::forward, Path::deferred}) {
      const MaterialDecision made = decide_on(table, rows, path, content_of(scene));
      nlohmann::json entry = decision_json(made);
      entry["scene"] = std::string(measure::scene_name(scene)), entry["path"] = std::string(path_name(path));
      entry["content"] = std::string(content_name(content_of(scene)));
      nlohmann::json engines = nlohmann::json::object();
      const std::string chosen = chosen_configuration(made);
      const auto chosen_row = std::find_if(rows.begin(), rows.end(), [&](const ContentRow& r) { return r.configuration == chosen; });
      for (const ContentRow& row : rows)
        if (is_engine_configuration(row.configuration) && chosen_row != rows.end())
          engines[row.configuration] = engine_comparison_json(to_decision(compare_configurations(table, chosen, row.configuration, keep)));
      entry["against_engines"] = engines;
      per_scene.push_back(entry);
    }
  }
  return {{"rule",
           "only what beats no SAA (no metric worse beyond its interval, one better), is not late and loses on none of "
           "the pooled scenes is chosen; accuracy: the largest gain in the temporal metric on the mean, the image metric "
           "as tie-break, or of it and what ties with it in their paired comparison, the cheapest that none of them beats "
           "in their own pairing; none where nothing beats no SAA (saagen/decision.hpp)"},
          {"image_metric", "image error (LDR-FLIP of every animation frame)"},
          {"temporal_metric", temporal_metric_description(table)},
          {"by_content", by_content},
          {"per_scene", per_scene}};
}

// The clip's JOD against the first ground-truth seed (the clip `--frames` writes as the ground
// truth); 10 without the video metric.
double first_seed_jod(const measure::TradeRow& row) {
  const std::vector<double>& losses = row.series.video[0];
  return losses.empty() ? 10.0 : 10.0 - measure::mean_interval(losses, 0.0).mean;
}

// A row's "loses_at": [{"scene", "alpha"}] (cost_tables.hpp, CellLoss).
nlohmann::json cells_json(const std::vector<CellLoss>& cells) {
  nlohmann::json out = nlohmann::json::array();
  for (const CellLoss& cell : cells) out.push_back({{"scene", cell.scene}, {"alpha", cell.alpha}});
  return out;
}

}  // namespace

// Under TAA, per content type and path: saagen's decision on the content's +taa rows against
// none+taa (findings.hpp, measured_taa_rows), what `saagen plan` gives with taa = true.
nlohmann::json taa_decisions_json(const measure::TradeTable& table) {
  return content_decisions_json(
      table, [&](Content content) { return measured_taa_rows(table, content); }, "none+taa");
}

// Under TAA, per content type: every configuration's means and its pairing with none+taa
// (measured_taa_rows), in by_content's form; `saagen plan --trade-table` reads it with taa = true.
nlohmann::json taa_by_content_json(const measure::TradeTable& table) {
  nlohmann::json out = nlohmann::json::array();
  const std::string temporal = has_video_metric(table) ? "video_error" : "flicker_error";
  for (Content content : kContents)
    for (const ContentRow& row : measured_taa_rows(table, content)) {
      nlohmann::json entry = {{"content", row.content}, {"configuration", row.configuration}, {"baseline", "none+taa"},
                              {"error", row.error},     {"image_error", row.error},           {temporal, row.temporal.value_or(0.0)}};
      if (row.against_none) entry["against_none"] = comparison_json(*row.against_none);
      if (!row.loses_on.empty()) entry["loses_on"] = row.loses_on;
      if (!row.not_worse_than.empty()) entry["not_worse_than"] = row.not_worse_than;
      if (!row.loses_at.empty()) entry["loses_at"] = cells_json(row.loses_at);
      out.push_back(entry);
    }
  return out;
}

nlohmann::json interval_json(const measure::Interval& interval) {
  return {{"mean", interval.mean}, {"low", interval.low}, {"high", interval.high}};
}

nlohmann::json difference_json(const MetricDifference& d) {
  nlohmann::json out = interval_json(d.difference);
  out["ground_truth_sd"] = d.ground_truth_sd;
  out["ground_truth_limited"] = d.ground_truth_limited;
  if (d.sample_bias) out["sample_bias"] = *d.sample_bias, out["bias_limited"] = d.bias_limited;
  out["outcome"] = std::string(metric_outcome_name(outcome_of(d)));
  return out;
}

namespace {

// Per configuration, the summary's means (summarize) with the measured costs, in bench_shading's
// row format: "error" is the mean LDR-FLIP.
nlohmann::json summary_rows_json(const std::vector<VariantSummary>& summary, const CostTable* costs) {
  nlohmann::json rows = nlohmann::json::array();
  for (const VariantSummary& row : summary) {
    nlohmann::json entry = {{"variant", row.variant},
                            {"error", row.flip_ldr},
                            {"rmse_tonemapped", row.rmse_tonemapped},
                            {"rmse_linear", row.rmse_linear},
                            {"flip_hdr", row.flip_hdr},
                            {"tde", row.tde},
                            {"tde_excess_flicker", row.tde_excess_flicker},
                            {"tde_lost_motion", row.tde_lost_motion},
                            {"flicker", row.flicker},
                            {"flicker_display", row.flicker_display}};
    if (const auto ratio = configuration_isa_cost(costs, row.variant); ratio && costs && !costs->isa_family.empty()) {
      entry["isa_inverse_throughput_ratio"] = *ratio;
      entry["isa_family"] = costs->isa_family;
    }
    if (const auto ratio = configuration_cost(costs, row.variant, true)) entry["cost_ratio"] = *ratio;
    if (const auto delta = configuration_cost(costs, row.variant, false)) entry["delta_spirv_instructions"] = *delta;
    rows.push_back(entry);
  }
  return rows;
}

// Every row of the table with its figures.
nlohmann::json cases_json(const measure::TradeTable& table) {
  nlohmann::json cases = nlohmann::json::array();
  for (const measure::TradeRow& row : table.rows) {
    cases.push_back({{"scene", std::string(measure::scene_name(row.scene))},
                     {"alpha", row.alpha},
                     {"fresnel", row.fresnel},
                     {"variant", id_of(row.variant)},
                     {"feed", std::string(measure::feed_name(row.feed))},
                     {"configuration", measure::configuration_id(row)},
                     {"image_error", interval_json(row.image_error)},
                     {"flicker_error", interval_json(row.flicker_error)},
                     {"video_error", interval_json(row.video_error)},
                     {"jod", first_seed_jod(row)},
                     {"lag", interval_json(row.lag)},
                     {"flicker_excess", row.flicker_excess},
                     {"flicker_missing", row.flicker_missing}});
    for (const measure::RowMetricField& field : measure::kRowMetricFields) cases.back()[std::string(field.name)] = row.*field.value;
  }
  return cases;
}

// The sanity suite's rows (measure::SanityRow).
nlohmann::json sanity_json(const measure::TradeTable& table) {
  nlohmann::json sanity = nlohmann::json::array();
  for (const measure::SanityRow& row : table.sanity)
    sanity.push_back({{"scene", std::string(measure::scene_name(row.scene))},
                      {"alpha", row.alpha},
                      {"fresnel", row.fresnel},
                      {"result", std::string(measure::sanity_name(row.result))},
                      {"image_error", row.image_error},
                      {"flicker_error", row.flicker_error},
                      {"video_error", row.video_error},
                      {"jod", 10.0 - row.video_error},
                      {"lag", row.lag}});
  return sanity;
}

// Per content type, the same means: the planner's advice for a material with or without normal maps.
nlohmann::json by_content_json(const measure::TradeTable& table) {
  nlohmann::json by_content = nlohmann::json::array();
  for (Content content : kContents) {
    const RowFilter keep = [content](const measure::TradeRow& row) { return content_of(row.scene) == content; };
    // The comparisons with no SAA as the decision reads them (findings.hpp, measured_rows).
    std::map<std::string, ContentRow> measured;
    for (ContentRow& row : measured_rows(table, keep, content_name(content))) measured.emplace(row.configuration, std::move(row));
    for (const std::string& id : configurations(table)) {
      const Metrics m = mean_metrics(table, id, keep);
      if (!m.cases || is_measurement_configuration(id)) continue;
      by_content.push_back({{"content", std::string(content_name(content))},
                            {"configuration", id},
                            {"error", m.flip_ldr},
                            {"rmse_tonemapped", m.rmse_tonemapped},
                            {"flip_hdr", m.flip_hdr},
                            {"tde", m.tde},
                            {"tde_excess_flicker", m.tde_excess_flicker},
                            {"tde_lost_motion", m.tde_lost_motion},
                            {"flicker_display", m.flicker_display},
                            {"image_error", m.image_error},
                            {"flicker_error", m.flicker_error},
                            {"video_error", m.video_error}});
      const auto row = measured.find(id);
      if (row == measured.end() || !row->second.against_none) continue;
      by_content.back()["against_none"] = comparison_json(*row->second.against_none);
      if (!row->second.loses_on.empty()) by_content.back()["loses_on"] = row->second.loses_on;
      if (!row->second.not_worse_than.empty()) by_content.back()["not_worse_than"] = row->second.not_worse_than;
      if (!row->second.loses_at.empty()) by_content.back()["loses_at"] = cells_json(row->second.loses_at);
    }
  }
  return by_content;
}

// Every configuration against `baseline`, paired, with 95 % intervals (comparison.hpp): per content
// type, per scene, and per cell (one scene at one alpha: "alpha" names it; its interval is over the
// cell's frames and ground-truth seeds only); the verdicts, the planner and the scripts read these.
// Against none+taa, only the configurations under TAA.
nlohmann::json comparisons_json(const measure::TradeTable& table, const std::string& baseline = "none") {
  nlohmann::json comparisons = nlohmann::json::array();
  const bool under_taa = baseline == "none+taa";
  const auto add_comparisons = [&](std::string_view scope, const std::string& name, const CellFilter& keep,
                                   std::optional<double> alpha = std::nullopt) {
    for (const std::string& id : configurations(table)) {
      if (id == baseline || is_measurement_configuration(id) || (under_taa && id == without_taa(id))) continue;
      const PairedComparison c = compare_configurations(table, id, baseline, keep);
      if (c.cells == 0) continue;
      comparisons.push_back({{"scope", scope},
                             {"name", name},
                             {"configuration", id},
                             {"baseline", baseline},
                             {"cells", c.cells},
                             {"image_error", difference_json(c.image)},
                             {"flicker_error", difference_json(c.flicker)},
                             {"lag", difference_json(c.lag)},
                             {"outcome", std::string(comparison_outcome_name(c))}});
      if (c.unconverged) comparisons.back()["unconverged"] = true;
      if (c.video) comparisons.back()["video_error"] = difference_json(*c.video);
      if (alpha) comparisons.back()["alpha"] = *alpha;
    }
  };
  for (Content content : kContents)
    add_comparisons("content", std::string(content_name(content)),
                    [content](const measure::TradeRow& row) { return content_of(row.scene) == content; });
  for (const measure::SceneId scene : table.config.scenes)
    add_comparisons("scene", std::string(measure::scene_name(scene)), [scene](const measure::TradeRow& row) { return row.scene == scene; });
  for (const measure::SceneId scene : table.config.scenes)
    for (const double alpha : table.config.alphas)
      add_comparisons(
          "cell", std::string(measure::scene_name(scene)),
          [scene, alpha](const measure::TradeRow& row) { return row.scene == scene && row.alpha == alpha; }, alpha);
  return comparisons;
}

// The device timing the decisions were costed with (MeasuredTradeTable::decision_timing), as a
// cost table (cost_tables.hpp) with the file it came from, for `saagen plan --trade-table` to cost
// as the bench did.
nlohmann::json device_timing_json(const MeasuredTradeTable& timing) {
  nlohmann::json rows = nlohmann::json::array();
  for (const MeasuredTradeRow& row : timing.rows) {
    if (!row.cost_ratio) continue;
    rows.push_back({{"device", timing.device_name()},
                    {"shader", "forward"},
                    {"target", row.target.name()},
                    {"variant", row.variant},
                    {"lights", timing.lights},
                    {"cost_ratio", *row.cost_ratio}});
  }
  return {
      {"source", timing.source_name}, {"cost_model", kTimeCostModel}, {"device", timing.device}, {"lights", timing.lights}, {"rows", rows}};
}

}  // namespace

nlohmann::json taa_comparisons_json(const measure::TradeTable& table) { return comparisons_json(table, "none+taa"); }

nlohmann::json trade_json(const measure::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs) {
  nlohmann::json json = {{"generator", std::string(output_tag) + " saagen bench"},
                         {"decisions", decisions_json(table)},
                         {"error_metric", "mean LDR-FLIP of the tonemapped images over scenes and alphas, no Fresnel"},
                         {"motion_metric", "tde: mean temporal difference error of the display-value animation against the ground truth's"},
                         {"config", config_line(table)},
                         {"half_vector_frame", to_string(table.config.half_vector_frame)},
                         {"rows", summary_rows_json(summary, costs)},
                         {"alphas", measured_alphas(table)},
                         {"by_content", by_content_json(table)},
                         {"cases", cases_json(table)},
                         {"sanity", sanity_json(table)},
                         {"comparisons", comparisons_json(table)}};
  if (table.decision_timing) json["device_timing"] = device_timing_json(*table.decision_timing);
  return json;
}

}  // namespace saagen::report

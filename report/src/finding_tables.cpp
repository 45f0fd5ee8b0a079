// The findings and the summaries as tables (see finding_tables.hpp).
#include "finding_tables.hpp"

#include <fmt/format.h>

#include <iterator>
#include <optional>

namespace saagen::report {
namespace {

std::string optional_number(const std::optional<double>& value, const char* format) {
  return value ? fmt::format(fmt::runtime(format), *value) : std::string("-");
}

const std::vector<std::string> kMetricHeaders{"RMSE linear", "RMSE tonemapped", "LDR-FLIP",    "HDR-FLIP",        "max error",
                                              "TDE",         "excess flicker",  "lost motion", "flicker tm ratio"};

std::vector<std::string> metric_cells(const Metrics& m) {
  return {fmt::format("{:.4g}", m.rmse_linear),        fmt::format("{:.4g}", m.rmse_tonemapped), fmt::format("{:.4f}", m.flip_ldr),
          fmt::format("{:.4f}", m.flip_hdr),           fmt::format("{:.4g}", m.max_error),       fmt::format("{:.5f}", m.tde),
          fmt::format("{:.5f}", m.tde_excess_flicker), fmt::format("{:.5f}", m.tde_lost_motion), fmt::format("{:.3f}", m.flicker_display)};
}

// ISA inverse-throughput ratio (primary), lavapipe time ratio (secondary), SPIR-V delta.
std::vector<std::string> cost_cells(const CostTable* costs, const std::string& configuration) {
  return {optional_number(configuration_isa_cost(costs, configuration), "{:.3f}"),
          optional_number(configuration_cost(costs, configuration, true), "{:.3f}"),
          optional_number(configuration_cost(costs, configuration, false), "{:+.0f}")};
}

Metrics metrics_of(const VariantSummary& s) {
  Metrics m;
  static_cast<measure::RowMetrics&>(m) = s;
  m.cases = s.cases;
  return m;
}

std::string percent_change(double ours, double theirs) {
  return theirs > 0.0 ? fmt::format("{:+.1f} %", 100.0 * (ours - theirs) / theirs) : std::string("-");
}

TextTable recommendation_table(const std::vector<Recommendation>& recs, const CostTable* costs) {
  TextTable t{{"path", "content", "recommended", "LDR-FLIP", "TDE", "HDR-FLIP", "RMSE tonemapped", "ISA inv.thr", "time ratio", "dSPIR-V"},
              {}};
  for (const Recommendation& r : recs) {
    std::vector<std::string> cells{std::string(path_name(r.path)),
                                   std::string(content_name(r.content)),
                                   r.configuration,
                                   fmt::format("{:.4f}", r.metrics.flip_ldr),
                                   fmt::format("{:.5f}", r.metrics.tde),
                                   fmt::format("{:.4f}", r.metrics.flip_hdr),
                                   fmt::format("{:.4g}", r.metrics.rmse_tonemapped)};
    for (auto& c : cost_cells(costs, r.configuration)) cells.push_back(c);
    t.rows.push_back(cells);
  }
  return t;
}

TextTable switch_table(const std::vector<EngineSwitch>& switches) {
  TextTable t{{"switching from", "content", "engine LDR-FLIP", "saagen that beats it at <= cost", "LDR-FLIP", "change LDR-FLIP",
               "change TDE", "change HDR-FLIP", "change RMSE tm"},
              {}};
  for (const EngineSwitch& s : switches) {
    if (s.configuration.empty()) {
      t.rows.push_back({s.engine, std::string(content_name(s.content)), fmt::format("{:.4f}", s.engine_metrics.flip_ldr), "(none beats it)",
                        "-", "-", "-", "-", "-"});
      continue;
    }
    t.rows.push_back(
        {s.engine, std::string(content_name(s.content)), fmt::format("{:.4f}", s.engine_metrics.flip_ldr), s.configuration,
         fmt::format("{:.4f}", s.saagen_metrics.flip_ldr), percent_change(s.saagen_metrics.flip_ldr, s.engine_metrics.flip_ldr),
         percent_change(s.saagen_metrics.tde, s.engine_metrics.tde), percent_change(s.saagen_metrics.flip_hdr, s.engine_metrics.flip_hdr),
         percent_change(s.saagen_metrics.rmse_tonemapped, s.engine_metrics.rmse_tonemapped)});
  }
  return t;
}

// Compact: whether the recommendation beats none and every engine on the scene, and how many
// (baseline, metric) pairs it loses; the losses themselves are in the report (loss_lists_*).
TextTable verdict_table(const std::vector<SceneVerdict>& verdicts) {
  TextTable t{{"scene", "path", "recommended", "LDR-FLIP", "TDE", "RMSE tonemapped", "beats none and every engine"}, {}};
  for (const SceneVerdict& v : verdicts) {
    t.rows.push_back({std::string(measure::scene_name(v.scene)), std::string(path_name(v.path)), v.configuration,
                      fmt::format("{:.4f}", v.recommended.flip_ldr), fmt::format("{:.5f}", v.recommended.tde),
                      fmt::format("{:.4g}", v.recommended.rmse_tonemapped),
                      v.losses.empty() ? "yes"
                                       : fmt::format("no: {} of {} comparisons lost", v.losses.size(),
                                                     v.baselines.size() * std::size(kVerdictMetrics))});
  }
  return t;
}

}  // namespace

TextTable summary_table(const std::vector<VariantSummary>& summary, const CostTable* costs) {
  TextTable t;
  t.headers = {"configuration"};
  t.headers.insert(t.headers.end(), kMetricHeaders.begin(), kMetricHeaders.end());
  t.headers.insert(t.headers.end(), {"ISA inv.thr", "time ratio", "dSPIR-V"});
  for (const VariantSummary& row : summary) {
    std::vector<std::string> cells{row.variant};
    for (auto& c : metric_cells(metrics_of(row))) cells.push_back(c);
    for (auto& c : cost_cells(costs, row.variant)) cells.push_back(c);
    t.rows.push_back(cells);
  }
  return t;
}

TextTable content_table(const measure::TradeTable& table, Content content, const CostTable* costs) {
  TextTable t;
  t.headers = {"configuration"};
  t.headers.insert(t.headers.end(), kMetricHeaders.begin(), kMetricHeaders.end());
  t.headers.insert(t.headers.end(), {"ISA inv.thr", "time ratio", "dSPIR-V"});
  const RowFilter keep = [content](const measure::TradeRow& row) { return content_of(row.scene) == content; };
  for (const std::string& id : configurations(table)) {
    const Metrics m = mean_metrics(table, id, keep);
    if (!m.cases) continue;
    std::vector<std::string> cells{id};
    for (auto& c : metric_cells(m)) cells.push_back(c);
    for (auto& c : cost_cells(costs, id)) cells.push_back(c);
    t.rows.push_back(cells);
  }
  return t;
}

TextTable cases_table(const measure::TradeTable& table) {
  TextTable t{{"scene", "alpha", "Fresnel", "configuration"}, {}};
  t.headers.insert(t.headers.end(), kMetricHeaders.begin(), kMetricHeaders.end());
  for (const measure::TradeRow& row : table.rows) {
    std::vector<std::string> cells{std::string(measure::scene_name(row.scene)), fmt::format("{}", row.alpha), row.fresnel ? "yes" : "no",
                                   measure::configuration_id(row)};
    for (auto& c : metric_cells(row_metrics(row))) cells.push_back(c);
    t.rows.push_back(cells);
  }
  return t;
}

std::vector<TitledTable> finding_tables(const measure::TradeTable& table, const CostTable* costs) {
  const std::vector<Recommendation> recs = recommend(table);
  std::vector<TitledTable> tables;
  tables.push_back(
      {"Recommended configuration per render path and content (saagen's decision: what beats no SAA in image and video error "
       "beyond their intervals, the largest video-error gain; none where nothing does; the columns: the older means)",
       recommendation_table(recs, costs)});
  tables.push_back({std::string("Switching from an engine's shipped form: saagen's decision against it (what beats it in image and "
                                "video error beyond their intervals, the largest video-error gain) at equal or lower cost") +
                        (costs ? "" : " (no cost file: cost not compared)"),
                    switch_table(engine_switches(table, costs))});
  tables.push_back(
      {"Per scene: the recommendation against no SAA and every engine (the older means: LDR-FLIP, TDE, HDR-FLIP, tonemapped RMSE)",
       verdict_table(scene_verdicts(table, recs))});
  return tables;
}

}  // namespace saagen::report

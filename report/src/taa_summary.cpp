// The trade under TAA: the +taa rows apart from the summaries, their per-scene comparison and
// its table (see taa_summary.hpp).
#include "saagen/report/taa_summary.hpp"

#include "verdict_text.hpp"

#include "saagen/decision.hpp"
#include "saagen/report/comparison.hpp"
#include "saagen/report/findings.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace saagen::report {

namespace {

bool is_engine(const std::string& id) { return id.starts_with("engine-"); }

// A saagen SAA configuration under TAA, any feed, prefilter or lobe ("deferred-aniso+taa/tail");
// not no SAA, texture prefiltering alone ("none+hdrp+taa") or an engine's form.
bool is_saagen_taa(const std::string& id) { return id.find("+taa") != std::string::npos && !id.starts_with("none") && !is_engine(id); }

bool is_engine_taa(const std::string& id) { return is_engine(id) && id.find("+taa") != std::string::npos; }

// One scene's rows (no Fresnel) by configuration, in the table's order of first appearance.
struct SceneRows {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const measure::TradeRow*>> rows;
};

std::vector<std::pair<measure::SceneId, SceneRows>> rows_by_scene(const measure::TradeTable& table) {
  std::vector<std::pair<measure::SceneId, SceneRows>> scenes;
  for (const measure::TradeRow& row : table.rows) {
    if (row.fresnel) continue;
    auto scene = std::find_if(scenes.begin(), scenes.end(), [&](const auto& s) { return s.first == row.scene; });
    if (scene == scenes.end()) scene = scenes.insert(scenes.end(), {row.scene, SceneRows{}});
    const std::string id = measure::configuration_id(row);
    std::vector<const measure::TradeRow*>& rows = scene->second.rows[id];
    if (rows.empty()) scene->second.order.push_back(id);
    rows.push_back(&row);
  }
  return scenes;
}

// A configuration's own figure over its rows (measure::series_interval over the cells).
template <typename Series>
measure::Interval own_interval(const std::vector<const measure::TradeRow*>& rows, Series series) {
  std::vector<measure::SeedSeries> cells;
  for (const measure::TradeRow* row : rows) cells.push_back(row->series.*series);
  return measure::series_interval(cells);
}

TaaComparisonRow row_of(const measure::TradeTable& table, measure::SceneId scene, const std::string& label, const std::string& id,
                        const std::vector<const measure::TradeRow*>& rows) {
  TaaComparisonRow out{label, id, own_interval(rows, &measure::AnimationSeries::image), std::nullopt, 0.0, std::nullopt};
  const bool video = std::all_of(rows.begin(), rows.end(), [](const measure::TradeRow* r) { return !r->series.video[0].empty(); });
  if (video) out.video_error = own_interval(rows, &measure::AnimationSeries::video);
  for (const measure::TradeRow* row : rows) out.tde += row->tde / static_cast<double>(rows.size());
  if (id != "none+taa")
    out.against_taa = compare_configurations(table, id, "none+taa", [scene](const measure::TradeRow& row) { return row.scene == scene; });
  return out;
}

// What the decision takes among saagen's configurations under TAA against none+taa.
decision::Decision decide_under_taa(const std::vector<TaaComparisonRow>& saagen_rows) {
  std::vector<decision::Candidate> candidates;
  for (const TaaComparisonRow& row : saagen_rows)
    candidates.push_back({row.configuration, to_decision(*row.against_taa), std::nullopt, true});
  decision::Preference preference;
  preference.baseline = "none+taa";
  return decision::decide(candidates, preference);
}

double temporal_mean(const TaaComparisonRow& row) { return row.video_error ? row.video_error->mean : row.image_error.mean; }

std::string interval_text(const measure::Interval& i) { return fmt::format("{:.4f} [{:.4f}, {:.4f}]", i.mean, i.low, i.high); }

std::string difference_text(const std::optional<PairedComparison>& c, bool video) {
  if (!c || c->cells == 0) return "";
  const MetricDifference& d = video && c->video ? *c->video : c->image;
  return fmt::format("{:+.4f} [{:+.4f}, {:+.4f}] {}", d.difference.mean, d.difference.low, d.difference.high, comparison_outcome_name(*c));
}

}  // namespace

measure::TradeTable without_taa_rows(const measure::TradeTable& table) {
  measure::TradeTable plain = table;
  std::erase_if(plain.rows, [](const measure::TradeRow& row) { return row.taa; });
  return plain;
}

std::vector<TaaComparison> taa_comparisons(const measure::TradeTable& table) {
  std::vector<TaaComparison> out;
  for (const auto& [scene, configs] : rows_by_scene(table)) {
    if (!configs.rows.count("none+taa")) continue;
    TaaComparison c;
    c.scene = scene;
    if (configs.rows.count("none")) c.rows.push_back(row_of(table, scene, "no TAA", "none", configs.rows.at("none")));
    c.rows.push_back(row_of(table, scene, "TAA", "none+taa", configs.rows.at("none+taa")));
    std::vector<TaaComparisonRow> saagen, engines;
    for (const std::string& id : configs.order) {
      if (is_saagen_taa(id)) saagen.push_back(row_of(table, scene, "saagen", id, configs.rows.at(id)));
      if (is_engine_taa(id)) engines.push_back(row_of(table, scene, "engine", id, configs.rows.at(id)));
    }
    const decision::Decision made = decide_under_taa(saagen);
    c.verdict = made.reason;
    if (made.chosen) {
      c.best_saagen = saagen[*made.chosen].configuration;
      c.rows.push_back(saagen[*made.chosen]);
    }
    const auto best_engine = std::min_element(engines.begin(), engines.end(), [](const TaaComparisonRow& a, const TaaComparisonRow& b) {
      return temporal_mean(a) < temporal_mean(b);
    });
    if (best_engine != engines.end()) c.best_engine = best_engine->configuration;
    c.rows.insert(c.rows.end(), engines.begin(), engines.end());
    out.push_back(std::move(c));
  }
  return out;
}

std::string taa_note(const measure::TradeTable& table) {
  const measure::TradeConfig& c = table.config;
  return fmt::format(
      "means over the alphas without Fresnel with 95 % intervals; the {} animation frames after a warm-up of {} at {} x {} px "
      "against their {}-spp ground truths; image error: LDR-FLIP per frame; video error: 10 - ColorVideoVDP's JOD of the clip; "
      "against none+taa: the paired difference in the video error (the image error without the video metric) and the "
      "verdict's reading of both",
      c.frames, c.taa_warmup_frames > 0 ? c.taa_warmup_frames : c.taa_options.sequence_length, c.flicker_width, c.flicker_height,
      c.flicker_strata * c.flicker_strata);
}

std::vector<std::string> taa_columns(const TaaComparisonRow& row) {
  const bool video = row.video_error.has_value();
  return {row.label,
          row.configuration,
          interval_text(row.image_error),
          video ? interval_text(*row.video_error) : "",
          difference_text(row.against_taa, video),
          fmt::format("{:.5f}", row.tde)};
}

std::vector<std::string> taa_headers() { return {"row", "configuration", "image error", "video error", "against none+taa", "TDE"}; }

std::string format_taa_summary(const measure::TradeTable& table) {
  const std::vector<TaaComparison> comparisons = taa_comparisons(table);
  if (comparisons.empty()) return {};
  std::string text = "With TAA (" + taa_note(table) + "):\n";
  const std::vector<std::string> headers = taa_headers();
  const std::string format = "{:<14} {:<36} {:<26} {:<26} {:<38} {:>8}\n";
  for (const TaaComparison& c : comparisons) {
    text += fmt::format("{}: {}\n", measure::scene_name(c.scene), c.verdict);
    text += fmt::format(fmt::runtime(format), headers[0], headers[1], headers[2], headers[3], headers[4], headers[5]);
    for (const TaaComparisonRow& row : c.rows) {
      const std::vector<std::string> v = taa_columns(row);
      text += fmt::format(fmt::runtime(format), v[0], v[1], v[2], v[3], v[4], v[5]);
    }
  }
  text +=
      "Per content and render path under TAA (saagen's decision against none+taa over the content's scenes; what `saagen plan` "
      "gives with taa = true and this table):\n";
  for (Content content : kContents) {
    const std::vector<ContentRow> rows = measured_taa_rows(table, content);
    if (rows.empty()) continue;
    for (Path path : {Path::forward, Path::deferred})
      text += fmt::format("  {}, {}: {}\n", path_name(path), content_name(content),
                          decide_on(table, rows, path, content, false, "none+taa").decision.reason);
  }
  text += fmt::format("{} under TAA ({}; against none+taa):\n", kByAlphaTitle, kByAlphaNote);
  for (const std::string& line : by_alpha_lines(recommend_taa_by_alpha(table))) text += "  " + line + "\n";
  return text;
}

nlohmann::json taa_cases_json(const measure::TradeTable& table) {
  nlohmann::json cases = nlohmann::json::array();
  for (const measure::TradeRow& row : table.rows)
    cases.push_back({{"scene", std::string(measure::scene_name(row.scene))},
                     {"alpha", row.alpha},
                     {"fresnel", row.fresnel},
                     {"configuration", measure::configuration_id(row)},
                     {"taa", row.taa},
                     {"flip_ldr_animation", row.flip_ldr_animation},
                     {"image_error", row.image_error.mean},
                     {"video_error", row.series.video[0].empty() ? nlohmann::json() : nlohmann::json(row.video_error.mean)},
                     {"lag", row.lag.mean},
                     {"tde", row.tde},
                     {"tde_excess_flicker", row.tde_excess_flicker},
                     {"tde_lost_motion", row.tde_lost_motion}});
  return cases;
}

}  // namespace saagen::report

// The trade under TAA: the +taa rows apart from the summaries, their per-scene comparison and
// its table (see report.hpp).
#include "saagen/report/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace saagen::report {

namespace {

// Sums over a scene's alphas (no Fresnel) of one configuration's comparison figures.
struct TaaSums {
  double flip = 0.0, tde = 0.0, excess = 0.0, lost = 0.0;
  int cases = 0;
};

bool is_engine(const std::string& id) { return id.starts_with("engine-"); }

// A saagen SAA configuration under TAA, any feed, prefilter or lobe ("deferred-aniso+taa/tail");
// not no SAA, texture prefiltering alone ("none+hdrp+taa") or an engine's form.
bool is_saagen_taa(const std::string& id) { return id.find("+taa") != std::string::npos && !id.starts_with("none") && !is_engine(id); }

bool is_engine_taa(const std::string& id) { return is_engine(id) && id.find("+taa") != std::string::npos; }

TaaComparisonRow row_of(const std::string& label, const std::string& id, const TaaSums& s) {
  return {label, id, s.flip / s.cases, s.tde / s.cases, s.excess / s.cases, s.lost / s.cases};
}

// The configuration with the lowest mean LDR-FLIP among those `keep` accepts ("" if none).
template <typename Keep>
std::string best_by_flip(const std::map<std::string, TaaSums>& configs, Keep keep) {
  std::string best;
  for (const auto& [id, s] : configs)
    if (keep(id) && (best.empty() || s.flip / s.cases < configs.at(best).flip / configs.at(best).cases)) best = id;
  return best;
}

std::string means_line(const std::string& scene, const TaaComparisonRow& row) {
  return fmt::format("{:<17} {:<14} {:<40} {:>8.4f} {:>9.5f} {:>10.5f} {:>9.5f}\n", scene, row.label, row.configuration, row.flip_ldr,
                     row.tde, row.tde_excess_flicker, row.tde_lost_motion);
}

}  // namespace

render::TradeTable without_taa_rows(const render::TradeTable& table) {
  render::TradeTable plain = table;
  std::erase_if(plain.rows, [](const render::TradeRow& row) { return row.taa; });
  return plain;
}

std::vector<TaaComparison> taa_comparisons(const render::TradeTable& table) {
  std::vector<render::SceneId> scenes;
  std::map<render::SceneId, std::map<std::string, TaaSums>> sums;  // scene -> configuration -> sums
  for (const render::TradeRow& row : table.rows) {
    if (row.fresnel) continue;
    if (std::find(scenes.begin(), scenes.end(), row.scene) == scenes.end()) scenes.push_back(row.scene);
    TaaSums& s = sums[row.scene][render::configuration_id(row)];
    s.flip += row.flip_ldr_animation;
    s.tde += row.tde;
    s.excess += row.tde_excess_flicker;
    s.lost += row.tde_lost_motion;
    ++s.cases;
  }
  std::vector<TaaComparison> out;
  for (render::SceneId scene : scenes) {
    const auto& configs = sums[scene];
    if (!configs.count("none+taa")) continue;
    TaaComparison c;
    c.scene = scene;
    if (configs.count("none")) c.rows.push_back(row_of("no TAA", "none", configs.at("none")));
    c.rows.push_back(row_of("TAA", "none+taa", configs.at("none+taa")));
    c.best_saagen = best_by_flip(configs, is_saagen_taa);
    if (!c.best_saagen.empty()) c.rows.push_back(row_of("best saagen", c.best_saagen, configs.at(c.best_saagen)));
    c.best_engine = best_by_flip(configs, is_engine_taa);
    for (const auto& [id, s] : configs)
      if (is_engine_taa(id)) c.rows.push_back(row_of("engine", id, s));
    out.push_back(std::move(c));
  }
  return out;
}

std::string taa_note(const render::TradeTable& table) {
  const render::TradeConfig& c = table.config;
  return fmt::format(
      "means over the alphas without Fresnel; LDR-FLIP of the {} animation frames after a warm-up of {} at {} x {} px against their "
      "{}-spp ground truths; TDE over those frames",
      c.frames, c.taa_warmup_frames > 0 ? c.taa_warmup_frames : c.taa_options.sequence_length, c.flicker_width, c.flicker_height,
      c.flicker_strata * c.flicker_strata);
}

std::string format_taa_summary(const render::TradeTable& table) {
  const std::vector<TaaComparison> comparisons = taa_comparisons(table);
  if (comparisons.empty()) return {};
  std::string text = "With TAA (" + taa_note(table) + "):\n";
  text += fmt::format("{:<17} {:<14} {:<40} {:>8} {:>9} {:>10} {:>9}\n", "scene", "row", "configuration", "ldr_flip", "tde", "tde_excess",
                      "tde_lost");
  for (const TaaComparison& c : comparisons)
    for (const TaaComparisonRow& row : c.rows) text += means_line(std::string(render::scene_name(c.scene)), row);
  return text;
}

nlohmann::json taa_cases_json(const render::TradeTable& table) {
  nlohmann::json cases = nlohmann::json::array();
  for (const render::TradeRow& row : table.rows)
    cases.push_back({{"scene", std::string(render::scene_name(row.scene))},
                     {"alpha", row.alpha},
                     {"fresnel", row.fresnel},
                     {"configuration", render::configuration_id(row)},
                     {"taa", row.taa},
                     {"flip_ldr_animation", row.flip_ldr_animation},
                     {"tde", row.tde},
                     {"tde_excess_flicker", row.tde_excess_flicker},
                     {"tde_lost_motion", row.tde_lost_motion}});
  return cases;
}

}  // namespace saagen::report

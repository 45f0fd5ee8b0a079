// The trade under TAA: the +taa rows apart from the summaries, and their per-scene table (see
// report.hpp).
#include "saagen/report/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace saagen::report {

namespace {

// Mean LDR-FLIP of the animation and TDE with its parts, over a scene's alphas (no Fresnel).
struct TaaMeans {
  double flip = 0.0, tde = 0.0, excess = 0.0, lost = 0.0;
  int cases = 0;
};

bool is_saagen_taa(const std::string& id) { return id.ends_with("+taa") && !id.starts_with("none") && !id.starts_with("engine-"); }

std::string means_line(const std::string& scene, const std::string& label, const std::string& id, const TaaMeans& m) {
  return fmt::format("{:<17} {:<14} {:<40} {:>8.4f} {:>9.5f} {:>10.5f} {:>9.5f}\n", scene, label, id, m.flip / m.cases, m.tde / m.cases,
                     m.excess / m.cases, m.lost / m.cases);
}

}  // namespace

render::TradeTable without_taa_rows(const render::TradeTable& table) {
  render::TradeTable plain = table;
  std::erase_if(plain.rows, [](const render::TradeRow& row) { return row.taa; });
  return plain;
}

std::string format_taa_summary(const render::TradeTable& table) {
  std::vector<std::string> scenes;
  std::map<std::string, std::map<std::string, TaaMeans>> means;  // scene -> configuration -> sums
  for (const render::TradeRow& row : table.rows) {
    if (row.fresnel) continue;
    const std::string scene(render::scene_name(row.scene));
    if (std::find(scenes.begin(), scenes.end(), scene) == scenes.end()) scenes.push_back(scene);
    TaaMeans& m = means[scene][render::configuration_id(row)];
    m.flip += row.flip_ldr_animation;
    m.tde += row.tde;
    m.excess += row.tde_excess_flicker;
    m.lost += row.tde_lost_motion;
    ++m.cases;
  }
  std::string text = fmt::format(
      "With TAA (means over the alphas without Fresnel; LDR-FLIP of the {} animation frames after a warm-up of {} at {} x {} px against "
      "their {}-spp ground truths; TDE over those frames):\n",
      table.config.frames, table.config.taa_warmup_frames > 0 ? table.config.taa_warmup_frames : table.config.taa_options.sequence_length,
      table.config.flicker_width, table.config.flicker_height, table.config.flicker_strata * table.config.flicker_strata);
  text += fmt::format("{:<17} {:<14} {:<40} {:>8} {:>9} {:>10} {:>9}\n", "scene", "row", "configuration", "ldr_flip", "tde", "tde_excess",
                      "tde_lost");
  bool any = false;
  for (const std::string& scene : scenes) {
    const auto& configs = means[scene];
    if (!configs.count("none+taa")) continue;
    any = true;
    if (configs.count("none")) text += means_line(scene, "no TAA", "none", configs.at("none"));
    text += means_line(scene, "TAA", "none+taa", configs.at("none+taa"));
    std::string best;
    for (const auto& [id, m] : configs)
      if (is_saagen_taa(id) && (best.empty() || m.flip / m.cases < configs.at(best).flip / configs.at(best).cases)) best = id;
    if (!best.empty()) text += means_line(scene, "best saagen", best, configs.at(best));
    for (const auto& [id, m] : configs)
      if (id.starts_with("engine-") && id.ends_with("+taa")) text += means_line(scene, "engine", id, m);
  }
  return any ? text : std::string();
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

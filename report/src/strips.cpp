// The report's image strips (see strips.hpp).
#include "strips.hpp"

#include "sheets.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <utility>

namespace saagen::report {
namespace {

const measure::ImageSet::Rendered* find_rendered(const measure::ImageSet& set, const std::string& configuration) {
  for (const auto& rendered : set.variants)
    if (configuration_of(rendered) == configuration) return &rendered;
  return nullptr;
}

const measure::ImageSet* worst_case_for_none(const measure::TradeTable& table, measure::SceneId scene) {
  const measure::ImageSet* worst = nullptr;
  double worst_error = -1.0;
  for (const measure::ImageSet& set : table.images) {
    if (set.scene != scene || set.material.fresnel) continue;
    const measure::TradeRow* none = table.find(measure::Variant::none, scene, set.material.alpha, false);
    if (none && none->flip_ldr > worst_error) worst = &set, worst_error = none->flip_ldr;
  }
  return worst;
}

}  // namespace

std::string strip_name(measure::SceneId scene) { return fmt::format("strip_{}.png", measure::scene_name(scene)); }

std::vector<Strip> strips(const measure::TradeTable& table, const std::vector<Verdict>& all) {
  std::vector<Strip> out;
  for (measure::SceneId scene : table.config.scenes) {
    const measure::ImageSet* set = worst_case_for_none(table, scene);
    if (!set) continue;
    std::vector<std::pair<std::string, std::string>> columns{{"none", "none"}};  // label, configuration
    for (const Verdict& v : all) {
      if (v.recommendation.content != content_of(scene)) continue;
      if (!v.best_engine_image.empty() && columns.size() == 1)
        columns.emplace_back("best engine: " + v.best_engine_image, v.best_engine_image);
      if (v.recommendation.configuration == "none") continue;  // no filter: the first column
      columns.emplace_back(fmt::format("{}: {}", path_name(v.recommendation.path), v.recommendation.configuration),
                           v.recommendation.configuration);
    }
    std::vector<Tile> tiles;
    std::vector<std::string> labels{"ground truth"};
    for (const auto& [label, configuration] : columns)
      if (const auto* rendered = find_rendered(*set, configuration)) tiles.push_back({label, &rendered->image}), labels.push_back(label);
    out.push_back(
        {strip_name(scene),
         fmt::format("{}, alpha {} (where no SAA errs most): {}", measure::scene_name(scene), set->material.alpha, fmt::join(labels, ", ")),
         grid_png(set->reference, tiles)});
  }
  return out;
}

}  // namespace saagen::report

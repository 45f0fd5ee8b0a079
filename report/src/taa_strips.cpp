// The report's strips under TAA (see taa_strips.hpp).
#include "taa_strips.hpp"

#include "sheets.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <utility>
#include <vector>

namespace saagen::report {
namespace {

struct Crop {
  int x = 0, y = 0, size = 0, scale = 1;
};

// The square window of half the frame's smaller side (8 px at least) holding the most
// tonemapped ground-truth radiance (where the highlights are, whichever configuration is
// shown), and the integer enlargement that shows it at 128 px or more. A summed-area table.
Crop brightest_crop(const measure::Image& reference) {
  const int w = reference.width, h = reference.height;
  Crop crop;
  crop.size = std::min(std::min(w, h), std::max(8, std::min(w, h) / 2));
  crop.scale = std::max(1, 128 / crop.size);
  std::vector<double> sat(static_cast<std::size_t>(w + 1) * (h + 1), 0.0);
  const auto at = [&](int x, int y) -> double& { return sat[static_cast<std::size_t>(y) * (w + 1) + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) at(x + 1, y + 1) = measure::tonemap(reference.at(x, y)) + at(x, y + 1) + at(x + 1, y) - at(x, y);
  double best = -1.0;
  for (int y = 0; y + crop.size <= h; ++y)
    for (int x = 0; x + crop.size <= w; ++x) {
      const double sum = at(x + crop.size, y + crop.size) - at(x, y + crop.size) - at(x + crop.size, y) + at(x, y);
      if (sum > best) best = sum, crop.x = x, crop.y = y;
    }
  return crop;
}

measure::Image cropped(const measure::Image& image, const Crop& crop) {
  measure::Image out(crop.size * crop.scale, crop.size * crop.scale);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) out.at(x, y) = image.at(crop.x + x / crop.scale, crop.y + y / crop.scale);
  return out;
}

std::string taa_configuration_of(const measure::ImageSet::Rendered& rendered) {
  return measure::configuration_id(rendered.variant, rendered.feed, rendered.prefilter, rendered.lobe, true);
}

// The +taa row of a case (scene, alpha, no Fresnel) by its configuration id.
const measure::TradeRow* taa_row(const measure::TradeTable& taa, measure::SceneId scene, double alpha, const std::string& configuration) {
  for (const measure::TradeRow& row : taa.rows)
    if (row.taa && !row.fresnel && row.scene == scene && row.alpha == alpha && measure::configuration_id(row) == configuration) return &row;
  return nullptr;
}

const measure::ImageSet* worst_case_for_none_taa(const measure::TradeTable& taa, measure::SceneId scene) {
  const measure::ImageSet* worst = nullptr;
  double worst_error = -1.0;
  for (const measure::ImageSet& set : taa.taa_images) {
    if (set.scene != scene || set.material.fresnel) continue;
    const measure::TradeRow* none = taa_row(taa, scene, set.material.alpha, "none+taa");
    if (none && none->flip_ldr_animation > worst_error) worst = &set, worst_error = none->flip_ldr_animation;
  }
  return worst;
}

Strip strip_of(const measure::TradeTable& taa, const TaaComparison& comparison, const measure::ImageSet& set) {
  const Crop crop = brightest_crop(set.reference);
  std::vector<std::pair<std::string, std::string>> columns{{"none+taa", "none+taa"}};  // label, configuration
  if (!comparison.best_saagen.empty()) columns.emplace_back("best saagen: " + comparison.best_saagen, comparison.best_saagen);
  if (!comparison.best_engine.empty()) columns.emplace_back("best engine: " + comparison.best_engine, comparison.best_engine);
  std::vector<measure::Image> images;
  std::vector<std::string> labels, figures;
  images.reserve(columns.size());
  for (const auto& column : columns) {
    const std::string& configuration = column.second;  // a named copy: clang 14 cannot capture a structured binding
    const auto rendered = std::find_if(set.variants.begin(), set.variants.end(),
                                       [&](const measure::ImageSet::Rendered& r) { return taa_configuration_of(r) == configuration; });
    const measure::TradeRow* row = taa_row(taa, set.scene, set.material.alpha, configuration);
    if (rendered == set.variants.end() || !row) continue;
    images.push_back(cropped(rendered->image, crop));
    labels.push_back(column.first);  // the label of the image kept, also when an earlier column had none
    figures.push_back(fmt::format("{} {:.4f} / {:.2f}", column.first, row->image_error.mean, row->video_error.mean));
  }
  std::vector<Tile> tiles;
  for (std::size_t i = 0; i < images.size(); ++i) tiles.push_back({labels[i], &images[i]});
  const std::string scene(measure::scene_name(set.scene));
  return {taa_strip_name(set.scene),
          fmt::format("{} under TAA, alpha {} (where none+taa errs most), last animation frame, the {} x {} px crop at ({}, {}) "
                      "shown {}x: ground truth, {} (image error / video error at this alpha)",
                      scene, set.material.alpha, crop.size, crop.size, crop.x, crop.y, crop.scale, fmt::join(figures, ", ")),
          grid_png(cropped(set.reference, crop), tiles)};
}

}  // namespace

std::string taa_strip_name(measure::SceneId scene) { return fmt::format("taa_{}.png", measure::scene_name(scene)); }

std::optional<Strip> taa_strip(const measure::TradeTable& taa, const TaaComparison& comparison) {
  const measure::ImageSet* set = worst_case_for_none_taa(taa, comparison.scene);
  if (!set) return std::nullopt;
  return strip_of(taa, comparison, *set);
}

}  // namespace saagen::report

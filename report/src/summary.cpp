// The trade table summed up (see summary.hpp).
#include "saagen/report/summary.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>

namespace saagen::report {
namespace {

// The sizes of the measured scenes that have sizes of their own.
std::vector<measure::TradeSceneSize> measured_scene_sizes(const measure::TradeConfig& c) {
  std::vector<measure::TradeSceneSize> sizes;
  for (const measure::TradeSceneSize& size : c.scene_sizes)
    if (std::find(c.scenes.begin(), c.scenes.end(), size.scene) != c.scenes.end()) sizes.push_back(size);
  return sizes;
}

// "; NAME at WxH px (animation wxh px), ..." for the scenes with sizes of their own.
std::string scene_sizes_line(const measure::TradeConfig& c) {
  std::string line;
  for (const measure::TradeSceneSize& size : measured_scene_sizes(c)) {
    line += fmt::format("{}{} at {}x{} px, {} spp (animation {}x{} px, {} spp)", line.empty() ? "; " : ", ",
                        measure::scene_name(size.scene), size.width, size.height, size.strata * size.strata, size.flicker_width,
                        size.flicker_height, size.flicker_strata * size.flicker_strata);
  }
  return line;
}

}  // namespace

std::string ground_truth_samples(const measure::TradeConfig& c) {
  std::vector<std::string> own;
  for (const measure::TradeSceneSize& size : measured_scene_sizes(c))
    own.push_back(fmt::format("{} {}", measure::scene_name(size.scene), size.strata * size.strata));
  const std::string samples = fmt::format("{}-spp ground truth", c.strata * c.strata);
  return own.empty() ? samples : fmt::format("{} (spp on the scenes of their own size: {})", samples, fmt::join(own, ", "));
}

std::vector<VariantSummary> summarize(const measure::TradeTable& table) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const measure::TradeRow*>> by_configuration;
  for (const measure::TradeRow& row : table.rows) {
    if (row.fresnel) continue;
    const std::string id = measure::configuration_id(row);
    if (!by_configuration.count(id)) order.push_back(id);
    by_configuration[id].push_back(&row);
  }
  std::vector<VariantSummary> summary;
  for (const std::string& id : order) {
    VariantSummary entry;
    entry.variant = id;
    const std::vector<const measure::TradeRow*>& rows = by_configuration[id];
    for (const measure::TradeRow* row : rows) measure::add_over_rows(entry, *row);
    measure::means_over_rows(entry, rows.size());
    entry.cases = rows.size();
    summary.push_back(entry);
  }
  return summary;
}

std::string config_line(const measure::TradeTable& table) {
  const measure::TradeConfig& c = table.config;
  return fmt::format(
             "{}x{} px, {} spp ground truth (Gaussian pixel filter, sigma^2 = 0.25 px^2); animation over {} frames at "
             "{} deg/frame and a camera pan of ({}, {}) px/frame ({}x{} px, {} spp); sigma^2 = {}, kappa = {}; {} derivatives; "
             "prefiltered rows at normal-map LOD bias {}",
             c.width, c.height, c.strata * c.strata, c.frames, c.rotation_degrees_per_frame, c.pan_pixels_per_frame.x,
             c.pan_pixels_per_frame.y, c.flicker_width, c.flicker_height, c.flicker_strata * c.flicker_strata, c.params.sigma2,
             c.params.kappa, c.derivative == ref::Derivative::coarse ? "coarse" : "fine", c.prefilter_lod_bias) +
         (c.half_vector_frame == measure::HalfVectorFrame::transported
              ? "; projected forward filters in transported frames (*_transported_fragment)"
              : "") +
         scene_sizes_line(c);
}

}  // namespace saagen::report

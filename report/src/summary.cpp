// The trade table summed up (see summary.hpp).
#include "saagen/report/summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace saagen::report {
namespace {

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double value : values) sum += value;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

// "; NAME at WxH px (animation wxh px), ..." for the scenes with sizes of their own.
std::string scene_sizes_line(const measure::TradeConfig& c) {
  std::string line;
  for (const measure::TradeSceneSize& size : c.scene_sizes) {
    if (std::find(c.scenes.begin(), c.scenes.end(), size.scene) == c.scenes.end()) continue;
    line += fmt::format("{}{} at {}x{} px, {} spp (animation {}x{} px, {} spp)", line.empty() ? "; " : ", ",
                        measure::scene_name(size.scene), size.width, size.height, size.strata * size.strata, size.flicker_width,
                        size.flicker_height, size.flicker_strata * size.flicker_strata);
  }
  return line;
}

}  // namespace

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
    VariantSummary entry{id};
    std::vector<double> linear, tonemapped, flicker, flicker_display, flip_ldr, flip_hdr, tde, excess, lost;
    for (const measure::TradeRow* row : by_configuration[id]) {
      tde.push_back(row->tde);
      excess.push_back(row->tde_excess_flicker);
      lost.push_back(row->tde_lost_motion);
      flip_ldr.push_back(row->flip_ldr);
      flip_hdr.push_back(row->flip_hdr);
      linear.push_back(row->rmse_linear);
      tonemapped.push_back(row->rmse_tonemapped);
      flicker.push_back(row->flicker);
      flicker_display.push_back(row->flicker_display);
      entry.max_error = std::max(entry.max_error, row->max_error);
    }
    entry.cases = linear.size();
    entry.rmse_linear = mean(linear);
    entry.rmse_tonemapped = mean(tonemapped);
    entry.tde = mean(tde);
    entry.tde_excess_flicker = mean(excess);
    entry.tde_lost_motion = mean(lost);
    entry.flicker = mean(flicker);
    entry.flicker_display = mean(flicker_display);
    entry.flip_ldr = mean(flip_ldr);
    entry.flip_hdr = mean(flip_hdr);
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
         scene_sizes_line(c);
}

}  // namespace saagen::report

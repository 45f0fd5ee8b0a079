// The short verdict as lines of text (see verdict_text.hpp).
#include "verdict_text.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <string_view>

namespace saagen::report {
namespace {

// "engine-hdrp 0.0150, -20 %"
std::string against(const std::string& name, double theirs, double ours, int digits) {
  const double percent = theirs > 0.0 ? 100.0 * (ours - theirs) / theirs : 0.0;
  const std::string change = theirs <= 0.0               ? std::string()
                             : std::fabs(percent) < 10.0 ? fmt::format(", {:+.1f} %", percent)
                                                         : fmt::format(", {:+.0f} %", percent);
  return fmt::format("{} {:.{}f}{}", name, theirs, digits, change);
}

std::string metric_comparison(const char* metric, double ours, double none, const std::string& engine, double engine_value, int digits) {
  std::string text = fmt::format("{} {:.{}f} ({}", metric, ours, digits, against("none", none, ours, digits));
  if (!engine.empty()) text += "; best engine " + against(engine, engine_value, ours, digits);
  return text + ")";
}

// A decision's reason after "no filter -- ": without its own "no filter: ".
std::string without_no_filter(const std::string& reason) {
  constexpr std::string_view prefix = "no filter: ";
  return reason.starts_with(prefix) ? reason.substr(prefix.size()) : reason;
}

// The decision's own words: the chosen configuration's comparison with no SAA (image and flicker
// error, 95 % intervals), then its means beside no SAA's and the best engine's.
std::string headline(const Verdict& v) {
  const Recommendation& r = v.recommendation;
  if (r.configuration == "none")
    return fmt::format("{}, {}: no filter -- {}", path_name(r.path), content_name(r.content), without_no_filter(r.reason));
  return fmt::format(
      "{}, {}: {}; {}, {}", path_name(r.path), content_name(r.content), r.reason,
      metric_comparison("image error", r.metrics.image_error, v.none.image_error, v.best_engine_image, v.engine_image.image_error, 4),
      v.video ? metric_comparison("video error (10 - JOD)", r.metrics.video_error, v.none.video_error, v.best_engine_motion,
                                  v.engine_motion.video_error, 3)
              : metric_comparison("flicker error", r.metrics.flicker_error, v.none.flicker_error, v.best_engine_motion,
                                  v.engine_motion.flicker_error, 5));
}

// "HDR-FLIP to engine-godot (0.0512 vs 0.0498)", per content-mean loss.
std::string mean_losses(const Verdict& v) {
  std::vector<std::string> parts;
  for (const Loss& loss : v.losses)
    parts.push_back(fmt::format("{} to {} ({:.4g} vs {:.4g})", loss.metric, loss.baseline, loss.ours, loss.theirs));
  return fmt::format("{}", fmt::join(parts, ", "));
}

// "tubes: TDE (none + 2 engines), HDR-FLIP (engine-godot)": per scene, each lost metric and whom
// it is lost to (engines counted past two).
std::string scene_losses(const Verdict& v) {
  std::vector<std::string> scenes;
  for (const auto& [scene, losses] : v.scene_losses) {
    std::vector<std::string> metrics;
    for (const VerdictMetric& metric : kVerdictMetrics) {
      bool none = false;
      std::vector<std::string> engines;
      for (const Loss& loss : losses) {
        if (loss.metric != metric.name) continue;
        if (loss.baseline == "none")
          none = true;
        else
          engines.push_back(loss.baseline);
      }
      if (!none && engines.empty()) continue;
      std::vector<std::string> whom;
      if (none) whom.push_back("none");
      if (engines.size() > 2)
        whom.push_back(fmt::format("{} engines", engines.size()));
      else
        whom.insert(whom.end(), engines.begin(), engines.end());
      metrics.push_back(fmt::format("{} ({})", metric.name, fmt::join(whom, " + ")));
    }
    scenes.push_back(fmt::format("{}: {}", measure::scene_name(scene), fmt::join(metrics, ", ")));
  }
  return fmt::format("{}", fmt::join(scenes, "; "));
}

}  // namespace

std::string verdict_note(const measure::TradeTable& table) {
  return fmt::format(
      "the decision's comparison with no SAA, paired, 95 % intervals, then means over the content's scenes and alphas, no Fresnel; "
      "lower is better; image error = LDR-FLIP of every animation frame; temporal = {}; docs/TEMPORAL.md; % = change from the "
      "baseline",
      temporal_metric_description(table));
}

// The verdict lines of one recommendation: the headline, then where it loses (or that it does not).
std::vector<std::string> verdict_lines(const Verdict& v) {
  std::vector<std::string> lines{headline(v)};
  const Recommendation& r = v.recommendation;
  if (r.speed_configuration != r.configuration)
    lines.push_back(r.speed_configuration == "none" ? "prefer speed: no filter -- " + without_no_filter(r.speed_reason)
                                                    : "prefer speed: " + r.speed_configuration + " -- " + r.speed_reason);
  // The older metrics, not the verdict's, so that nothing it gives up is hidden.
  if (!v.losses.empty()) lines.push_back("in the older metrics (means, no interval), loses on the content means: " + mean_losses(v));
  if (!v.scene_losses.empty()) lines.push_back("in the older metrics, loses per scene: " + scene_losses(v));
  if (v.losses.empty() && v.scene_losses.empty() && v.recommendation.configuration != "none")
    lines.push_back("in the older metrics too, beats none and every engine on LDR-FLIP, TDE, HDR-FLIP and tonemapped RMSE, on every scene");
  return lines;
}

// Verdicts grouped by render path, then content type.
std::vector<Verdict> ordered_verdicts(const measure::TradeTable& table) {
  std::vector<Verdict> all = verdicts(table, recommend(table));
  std::stable_sort(all.begin(), all.end(),
                   [](const Verdict& a, const Verdict& b) { return a.recommendation.path < b.recommendation.path; });
  return all;
}

std::vector<std::string> by_alpha_lines(const measure::TradeTable& table) { return by_alpha_lines(recommend_by_alpha(table)); }

std::vector<std::string> by_alpha_lines(const std::vector<AlphaRecommendation>& recs) {
  std::vector<std::string> lines;
  std::vector<Content> contents;  // in the table's order
  for (const AlphaRecommendation& rec : recs)
    if (std::find(contents.begin(), contents.end(), rec.content) == contents.end()) contents.push_back(rec.content);
  for (Path path : {Path::forward, Path::deferred})
    for (Content content : contents) {
      std::vector<std::string> cells;
      for (const AlphaRecommendation& rec : recs)
        if (rec.path == path && rec.content == content) cells.push_back(fmt::format("alpha {:g} {}", rec.alpha, rec.configuration));
      if (!cells.empty())
        lines.push_back(
            fmt::format("{}, {}: {}", content_name(content), path == Path::forward ? "forward" : "deferred", fmt::join(cells, "; ")));
    }
  return lines;
}

}  // namespace saagen::report

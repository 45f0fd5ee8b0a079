// The sanity suite (see sanity.hpp).
#include "saagen/report/sanity.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>
#include <optional>
#include <span>

namespace saagen::report {

namespace {

// The series of one clip per material of a scene, against the first ground-truth seed only.
using Clip = std::vector<measure::SeedSeries>;

measure::SeedSeries first_seed(const measure::SeedSeries& series) { return {series[0], {}}; }
// The verdict's temporal series (comparison.hpp, temporal_metric): the video error where measured.
const measure::SeedSeries& temporal_series(const measure::AnimationSeries& series) {
  return series.video[0].empty() ? series.flicker : series.video;
}
measure::SeedSeries first_seed_temporal(const measure::AnimationSeries& series) { return first_seed(temporal_series(series)); }

// One result's clips on a scene's sanity materials (one per alpha), per metric.
struct Clips {
  Clip image, temporal, lag;
};

struct SceneClips {
  std::vector<double> alphas;
  std::map<std::string, Clips> clips;   // by result name
  std::map<std::string, Clip> flicker;  // name -> flicker error: whether the ground truth moves
};

SceneClips scene_clips(const measure::TradeTable& table, measure::SceneId scene) {
  SceneClips out;
  for (const measure::SanityRow& row : table.sanity) {
    if (row.scene != scene || row.fresnel) continue;
    if (std::find(out.alphas.begin(), out.alphas.end(), row.alpha) == out.alphas.end()) out.alphas.push_back(row.alpha);
    const std::string name(measure::sanity_name(row.result));
    Clips& clips = out.clips[name];
    clips.image.push_back(first_seed(row.series.image));
    clips.temporal.push_back(first_seed_temporal(row.series));
    clips.lag.push_back(first_seed(row.series.lag));
    out.flicker[name].push_back(first_seed(row.series.flicker));
  }
  return out;
}

// A configuration's clips on the scene's sanity materials, first seed only (nullopt if missing).
std::optional<Clips> configuration_clips(const measure::TradeTable& table, measure::SceneId scene, const std::vector<double>& alphas,
                                         const std::string& configuration) {
  Clips out;
  for (double alpha : alphas) {
    const measure::TradeRow* found = nullptr;
    for (const measure::TradeRow& row : table.rows)
      if (row.scene == scene && row.alpha == alpha && !row.fresnel && !row.taa && measure::configuration_id(row) == configuration)
        found = &row;
    if (!found) return std::nullopt;
    out.image.push_back(first_seed(found->series.image));
    out.temporal.push_back(first_seed_temporal(found->series));
    out.lag.push_back(first_seed(found->series.lag));
  }
  return out;
}

double clip_mean(const Clip& clip) { return measure::series_interval(clip).mean; }

bool worse(const MetricDifference& d) { return outcome_of(d) == MetricOutcome::worse; }
bool better(const MetricDifference& d) { return outcome_of(d) == MetricOutcome::better; }
// The verdict's "beats": better beyond the interval in one metric, worse in none.
bool beats(const MetricDifference& image, const MetricDifference& flicker) {
  return !worse(image) && !worse(flicker) && (better(image) || better(flicker));
}

// Each degenerate result that must rank clearly worse, and the result it is compared with: frozen
// and no-highlight against the quarter-sample ground truth; delayed, which is made from the second
// seed's frames (four times the quarter's samples), against those frames on time.
constexpr std::pair<const char*, const char*> kClearlyWorse[] = {
    {"delayed", "other-seed"}, {"frozen", "quarter-samples"}, {"no-highlight", "quarter-samples"}};
// The degenerate results, which must never be the verdict's choice: each misses what the ground
// truth shows (its timing, its motion, its highlight). The blurred result is not one of them: it
// must rank below the quarter-sample ground truth (the first rule), but a 1 px blur of the
// converged image is what a pixel-footprint filter aims at, and where it beats every 1-spp
// configuration the table says so.
constexpr const char* kDegenerate[] = {"delayed", "frozen", "no-highlight"};

bool is_degenerate(const std::string& name) {
  return std::find(std::begin(kDegenerate), std::end(kDegenerate), name) != std::end(kDegenerate);
}

// The verdict's choice on the scene among `candidates` against no SAA (saagen/decision.hpp's
// accuracy rule): among those no worse than no SAA in either metric, better in at least one and
// not late (following the ground truth more than half a frame late beyond the interval, lag_of),
// the lowest temporal error, then image error ("" if none).
std::string verdict_choice(const std::map<std::string, Clips>& candidates, const Clips& none) {
  std::string chosen;
  std::pair<double, double> best{0.0, 0.0};
  for (const auto& [name, clips] : candidates) {
    const MetricDifference image = compare_series(clips.image, none.image), temporal = compare_series(clips.temporal, none.temporal);
    if (!beats(image, temporal) || worse(lag_of(clips.lag))) continue;
    const std::pair<double, double> key{temporal.difference.mean, image.difference.mean};
    if (chosen.empty() || key < best) chosen = name, best = key;
  }
  return chosen;
}

// The configurations' rows of one cell (non-Fresnel; without TAA, or under it), by configuration id.
std::map<std::string, const measure::TradeRow*> cell_rows(const measure::TradeTable& table, measure::SceneId scene, double alpha,
                                                          bool taa) {
  std::map<std::string, const measure::TradeRow*> rows;
  for (const measure::TradeRow& row : table.rows)
    if (row.scene == scene && row.alpha == alpha && !row.fresnel && row.taa == taa) rows[measure::configuration_id(row)] = &row;
  return rows;
}

// stable, per alpha: every configuration's standing against no SAA (beats; ties; loses or mixed,
// "against") is read as the verdict reads it, and again with the bias the ground truth's samples
// leave taken out (without_sample_bias, from the quarter-sample ground truth). The verdict reads a
// metric whose call that bias would change as a tie (comparison.hpp, bias_limited), so what can
// still reverse is a standing whose other metric turns: beats on the video error with the image
// error a tie that is worse once the bias is out. Such a comparison has not converged: more samples
// in the ground truth would change its call, so the verdict reads it as a tie (comparison.hpp,
// PairedComparison::unconverged). The rule fails where the verdict still calls one (beats, loses
// or mixed), and lists the alphas with one (unconverged_alphas); a standing that moves to or from
// a tie is recorded, not failed (an interval's end near 0 moves with any estimate). It asks the
// question the decision depends on: whether more samples in the ground truth would change what
// it decides. Noise in a ground truth is not neutral: one that catches a highlight in a few pixels
// by chance favours the results that miss it as it does, as 1-spp no SAA does (docs/TEMPORAL.md).
// An earlier rule, another seed beating the quarter-sample ground truth in the image or temporal
// error, failed on converged ground truths, where both are too close for the interval to tell apart.
// With `taa`, the same for the +taa rows against none+taa: the verdict under TAA.
void check_stability(const measure::TradeTable& table, const std::vector<double>& alphas, measure::SceneId scene, bool taa,
                     SceneSanity& out) {
  const std::string baseline = taa ? "none+taa" : "none";
  for (const double alpha : alphas) {
    const auto rows = cell_rows(table, scene, alpha, taa);
    const auto none = rows.find(baseline);
    if (none == rows.end() || none->second->quarter_series.image[0].empty()) continue;
    Convergence cell{alpha, taa, 0, {}, {}, true, {}};
    for (const auto& [id, row] : rows) {
      if (id == baseline || row->quarter_series.image[0].empty()) continue;
      ++cell.comparisons;
      const measure::TradeRow& base = *none->second;
      const CellPair cell_pair{&row->series, &base.series, &row->quarter_series, &base.quarter_series};
      const PairedComparison comparison = compare_cells(id, baseline, std::span(&cell_pair, 1));
      const MetricDifference& temporal = temporal_metric(comparison);
      const Standing read = standing(comparison.image, temporal);
      const Standing converged = standing(without_sample_bias(comparison.image), without_sample_bias(temporal));
      if (read == converged) continue;
      cell.moved.push_back({id, std::string(standing_name(read)), std::string(standing_name(converged))});
      if (!comparison.unconverged) continue;
      cell.reversed.push_back(id);
      if (decision::outcome(to_decision(comparison)) != decision::Outcome::ties || comparison_outcome_name(comparison) != "ties")
        cell.called.push_back(id);
    }
    cell.converged = cell.reversed.empty();
    out.convergence.push_back(cell);
    if (cell.converged) continue;
    (taa ? out.unconverged_taa_alphas : out.unconverged_alphas).push_back(alpha);
    if (cell.called.empty()) continue;
    out.failures.push_back(
        fmt::format("{}: the verdict{} calls a comparison more samples would reverse at alpha {:g}: {} of {} configurations "
                    "reverse their standing against {} (beats <-> loses or mixed) once the bias of the ground truth's "
                    "samples is taken out, and the verdict does not read them as ties ({})",
                    measure::scene_name(scene), taa ? " under TAA" : "", alpha, cell.called.size(), cell.comparisons,
                    taa ? "TAA alone" : "no SAA", fmt::join(cell.called, ", ")));
  }
}

SceneSanity check_scene(const measure::TradeTable& table, measure::SceneId scene) {
  SceneSanity out;
  out.scene = scene;
  SceneClips clips = scene_clips(table, scene);
  const auto none = configuration_clips(table, scene, clips.alphas, "none");
  if (none) clips.clips["none"] = *none;
  const auto& quarter = clips.clips.at("quarter-samples");
  for (const auto& [name, clip] : clips.clips) {
    SanityEntry entry{name,
                      clip_mean(clip.image),
                      clip_mean(clip.temporal),
                      compare_series(clip.image, quarter.image),
                      compare_series(clip.temporal, quarter.temporal),
                      clip_mean(clip.lag)};
    out.entries.push_back(entry);
  }
  out.moves = worse(compare_series(clips.flicker.at("frozen"), clips.flicker.at("other-seed")));
  out.video = std::any_of(table.sanity.begin(), table.sanity.end(), [](const measure::SanityRow& r) { return !r.series.video[0].empty(); });
  // best: nothing beats another seed; nothing made from fewer samples beats a quarter of them.
  for (const auto& [name, clip] : clips.clips) {
    for (const char* best : {"other-seed", "quarter-samples"}) {
      if (name == best || name == "other-seed" || (std::string_view(best) == "quarter-samples" && name == "delayed")) continue;
      const MetricDifference image = compare_series(clip.image, clips.clips.at(best).image);
      const MetricDifference flicker = compare_series(clip.temporal, clips.clips.at(best).temporal);
      if (beats(image, flicker))
        out.failures.push_back(fmt::format("{}: {} beats {} (image {:+.4g}, temporal {:+.4g})", measure::scene_name(scene), name, best,
                                           image.difference.mean, flicker.difference.mean));
    }
  }
  // clearly worse, where the ground truth moves: each against the result of the same samples.
  if (out.moves) {
    for (const auto& [name, against] : kClearlyWorse) {
      const auto& clip = clips.clips.at(name);
      const auto& base = clips.clips.at(against);
      const MetricDifference image = compare_series(clip.image, base.image), flicker = compare_series(clip.temporal, base.temporal);
      const MetricDifference lag = compare_series(clip.lag, base.lag);
      const auto text = [](const MetricDifference& d) {
        return fmt::format("{:+.4g} [{:+.4g}, {:+.4g}]", d.difference.mean, d.difference.low, d.difference.high);
      };
      if (!worse(image) && !worse(flicker) && !worse(lag))
        out.failures.push_back(fmt::format("{}: {} is not worse than {} beyond the interval in any metric (image {}, temporal {}, lag {})",
                                           measure::scene_name(scene), name, against, text(image), text(flicker), text(lag)));
    }
  }
  check_stability(table, clips.alphas, scene, false, out);
  check_stability(table, clips.alphas, scene, true, out);
  if (none) {
    std::map<std::string, Clips> candidates;
    for (const char* name : kDegenerate) candidates[name] = clips.clips.at(name);
    candidates["blurred"] = clips.clips.at("blurred");
    std::vector<std::string> ids;
    for (const measure::TradeRow& row : table.rows)
      if (row.scene == scene && !row.taa && std::find(ids.begin(), ids.end(), measure::configuration_id(row)) == ids.end())
        ids.push_back(measure::configuration_id(row));
    for (const std::string& id : ids)
      if (id != "none")
        if (const auto c = configuration_clips(table, scene, clips.alphas, id)) candidates[id] = *c;
    const std::string chosen = verdict_choice(candidates, *none);
    out.verdict_choice = chosen;
    if (is_degenerate(chosen))
      out.failures.push_back(fmt::format("{}: the degenerate result {} wins the verdict", measure::scene_name(scene), chosen));
  }
  return out;
}

}  // namespace

std::vector<SceneSanity> check_sanity(const measure::TradeTable& table) {
  std::vector<SceneSanity> scenes;
  for (measure::SceneId scene : table.config.scenes) {
    const bool has_rows =
        std::any_of(table.sanity.begin(), table.sanity.end(), [&](const measure::SanityRow& r) { return r.scene == scene; });
    if (has_rows) scenes.push_back(check_scene(table, scene));
  }
  return scenes;
}

std::string format_sanity(const std::vector<SceneSanity>& scenes) {
  const bool video = std::any_of(scenes.begin(), scenes.end(), [](const SceneSanity& scene) { return scene.video; });
  const std::string temporal = video ? "video error" : "flicker error";
  std::string text = fmt::format("{:<20} {:<16} {:>11} {:>13} {:>10}  {:<22} {:<22}\n", "scene", "result", "image error", temporal, "lag",
                                 "image vs quarter", temporal + " vs quarter");
  const auto cell = [](const MetricDifference& d) {
    return fmt::format("{:+.4f} [{:+.4f},{:+.4f}]", d.difference.mean, d.difference.low, d.difference.high);
  };
  int failures = 0;
  for (const SceneSanity& scene : scenes) {
    for (const SanityEntry& e : scene.entries)
      text += fmt::format("{:<20} {:<16} {:>11.4f} {:>13.5f} {:>+10.2e}  {:<22} {:<22}\n", measure::scene_name(scene.scene), e.result,
                          e.image_error, e.flicker_error, e.lag, cell(e.image_vs_quarter), cell(e.flicker_vs_quarter));
    text += fmt::format("  the verdict's choice with the degenerate results entered: {}{}\n",
                        scene.verdict_choice.empty() ? "no filter" : scene.verdict_choice,
                        is_degenerate(scene.verdict_choice) ? " (degenerate)"
                        : scene.verdict_choice == "blurred" ? " (the converged animation blurred by 1 px beats every 1-spp configuration)"
                                                            : "");
    for (const std::string& failure : scene.failures) text += "  FAILED " + failure + "\n";
    failures += static_cast<int>(scene.failures.size());
  }
  text += failures == 0 ? fmt::format("sanity: passed on {} scenes\n", scenes.size())
                        : fmt::format("sanity: {} rule(s) failed on {} scenes\n", failures, scenes.size());
  return text;
}

std::string format_unconverged(const std::vector<SceneSanity>& scenes) {
  std::vector<std::string> cells;
  for (const SceneSanity& scene : scenes) {
    for (double alpha : scene.unconverged_alphas) cells.push_back(fmt::format("{} at alpha {:g}", measure::scene_name(scene.scene), alpha));
    for (double alpha : scene.unconverged_taa_alphas)
      cells.push_back(fmt::format("{} at alpha {:g} under TAA", measure::scene_name(scene.scene), alpha));
  }
  if (cells.empty()) return "";
  return fmt::format(
      "The ground truth has not converged on {} cell(s): {}. There, a configuration that beats no SAA (under TAA: TAA alone) "
      "would lose to it or be mixed, or the reverse, once the bias the ground truth's samples leave is taken out (estimated "
      "from the quarter-sample ground truth; the sanity suite's stable rule): the verdict reads those comparisons as ties. "
      "More samples would settle them: --truth-samples-scale 2 (docs/TEMPORAL.md).\n",
      cells.size(), fmt::join(cells, ", "));
}

nlohmann::json sanity_json(const std::vector<SceneSanity>& scenes) {
  const auto difference = [](const MetricDifference& d) {
    return nlohmann::json{{"mean", d.difference.mean}, {"low", d.difference.low}, {"high", d.difference.high}};
  };
  nlohmann::json out = nlohmann::json::array();
  for (const SceneSanity& scene : scenes) {
    nlohmann::json convergence = nlohmann::json::array();
    for (const Convergence& c : scene.convergence) {
      nlohmann::json moved = nlohmann::json::array();
      for (const StandingMove& m : c.moved)
        moved.push_back({{"configuration", m.configuration}, {"standing", m.standing}, {"extrapolated", m.extrapolated}});
      convergence.push_back(
          {{"alpha", c.alpha}, {"comparisons", c.comparisons}, {"moved", moved}, {"reversed", c.reversed}, {"converged", c.converged}});
      if (!c.called.empty()) convergence.back()["called"] = c.called;  // the stable rule's failures
      if (c.taa) convergence.back()["taa"] = true;
    }
    nlohmann::json entries = nlohmann::json::array();
    for (const SanityEntry& e : scene.entries)
      entries.push_back({{"result", e.result},
                         {"image_error", e.image_error},
                         {scene.video ? "video_error" : "flicker_error", e.flicker_error},
                         {"image_vs_quarter", difference(e.image_vs_quarter)},
                         {scene.video ? "video_vs_quarter" : "flicker_vs_quarter", difference(e.flicker_vs_quarter)},
                         {"lag", e.lag}});
    out.push_back({{"scene", std::string(measure::scene_name(scene.scene))},
                   {"moves", scene.moves},
                   {"entries", entries},
                   {"failures", scene.failures},
                   {"verdict_choice", scene.verdict_choice},
                   {"convergence", convergence},
                   {"unconverged_alphas", scene.unconverged_alphas},
                   {"passed", scene.failures.empty()}});
    const bool taa = std::any_of(scene.convergence.begin(), scene.convergence.end(), [](const Convergence& c) { return c.taa; });
    if (taa) out.back()["unconverged_taa_alphas"] = scene.unconverged_taa_alphas;  // a table measured with --taa
  }
  return out;
}

}  // namespace saagen::report

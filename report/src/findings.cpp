#include "saagen/report/findings.hpp"

#include "saagen/measure/gltf.hpp"
#include "saagen/report/comparison.hpp"
#include "saagen/scene/planner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <tuple>

namespace saagen::report {

namespace {

bool starts_with(const std::string& text, std::string_view prefix) { return text.rfind(prefix, 0) == 0; }

bool is_saagen_configuration(const std::string& configuration) {
  return configuration != "none" && !is_engine_configuration(configuration) && !is_measurement_configuration(configuration);
}

RowFilter content_filter(Content content) {
  return [content](const measure::TradeRow& row) { return content_of(row.scene) == content; };
}

std::vector<Content> contents_of(const measure::TradeTable& table) {
  std::vector<Content> contents;
  for (measure::SceneId scene : table.config.scenes)
    if (std::find(contents.begin(), contents.end(), content_of(scene)) == contents.end()) contents.push_back(content_of(scene));
  return contents;
}

// The configurations measured on every scene of a content type (the geometric feed exists only
// where the scene has normal detail).
std::vector<std::string> configurations_of(const measure::TradeTable& table, Content content) {
  std::vector<std::string> ids;
  for (const std::string& id : configurations(table))
    if (mean_metrics(table, id, content_filter(content)).cases > 0) ids.push_back(id);
  return ids;
}

}  // namespace

Content content_of(measure::SceneId scene) {
  if (measure::is_gltf_coat_scene(scene)) return Content::clearcoat;
  if (measure::scene_has_normal_map(scene)) return Content::normal_mapped;
  return measure::scene_has_normal_detail(scene) ? Content::bumps : Content::curved;
}

Metrics row_metrics(const measure::TradeRow& row) {
  Metrics m;
  static_cast<measure::RowMetrics&>(m) = row;
  m.image_error = row.image_error.mean;
  m.flicker_error = row.flicker_error.mean;
  m.video_error = row.video_error.mean;
  m.cases = 1;
  return m;
}

namespace {

// The verdict's metrics of Metrics, averaged as the scalar metrics are.
constexpr double Metrics::*kVerdictMeans[] = {&Metrics::image_error, &Metrics::flicker_error, &Metrics::video_error};

}  // namespace

bool has_video_metric(const measure::TradeTable& table) {
  return std::any_of(table.rows.begin(), table.rows.end(), [](const measure::TradeRow& row) { return !row.series.video[0].empty(); });
}

std::string temporal_metric_description(const measure::TradeTable& table) {
  return has_video_metric(table) ? "video error (10 - ColorVideoVDP's JOD of the animation clip against the ground truth's)"
                                 : "flicker error (pooled frame-to-frame change against the ground truth's)";
}

Metrics mean_metrics(const measure::TradeTable& table, const std::string& configuration, const RowFilter& keep) {
  Metrics m;
  for (const measure::TradeRow& row : table.rows) {
    if (row.fresnel || measure::configuration_id(row) != configuration || !keep(row)) continue;
    const Metrics r = row_metrics(row);
    measure::add_over_rows(m, r);
    for (auto field : kVerdictMeans) m.*field += r.*field;
    ++m.cases;
  }
  measure::means_over_rows(m, m.cases);
  if (m.cases)
    for (auto field : kVerdictMeans) m.*field /= static_cast<double>(m.cases);
  return m;
}

std::vector<std::string> configurations(const measure::TradeTable& table) {
  std::vector<std::string> ids;
  for (const measure::TradeRow& row : table.rows) {
    const std::string id = measure::configuration_id(row);
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  }
  return ids;
}

std::string_view path_name(Path path) { return path == Path::forward ? "forward" : "deferred"; }

bool is_engine_configuration(const std::string& configuration) { return starts_with(configuration, "engine-"); }

bool is_measurement_configuration(const std::string& configuration) {
  const std::string_view suffix = "/exact";
  return configuration.size() >= suffix.size() && configuration.compare(configuration.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool serves(const std::string& configuration, Path path) {
  if (configuration == "none" || is_engine_configuration(configuration)) return true;
  return starts_with(configuration, path == Path::forward ? "forward-" : "deferred-");
}

// Engines' forms cost what deferred-sum costs: the same operations (two normal derivatives, their
// squared lengths, a min and an add; the pow-based forms of Unreal and Babylon.js add one
// transcendental). bench_shading measures deferred-sum.
namespace {

// The shader a configuration costs: its variant and lobe ("deferred-avg:geometric+lean/tail" ->
// "deferred-avg/tail"); the feed and the prefilter change inputs, not the variant's code.
std::string costed_variant(const std::string& configuration) {
  if (is_engine_configuration(configuration)) return "deferred-sum";
  const std::size_t slash = configuration.find('/');
  const std::string lobe = slash == std::string::npos ? "" : configuration.substr(slash);
  return configuration.substr(0, configuration.find_first_of(":+/")) + lobe;
}

}  // namespace

std::optional<double> configuration_cost(const CostTable* costs, const std::string& configuration, bool time) {
  const std::string variant = costed_variant(configuration);
  if (variant == "none") return time ? 1.0 : 0.0;
  if (!costs) return std::nullopt;
  const std::optional<VariantCost> cost = costs->find(variant);
  if (!cost) return std::nullopt;
  return time ? cost->time_ratio : cost->delta_instructions;
}

std::optional<double> configuration_isa_cost(const CostTable* costs, const std::string& configuration) {
  const std::string variant = costed_variant(configuration);
  if (variant == "none") return 1.0;
  if (!costs) return std::nullopt;
  const std::optional<VariantCost> cost = costs->find(variant);
  return cost ? cost->isa_ratio : std::nullopt;
}

bool costs_at_most(const CostTable* costs, const std::string& a, const std::string& b) {
  // The optimized SPIR-V delta first: deterministic, while lavapipe's time ratios of the cheap
  // filters differ by less than their own quartile spread (bench_shading: 0.95-1.0, p25-p75
  // +-0.06), which would order equal-cost forms by noise.
  // ACO's ISA estimate first: deterministic and a GPU's cost model; within kIsaTieTolerance
  // (about two instructions of these shaders) costs count as equal, as in the planner.
  const auto isa_a = configuration_isa_cost(costs, a), isa_b = configuration_isa_cost(costs, b);
  if (isa_a && isa_b) return *isa_a <= *isa_b * (1.0 + kIsaTieTolerance);
  for (bool time : {false, true}) {
    const auto ca = configuration_cost(costs, a, time), cb = configuration_cost(costs, b, time);
    if (ca && cb) return *ca <= *cb;
  }
  return true;
}

namespace {

// The scenes among `keep`'s rows on which `configuration` loses to `baseline` beyond the interval
// in either metric (loses or mixed there): what a recommendation for the rows' content must not do.
std::vector<std::string> scenes_lost(const measure::TradeTable& table, const ConfigurationRows& index, const std::string& configuration,
                                     const std::string& baseline, const RowFilter& keep) {
  std::vector<std::string> lost;
  for (const measure::SceneId scene : table.config.scenes) {
    const RowFilter on_scene = [&](const measure::TradeRow& row) { return row.scene == scene && keep(row); };
    const PairedComparison c = compare_configurations(index, configuration, baseline, on_scene);
    if (c.cells == 0) continue;
    const decision::Outcome there = decision::outcome(to_decision(c));
    if (there == decision::Outcome::loses || there == decision::Outcome::mixed) lost.emplace_back(measure::scene_name(scene));
  }
  return lost;
}

// The cells (a scene at one alpha) among `keep`'s rows on which `configuration` loses to `baseline`
// beyond the interval in either metric: what a recommendation for a material of that roughness
// must not do (a cell comparison's outcome in the JSON, paired on that cell alone).
std::vector<CellLoss> cells_lost(const measure::TradeTable& table, const ConfigurationRows& index, const std::string& configuration,
                                 const std::string& baseline, const RowFilter& keep) {
  std::vector<CellLoss> lost;
  for (const measure::SceneId scene : table.config.scenes)
    for (const double alpha : table.config.alphas) {
      const RowFilter in_cell = [&](const measure::TradeRow& row) { return row.scene == scene && row.alpha == alpha && keep(row); };
      const PairedComparison c = compare_configurations(index, configuration, baseline, in_cell);
      if (c.cells == 0) continue;
      const decision::Outcome there = decision::outcome(to_decision(c));
      if (there == decision::Outcome::loses || there == decision::Outcome::mixed)
        lost.push_back({std::string(measure::scene_name(scene)), alpha});
    }
  return lost;
}

// Whether the row can be a content's recommendation: it beats the baseline, is on time and loses
// on none of the scenes (decision.hpp's eligibility, before a material's own constraints).
bool may_be_recommended(const ContentRow& row) {
  return row.against_none && decision::outcome(*row.against_none) == decision::Outcome::beats && !decision::late(*row.against_none) &&
         row.loses_on.empty();
}

// Each recommendable row's not_worse_than: the other recommendable rows it is worse than beyond the
// interval in neither metric, paired on `keep`'s cells (decision.hpp: a lead inside the interval
// is a tie, and the cheaper of a tie wins).
void pair_recommendable(const ConfigurationRows& index, const RowFilter& keep, std::vector<ContentRow>& rows) {
  for (ContentRow& row : rows) {
    if (!may_be_recommended(row)) continue;
    for (const ContentRow& other : rows) {
      if (&other == &row || !may_be_recommended(other)) continue;
      const PairedComparison c = compare_configurations(index, row.configuration, other.configuration, keep);
      if (c.cells == 0) continue;
      const decision::Outcome against = decision::outcome(to_decision(c));
      if (against == decision::Outcome::ties || against == decision::Outcome::beats) row.not_worse_than.push_back(other.configuration);
    }
  }
}

}  // namespace

std::vector<ContentRow> measured_rows(const measure::TradeTable& table, const RowFilter& keep, std::string_view scope,
                                      const std::string& baseline) {
  std::vector<ContentRow> rows;
  const bool video = has_video_metric(table);
  const ConfigurationRows index(table);
  for (const std::string& id : configurations(table)) {
    const Metrics m = mean_metrics(table, id, keep);
    if (!m.cases || is_measurement_configuration(id)) continue;
    ContentRow row{std::string(scope), id, m.image_error, video ? m.video_error : m.flicker_error, std::nullopt};
    // The decision reads the paired comparison with its intervals (comparison.hpp).
    if (id != baseline) {
      const PairedComparison against_baseline = compare_configurations(index, id, baseline, keep);
      if (against_baseline.cells > 0) row.against_none = to_decision(against_baseline);
      if (row.against_none && decision::outcome(*row.against_none) == decision::Outcome::beats) {
        row.loses_on = scenes_lost(table, index, id, baseline, keep);
        row.loses_at = cells_lost(table, index, id, baseline, keep);
      }
    }
    rows.push_back(std::move(row));
  }
  pair_recommendable(index, keep, rows);
  return rows;
}

std::string without_taa(std::string configuration) {
  constexpr std::string_view taa = "+taa";
  if (const std::size_t at = configuration.find(taa); at != std::string::npos) configuration.erase(at, taa.size());
  return configuration;
}

std::vector<ContentRow> measured_taa_rows(const measure::TradeTable& table, Content content) {
  const RowFilter keep = [content](const measure::TradeRow& row) { return row.taa && content_of(row.scene) == content; };
  std::vector<ContentRow> rows = measured_rows(table, keep, content_name(content), "none+taa");
  for (ContentRow& row : rows) {
    row.configuration = without_taa(row.configuration);
    for (std::string& other : row.not_worse_than) other = without_taa(other);
  }
  return rows;
}

// Whether the table's projected forward filters were shaded with their transported wrappers,
// which then cost them (decide_material).
bool measured_transported(const measure::TradeTable& table) {
  return table.config.half_vector_frame == measure::HalfVectorFrame::transported;
}

MaterialDecision decide_on(const measure::TradeTable& table, const std::vector<ContentRow>& rows, Path path, Content content, bool speed,
                           std::string_view baseline) {
  Material material = reference_material(path == Path::forward ? RenderPath::forward : RenderPath::deferred, content);
  if (speed) material.prefer = Preference::speed;
  return decide_material(Catalogue::builtin(), material, kDefaultGpuFamily, rows, measured_transported(table), baseline,
                         table.decision_timing.get());
}

namespace {

// The reference materials shade one light, as the trade renders.
int decided_lights() { return reference_material(RenderPath::forward, Content::curved).lights; }

// The decision_timing where it costs the decisions (taken at decided_lights), else null.
const MeasuredTradeTable* deciding_timing(const measure::TradeTable& table) {
  const MeasuredTradeTable* timing = table.decision_timing.get();
  return timing && timing->timed_at(decided_lights()) ? timing : nullptr;
}

}  // namespace

std::string decision_cost_axis(const measure::TradeTable& table) {
  if (const MeasuredTradeTable* timing = deciding_timing(table))
    return fmt::format("{} GPU time ratio to no SAA at {} light", timing->device_name(), decided_lights());
  return fmt::format("{} ISA ratio to no SAA", kDefaultGpuFamily);
}

std::string decision_cost_words(const measure::TradeTable& table) {
  const MeasuredTradeTable* timing = table.decision_timing.get();
  if (!timing) return decision_cost_axis(table);
  if (deciding_timing(table)) return fmt::format("{} ({})", decision_cost_axis(table), timing->source_name);
  return fmt::format("{} ({} was timed at {} lights)", decision_cost_axis(table), timing->source_name, timing->lights);
}

std::string chosen_configuration(const MaterialDecision& made) {
  return made.decision.chosen ? made.candidates[*made.decision.chosen].configuration : "none";
}

std::vector<Recommendation> recommend(const measure::TradeTable& table) {
  std::vector<Recommendation> recs;
  for (Content content : contents_of(table)) {
    // Without TAA: the +taa rows are compared with none+taa (taa_summary.hpp).
    const RowFilter keep = [content](const measure::TradeRow& row) { return !row.taa && content_of(row.scene) == content; };
    const std::vector<ContentRow> rows = measured_rows(table, keep, content_name(content));
    for (Path path : {Path::forward, Path::deferred}) {
      const MaterialDecision made = decide_on(table, rows, path, content), speed = decide_on(table, rows, path, content, true);
      const std::string id = chosen_configuration(made);
      recs.push_back(
          {path, content, id, mean_metrics(table, id, keep), made.decision.reason, chosen_configuration(speed), speed.decision.reason});
    }
  }
  return recs;
}

std::vector<double> measured_alphas(const measure::TradeTable& table) {
  std::vector<double> alphas = table.config.alphas;
  std::sort(alphas.begin(), alphas.end());
  alphas.erase(std::unique(alphas.begin(), alphas.end()), alphas.end());
  return alphas;
}

namespace {

// Per content (`rows_of` gives its rows) and measured alpha, the decision against `baseline` with
// the rows' cell losses at that alpha (add_cell_losses).
std::vector<AlphaRecommendation> decide_by_alpha(const measure::TradeTable& table, const std::vector<Content>& contents,
                                                 const std::function<std::vector<ContentRow>(Content)>& rows_of,
                                                 std::string_view baseline) {
  std::vector<AlphaRecommendation> recs;
  const std::vector<double> alphas = measured_alphas(table);
  for (Content content : contents) {
    const std::vector<ContentRow> rows = rows_of(content);
    if (rows.empty()) continue;
    for (const double alpha : alphas) {
      std::vector<ContentRow> at_alpha = rows;
      for (ContentRow& row : at_alpha) add_cell_losses(row, {alpha});
      for (Path path : {Path::forward, Path::deferred})
        recs.push_back({path, content, alpha, chosen_configuration(decide_on(table, at_alpha, path, content, false, baseline))});
    }
  }
  return recs;
}

}  // namespace

std::vector<AlphaRecommendation> recommend_by_alpha(const measure::TradeTable& table) {
  return decide_by_alpha(
      table, contents_of(table),
      [&](Content content) {
        const RowFilter keep = [content](const measure::TradeRow& row) { return !row.taa && content_of(row.scene) == content; };
        return measured_rows(table, keep, content_name(content));
      },
      "none");
}

std::vector<AlphaRecommendation> recommend_taa_by_alpha(const measure::TradeTable& table) {
  return decide_by_alpha(
      table, {std::begin(kContents), std::end(kContents)}, [&](Content content) { return measured_taa_rows(table, content); }, "none+taa");
}

const Recommendation* find_recommendation(const std::vector<Recommendation>& recs, Path path, Content content) {
  for (const Recommendation& rec : recs)
    if (rec.path == path && rec.content == content) return &rec;
  return nullptr;
}

std::vector<EngineSwitch> engine_switches(const measure::TradeTable& table, const CostTable* costs) {
  std::vector<EngineSwitch> switches;
  for (Content content : contents_of(table)) {
    const RowFilter keep = [content](const measure::TradeRow& row) { return !row.taa && content_of(row.scene) == content; };
    const std::vector<ContentRow> rows = measured_rows(table, keep, content_name(content));
    for (const ContentRow& engine : rows) {
      if (!is_engine_configuration(engine.configuration)) continue;
      // saagen's decision with the engine's form as the baseline: what beats it, at no more cost.
      std::vector<decision::Candidate> candidates;
      for (const ContentRow& row : rows)
        if (is_saagen_configuration(row.configuration))
          candidates.push_back(
              {row.configuration, comparison_against(row, engine), 1.0, costs_at_most(costs, row.configuration, engine.configuration)});
      const decision::Decision made = decision::decide(candidates, {});
      EngineSwitch entry{engine.configuration, content, "", mean_metrics(table, engine.configuration, keep), {}};
      if (made.chosen) {
        entry.configuration = candidates[*made.chosen].configuration;
        entry.saagen_metrics = mean_metrics(table, entry.configuration, keep);
      }
      switches.push_back(entry);
    }
  }
  return switches;
}

std::vector<SceneVerdict> scene_verdicts(const measure::TradeTable& table, const std::vector<Recommendation>& recs) {
  std::vector<SceneVerdict> verdicts;
  for (measure::SceneId scene : table.config.scenes) {
    const RowFilter on_scene = [scene](const measure::TradeRow& row) { return row.scene == scene; };
    for (Path path : {Path::forward, Path::deferred}) {
      const Recommendation* rec = find_recommendation(recs, path, content_of(scene));
      if (!rec) continue;
      SceneVerdict verdict{scene, path, rec->configuration, mean_metrics(table, rec->configuration, on_scene), {}, {}};
      for (const std::string& id : configurations(table)) {
        if (id != "none" && !is_engine_configuration(id)) continue;
        const Metrics base = mean_metrics(table, id, on_scene);
        if (!base.cases) continue;
        verdict.baselines.emplace_back(id, base);
        for (const VerdictMetric& metric : kVerdictMetrics)
          if (verdict.recommended.*metric.value > base.*metric.value)
            verdict.losses.push_back({id, metric.name, verdict.recommended.*metric.value, base.*metric.value});
      }
      verdicts.push_back(std::move(verdict));
    }
  }
  return verdicts;
}

std::string describe(const Loss& loss) { return fmt::format("{}: {} {:.4g} > {:.4g}", loss.baseline, loss.metric, loss.ours, loss.theirs); }

namespace {

// The engine with the lowest mean `value` on a content type ("" when the table has no engine).
std::pair<std::string, Metrics> best_engine(const measure::TradeTable& table, Content content, double Metrics::*value) {
  std::pair<std::string, Metrics> best;
  for (const std::string& id : configurations_of(table, content)) {
    if (!is_engine_configuration(id)) continue;
    const Metrics m = mean_metrics(table, id, content_filter(content));
    if (best.first.empty() || m.*value < best.second.*value) best = {id, m};
  }
  return best;
}

}  // namespace

std::vector<Verdict> verdicts(const measure::TradeTable& table, const std::vector<Recommendation>& recs) {
  const std::vector<SceneVerdict> per_scene = scene_verdicts(table, recs);
  std::vector<Verdict> out;
  for (const Recommendation& rec : recs) {
    Verdict v;
    v.recommendation = rec;
    v.none = mean_metrics(table, "none", content_filter(rec.content));
    std::tie(v.best_engine_image, v.engine_image) = best_engine(table, rec.content, &Metrics::image_error);
    v.video = has_video_metric(table);
    std::tie(v.best_engine_motion, v.engine_motion) =
        best_engine(table, rec.content, v.video ? &Metrics::video_error : &Metrics::flicker_error);
    for (const VerdictMetric& metric : kVerdictMetrics) {
      const double ours = rec.metrics.*metric.value;
      if (v.none.cases && ours > v.none.*metric.value) v.losses.push_back({"none", metric.name, ours, v.none.*metric.value});
      const auto [engine, engine_metrics] = best_engine(table, rec.content, metric.value);
      if (!engine.empty() && ours > engine_metrics.*metric.value)
        v.losses.push_back({engine, metric.name, ours, engine_metrics.*metric.value});
    }
    for (const SceneVerdict& scene : per_scene)
      if (scene.path == rec.path && content_of(scene.scene) == rec.content && !scene.losses.empty())
        v.scene_losses.emplace_back(scene.scene, scene.losses);
    out.push_back(std::move(v));
  }
  return out;
}

namespace {

// The usable candidates with a known cost, each marked when no other is both cheaper and lower in
// image error (the mean of the comparison with no SAA; no SAA itself is the point (1, 0)).
std::vector<TradePoint> candidate_points(const MaterialDecision& made) {
  std::vector<TradePoint> points;
  for (std::size_t i = 0; i < made.candidates.size(); ++i) {
    const decision::Candidate& c = made.candidates[i];
    if (c.usable && c.cost_ratio) points.push_back({c.configuration, *c.cost_ratio, c.against_none, made.decision.outcomes[i]});
  }
  std::sort(points.begin(), points.end(), [](const TradePoint& a, const TradePoint& b) {
    return std::tie(a.cost, a.against_none.image.mean) < std::tie(b.cost, b.against_none.image.mean);
  });
  double best_image = 0.0;  // no SAA's, at cost 1: a frontier point must do better than it
  for (TradePoint& point : points) {
    if (point.against_none.image.mean >= best_image) continue;
    point.frontier = true;
    best_image = point.against_none.image.mean;
  }
  return points;
}

// The engines' shipped forms, at deferred-sum's cost (the convention of configuration_cost).
std::vector<TradePoint> engine_points(const MaterialDecision& made, const std::vector<ContentRow>& rows) {
  const auto sum = std::find_if(made.candidates.begin(), made.candidates.end(),
                                [](const decision::Candidate& c) { return c.configuration == "deferred-sum"; });
  if (sum == made.candidates.end() || !sum->cost_ratio) return {};
  std::vector<TradePoint> points;
  for (const ContentRow& row : rows)
    if (is_engine_configuration(row.configuration) && row.against_none) {
      TradePoint point{row.configuration, *sum->cost_ratio, *row.against_none, decision::outcome(*row.against_none)};
      point.engine = true;
      points.push_back(std::move(point));
    }
  return points;
}

std::string budget_choice(const measure::TradeTable& table, const ContentTrade& trade, std::optional<double> budget) {
  Material material = reference_material(trade.path == Path::forward ? RenderPath::forward : RenderPath::deferred, trade.content);
  material.budget = budget;
  return chosen_configuration(decide_material(Catalogue::builtin(), material, kDefaultGpuFamily, trade.rows, measured_transported(table),
                                              "no SAA", table.decision_timing.get()));
}

}  // namespace

std::vector<ContentTrade> content_trades(const measure::TradeTable& table) {
  std::vector<ContentTrade> trades;
  for (Content content : contents_of(table)) {
    const RowFilter keep = [content](const measure::TradeRow& row) { return !row.taa && content_of(row.scene) == content; };
    const std::vector<ContentRow> rows = measured_rows(table, keep, content_name(content));
    for (Path path : {Path::forward, Path::deferred}) {
      ContentTrade trade{content, path, {}, "", decide_on(table, rows, path, content), rows, decision_cost_axis(table)};
      trade.points = candidate_points(trade.made);
      for (TradePoint& engine : engine_points(trade.made, rows)) trade.points.push_back(std::move(engine));
      trade.chosen = chosen_configuration(trade.made);
      trades.push_back(std::move(trade));
    }
  }
  return trades;
}

std::string format_frontier(const measure::TradeTable& table) {
  std::string text = fmt::format(
      "\nThe trade per content and render path: the frontier (no configuration is both cheaper and lower in image error), "
      "cost = {}, image / video error (10 - JOD) against no SAA with 95 % intervals:\n",
      decision_cost_words(table));
  for (const ContentTrade& trade : content_trades(table)) {
    text += fmt::format("  {}, {}:\n    {:<44} {:>5}  {:<34} {:<34} {}\n", path_name(trade.path), content_name(trade.content),
                        "configuration", "cost", "image error", "video error (10 - JOD)", "against no SAA");
    text += fmt::format("    {:<44} {:>5.3f}\n", "none", 1.0);
    for (const TradePoint& point : trade.points)
      if (point.frontier)
        text += fmt::format("    {:<44} {:>5.3f}  {:<34} {:<34} {}\n", point.configuration, point.cost,
                            decision::describe(point.against_none.image), decision::describe(point.against_none.temporal),
                            decision::name(point.outcome));
    text += fmt::format("    at x{} (the papers' overhead): {}; at x1.25: {}; unlimited: {}\n", kPapersBudget,
                        budget_choice(table, trade, kPapersBudget), budget_choice(table, trade, 1.25),
                        budget_choice(table, trade, std::nullopt));
  }
  return text;
}

}  // namespace saagen::report

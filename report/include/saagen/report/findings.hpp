// What the trade table says: per content type and render path, saagen's decision (decide_on below:
// saagen/decision.hpp through the planner's decide_material, so the bench's verdict and `saagen
// plan` give one answer): the configuration that beats no SAA with the largest image gain, or
// none; per engine, the best saagen configuration at equal or lower cost;
// per scene, whether the recommendation beats no SAA and every engine's shipped form. The advice
// of `saagen bench`, `saagen report` and the planner comes from here.
//
// Display-referred criteria (what a viewer sees):
//   image    mean LDR-FLIP of the tonemapped frame-0 images (ties: tonemapped RMSE);
//   motion   mean temporal difference error (TDE, image.hpp) of the display-value animation:
//            how far the frame-to-frame changes are from the converged animation's (0: as the
//            ground truth). It counts both excess flicker (aliasing) and lost motion (a highlight
//            blurred away), where the old temporal-std ratio rewarded the latter.
// A configuration "beats" another on a metric when its value is lower.
#pragma once

#include "saagen/advice.hpp"
#include "saagen/decision.hpp"
#include "saagen/measure/trade.hpp"
#include "saagen/report/cost_table.hpp"
#include "saagen/scene/planner.hpp"

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen::report {

// The content types advice is given for, each a set of scenes every configuration is measured on:
//   curved         smooth geometry, the normal is the geometry's (sphere, torus, tubes, mesh);
//   normal-mapped  a tangent-space normal map texture with MIPs on curved geometry;
//   bump           analytic bump shading (the bump plane: normals with detail but no texture,
//                  hence no prefiltering);
//   clearcoat      the coat layer of a KHR_materials_clearcoat asset (its scene NAME-coat: the
//                  coat lobe alone, a second filtered lobe); the asset's base lobe is classified
//                  as any scene (normal-mapped where it has normal textures).
// The planner's content types (saagen/advice.hpp), one enum for the manifest, the planner and the
// bench.
using Content = advice::Content;
inline constexpr Content kContents[] = {Content::curved, Content::normal_mapped, Content::bumps, Content::clearcoat};
// As a trade table's by_content rows name it: "curved", "normal-mapped", "bump", "clearcoat".
inline constexpr std::string_view content_name(Content content) { return advice::table_content(content); }
Content content_of(measure::SceneId scene);

// Means over a set of trade rows (no Fresnel rows: they differ by a dim factor only): the scalar
// metrics (max_error the largest) and the verdict's metrics (their intervals' means).
struct Metrics : measure::RowMetrics, measure::VerdictMetrics<double> {
  std::size_t cases = 0;
};
// Whether the table's rows carry the video metric (TradeConfig::video_metric), which the verdict
// then reads as its temporal metric (comparison.hpp, temporal_metric).
bool has_video_metric(const measure::TradeTable& table);
// What the verdict's temporal metric is for this table, as the printed verdict and the JSON's
// "temporal_metric" name it: the video error where the table has the video metric, else the
// flicker error.
std::string temporal_metric_description(const measure::TradeTable& table);
// The metrics of one trade row (cases = 1).
Metrics row_metrics(const measure::TradeRow& row);

using RowFilter = std::function<bool(const measure::TradeRow&)>;
// Means of one configuration (measure::configuration_id) over the non-Fresnel rows `keep` accepts.
Metrics mean_metrics(const measure::TradeTable& table, const std::string& configuration, const RowFilter& keep);
// The configurations of a table in row order.
std::vector<std::string> configurations(const measure::TradeTable& table);

enum class Path { forward, deferred };
std::string_view path_name(Path path);
// Whether a configuration belongs to a path: forward-* and deferred-* by name; none and the
// engines to both.
bool serves(const std::string& configuration, Path path);
bool is_engine_configuration(const std::string& configuration);
// Rows of the exact filtered GGX ("VARIANT/exact", saagen bench --exact-lobe): a yardstick that no
// target emits, never recommended nor written to the planner's per-content table.
bool is_measurement_configuration(const std::string& configuration);

// The cost of a configuration, lavapipe time ratio (time) or optimized SPIR-V delta; nullopt when
// the cost table does not have it. The feed changes inputs, not code; engines cost what
// deferred-sum costs (see findings.cpp).
std::optional<double> configuration_cost(const CostTable* costs, const std::string& configuration, bool time);
// The ISA inverse-throughput ratio of a configuration (VariantCost::isa_ratio), same conventions.
std::optional<double> configuration_isa_cost(const CostTable* costs, const std::string& configuration);
// Whether a's cost is at most b's (the ISA ratio when both have one, within kIsaTieTolerance;
// else the SPIR-V delta, else the time ratio; true when none is known, and the caller says so).
bool costs_at_most(const CostTable* costs, const std::string& a, const std::string& b);

// The measured rows of a set of trade rows, one per configuration: the means the trade's JSON
// writes ("by_content") and saagen's decision reads (through comparison_against,
// saagen/scene/cost_tables.hpp). `scope` names the content type or the scene; each row is paired
// against the rows' `baseline` (its against_none; none+taa for measured_taa_rows), and where it
// beats the baseline over the rows, the scenes among them on which it loses (its loses_on); each
// row that may be recommended (beats, on time, loses on no scene) is paired with the others that
// may, and names those it is worse than beyond the interval in neither metric (its not_worse_than).
std::vector<ContentRow> measured_rows(const measure::TradeTable& table, const RowFilter& keep, std::string_view scope,
                                      const std::string& baseline = "none");

// Under TAA (`saagen bench --taa`): a content type's +taa rows, named as the configurations a
// material under TAA uses (without "+taa"; none+taa is "none"), each paired against none+taa:
// what `saagen plan` decides on with taa = true (the JSON's "taa_by_content").
std::vector<ContentRow> measured_taa_rows(const measure::TradeTable& table, Content content);
// A +taa configuration's id without "+taa" ("deferred-avg:geometric+hdrp+taa/tail" ->
// "deferred-avg:geometric+hdrp/tail"; "none+taa" -> "none").
std::string without_taa(std::string configuration);

// saagen's decision (saagen/decision.hpp, through the planner's decide_material) on measured rows
// for a path's reference material of a content type (reference_material): what `saagen plan`
// gives such a material with this table.
// `baseline` names what the rows' comparisons are against ("none+taa" for measured_taa_rows).
// The candidates are costed as `table` says (decision_cost_words): by its decision_timing, a GPU's,
// where that was taken at one light, else by the committed ISA model.
MaterialDecision decide_on(const measure::TradeTable& table, const std::vector<ContentRow>& rows, Path path, Content content,
                           bool speed = false, std::string_view baseline = "no SAA");
// What the decisions' costs are, as a plot's axis names them: "vega10 ISA ratio to no SAA", or
// "NVIDIA H200 GPU time ratio to no SAA at 1 light"; decision_cost_words adds the timing's file.
std::string decision_cost_axis(const measure::TradeTable& table);
std::string decision_cost_words(const measure::TradeTable& table);

// The configuration a decision chose, "none" for no filter.
std::string chosen_configuration(const MaterialDecision& made);

// The trade as a user reads it, per content type and render path: the frontier, the usable
// configurations no other beats in both cost (the decisions' cost: decision_cost_words) and image
// error against no SAA (the decision's comparison, its mean), with each one's comparison and
// outcome; then saagen's decision at three budgets: the papers' overhead (x1.05, Tokuyoshi &
// Kaplanyan 2019 Table 2), x1.25 and unlimited.
inline constexpr double kPapersBudget = 1.05;
std::string format_frontier(const measure::TradeTable& table);

// One configuration on the trade's picture of a content type and render path.
struct TradePoint {
  std::string configuration;
  double cost = 1.0;                  // the decision's cost ratio to no SAA (decision_cost_words)
  decision::Comparison against_none;  // image / temporal error minus no SAA's, 95 % intervals
  decision::Outcome outcome = decision::Outcome::ties;
  bool frontier = false;  // no usable configuration is both cheaper and lower in image error
  bool engine = false;    // an engine's shipped form, at deferred-sum's cost (configuration_cost)
};
struct ContentTrade {
  Content content = Content::curved;
  Path path = Path::forward;
  std::vector<TradePoint> points;  // the usable configurations with a known cost, then the engines
  std::string chosen;              // saagen's decision ("none": no filter)
  MaterialDecision made;           // the decision the points come from (decide_on)
  std::vector<ContentRow> rows;    // what it decided on
  std::string cost_axis;           // what `cost` is (decision_cost_axis)
};
// Per content type of the table and render path: what format_frontier prints and the report plots.
std::vector<ContentTrade> content_trades(const measure::TradeTable& table);

struct Recommendation {
  Path path = Path::deferred;
  Content content = Content::curved;
  std::string configuration;  // "none": no filter (nothing beats no SAA on the content)
  Metrics metrics;
  std::string reason;  // the decision's
  // The same decision for prefer = "speed" (the cheapest that beats no SAA, never the most
  // expensive form): configuration ("none": no filter) and reason.
  std::string speed_configuration;
  std::string speed_reason;
};
// Per path and content type present in the table: saagen's decision on that content's means
// (decide_on): the configuration that beats no SAA with the largest image improvement, or none.
std::vector<Recommendation> recommend(const measure::TradeTable& table);
// The GGX alphas the table measured, ascending and each once (what a row's loses_at cells range over).
std::vector<double> measured_alphas(const measure::TradeTable& table);

// The same decision for a material of one roughness: per path, content type and measured alpha,
// on the content's rows with the cells (a scene at one alpha) each loses on at that alpha counted
// as losses (add_cell_losses), as `saagen plan` decides for a material whose `roughness` is
// sqrt(alpha). configuration "none": no filter.
struct AlphaRecommendation {
  Path path = Path::deferred;
  Content content = Content::curved;
  double alpha = 0.0;
  std::string configuration;
};
std::vector<AlphaRecommendation> recommend_by_alpha(const measure::TradeTable& table);
// The same under TAA: the +taa rows against none+taa (measured_taa_rows), what `saagen plan` gives a
// material with taa = true and a roughness.
std::vector<AlphaRecommendation> recommend_taa_by_alpha(const measure::TradeTable& table);

const Recommendation* find_recommendation(const std::vector<Recommendation>& recs, Path path, Content content);

struct EngineSwitch {
  std::string engine;
  Content content = Content::curved;
  std::string configuration;  // what beats the engine's form at equal or lower cost; empty: nothing does
  Metrics engine_metrics;
  Metrics saagen_metrics;
};
// Per engine and content type: saagen's decision (saagen/decision.hpp) with the engine's form as
// the baseline, among the saagen configurations (either path) whose cost is at most the engine's:
// the one that beats the engine's form (decision::decide: the largest temporal gain, the video
// error where measured); empty where none does.
std::vector<EngineSwitch> engine_switches(const measure::TradeTable& table, const CostTable* costs);

// The metrics a verdict compares, in the order they are reported: LDR-FLIP, TDE, HDR-FLIP,
// tonemapped RMSE (all lower-is-better).
struct VerdictMetric {
  const char* name;
  double Metrics::*value;
};
inline constexpr VerdictMetric kVerdictMetrics[] = {{"LDR-FLIP", &Metrics::flip_ldr},
                                                    {"TDE", &Metrics::tde},
                                                    {"HDR-FLIP", &Metrics::flip_hdr},
                                                    {"tonemapped RMSE", &Metrics::rmse_tonemapped}};

// A metric on which the recommendation is worse than a baseline.
struct Loss {
  std::string baseline;  // "none" or an engine configuration
  std::string metric;    // a kVerdictMetrics name
  double ours = 0.0;
  double theirs = 0.0;
};
std::string describe(const Loss& loss);  // "engine-filament: LDR-FLIP 0.0312 > 0.0305"

struct SceneVerdict {
  measure::SceneId scene = measure::SceneId::sphere;
  Path path = Path::deferred;
  std::string configuration;                               // the recommendation for its content
  Metrics recommended;                                     // over the scene's alphas
  std::vector<std::pair<std::string, Metrics>> baselines;  // none and every engine
  std::vector<Loss> losses;                                // one per baseline and lost metric
};
// Per scene and path: the recommendation against no SAA and every engine, on every
// kVerdictMetrics metric.
std::vector<SceneVerdict> scene_verdicts(const measure::TradeTable& table, const std::vector<Recommendation>& recs);

// The short verdict per render path and content type: the recommendation against no SAA and the
// best engine form on that content (the lowest mean of each metric over the engines), and every
// place it loses: content means (losses) and single scenes (scene_losses, from scene_verdicts).
struct Verdict {
  Recommendation recommendation;
  Metrics none;
  std::string best_engine_image;  // the engine with the lowest mean image error ("" without engines)
  Metrics engine_image;
  std::string best_engine_motion;  // the engine with the lowest mean temporal error (video error, else flicker error)
  Metrics engine_motion;
  std::vector<Loss> losses;                                                  // against none and, per metric, that metric's best engine
  std::vector<std::pair<measure::SceneId, std::vector<Loss>>> scene_losses;  // scenes with losses only
  bool video = false;                                                        // the temporal metric is the video error (has_video_metric)
};
std::vector<Verdict> verdicts(const measure::TradeTable& table, const std::vector<Recommendation>& recs);

}  // namespace saagen::report

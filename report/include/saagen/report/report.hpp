// The speed/accuracy trade report: the ground-truth trade table of saagen::render
// joined with the measured cost of each variant (bench_shading --json: lavapipe time ratio and
// optimized SPIR-V instruction delta), printed for the terminal (`saagen bench`) and written as a
// self-contained report (`saagen report -o DIR`: index.html, report.md, PNG sheets, an SVG plot).
#pragma once

#include "saagen/io/output.hpp"
#include "saagen/reference/render/trade.hpp"
#include "saagen/report/comparison.hpp"
#include "saagen/report/cost_table.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen::report {

// Means over the table's scenes and alphas, without Fresnel (with Fresnel the radiance is ~25x
// dimmer and the orderings are the same).
// Means over the cases (scenes x alphas, no Fresnel) of one configuration: a variant, or a
// variant fed the geometric normal ("deferred-avg:geometric"), or an engine's shipped form.
struct VariantSummary {
  std::string variant;  // render::configuration_id
  double rmse_linear = 0.0;
  double rmse_tonemapped = 0.0;
  double max_error = 0.0;  // the largest over the cases
  double tde = 0.0;        // temporal difference error (trade.hpp) and its two parts
  double tde_excess_flicker = 0.0;
  double tde_lost_motion = 0.0;
  double flicker = 0.0;
  double flicker_display = 0.0;  // secondary: tonemapped temporal std relative to the ground truth's
  double flip_ldr = 0.0;
  double flip_hdr = 0.0;
  std::size_t cases = 0;
};

std::vector<VariantSummary> summarize(const render::TradeTable& table);

// The preset configurations: "full" (256 x 256, 1024 spp, 32 flicker frames, every scene, alpha
// and Fresnel mode) and "quick" (64 x 64, 64 spp, 4 frames; for smoke tests).
render::TradeConfig preset_config(std::string_view preset);

// The medium and full presets' scenes of content nobody here authored (render/assets.hpp:
// ClearCoatTest and its coat, 2CylinderEngine, three @pmndrs/assets normal maps on the sphere):
// registers them and appends them to config.scenes, then size_preset_assets; nothing for the
// quick preset. Error (one line: the scene, the missing file, what to install) when a package
// is missing, before anything is loaded.
void add_preset_assets(std::string_view preset, render::TradeConfig& config);
// The sizes the preset measures its asset scenes at (TradeConfig::scene_sizes), for those in
// config.scenes: the medium preset 64 x 64, the full preset 128 x 128 (a quarter of the preset's
// pixels, so that six more scenes keep the presets' run times), the animation never below
// 64 x 64 (the sanity suite's floor), both at the preset's samples per pixel (docs/GLTF_SCENES.md).
void size_preset_assets(std::string_view preset, render::TradeConfig& config);

// Terminal table: one row per variant (means), with the cost columns when known.
std::string format_summary(const std::vector<VariantSummary>& summary, const CostTable* costs);

// The findings (findings.hpp) as terminal tables: recommendation per path and content, engine
// switches, per-scene verdicts.
std::string format_findings(const render::TradeTable& table, const CostTable* costs);

// The short verdict (findings.hpp, verdicts()): per render path and content type, what to use,
// how much it beats no SAA and the best engine form in LDR-FLIP and TDE, and where it loses.
// Printed last by `saagen bench` and `saagen report`, and at the top of the report.
std::string format_verdict(const render::TradeTable& table);

// Rows in the format bench_shading --json uses, each carrying "error" (mean LDR-FLIP),
// so that `saagen plan --trade-table` can choose by accuracy; plus the full trade rows.
// An interval as the JSON outputs write it ({mean, low, high}), and a paired difference's: the
// interval with the ground truth's part of it and its reading (better / tie / worse).
nlohmann::json interval_json(const render::Interval& interval);
nlohmann::json difference_json(const MetricDifference& difference);

nlohmann::json trade_json(const render::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs);

// Under TAA (TradeConfig::taa): the table without its +taa rows, which the summaries, findings,
// verdicts and trade_json read (their flip_ldr is the animation's, not frame 0's at the main
// resolution); per scene, the comparison under TAA (taa_comparisons) as a terminal table (empty
// without +taa rows); and every row's figures, for trade_json's "taa_cases".
render::TradeTable without_taa_rows(const render::TradeTable& table);
std::string format_taa_summary(const render::TradeTable& table);
nlohmann::json taa_cases_json(const render::TradeTable& table);
// Under TAA, per content type (findings.hpp, measured_taa_rows): every configuration's means and
// its pairing with none+taa in by_content's form, the JSON's "taa_by_content" that `saagen plan
// --trade-table` reads with taa = true; and saagen's decision on them per path, the JSON's
// decisions.taa_by_content.
nlohmann::json taa_by_content_json(const render::TradeTable& table);
nlohmann::json taa_decisions_json(const render::TradeTable& table);

// The per-scene comparison under TAA behind format_taa_summary and the report's "with TAA"
// section, read with the verdict's metrics and decision (comparison.hpp, saagen/decision.hpp):
// rows "no TAA" (none), "TAA" (none+taa), "saagen" (the configuration the decision takes among
// saagen's under TAA, any feed, prefilter or lobe, against none+taa; absent when none beats it)
// and "engine" (each engine form under TAA); each with its own figures (means over the scene's
// alphas without Fresnel, with 95 % intervals) and its paired comparison against none+taa.
struct TaaComparisonRow {
  std::string label;
  std::string configuration;                    // render::configuration_id
  render::Interval image_error;                 // LDR-FLIP per frame of the animation
  std::optional<render::Interval> video_error;  // 10 - ColorVideoVDP's JOD; nullopt without the video metric
  double tde = 0.0;                             // the older temporal figure, for comparison with older tables
  std::optional<PairedComparison> against_taa;  // against none+taa; nullopt on none+taa's own row
};
struct TaaComparison {
  render::SceneId scene = render::SceneId::sphere;
  std::vector<TaaComparisonRow> rows;
  std::string best_saagen;  // the decision's choice under TAA ("" when none beats none+taa)
  std::string best_engine;  // the engine form under TAA with the lowest temporal error ("" when the table has none)
  std::string verdict;      // the decision's reason
};
std::vector<TaaComparison> taa_comparisons(const render::TradeTable& table);
// A row's columns as the terminal table and the report print them, and their headers.
std::vector<std::string> taa_headers();
std::vector<std::string> taa_columns(const TaaComparisonRow& row);
// What the comparison's figures are (frames, warm-up, resolution, ground truth), for captions.
std::string taa_note(const render::TradeTable& table);

// Writes DIR/index.html, DIR/report.md, DIR/trade_<content>_<path>.svg (plots.hpp), DIR/sheet_<scene>_<alpha>.png
// (the ground truth beside every variant's 1-spp image, over false-colour difference maps) and
// DIR/strip_<scene>.png (the ground truth, no SAA, the best engine form and the recommendations
// at the alpha where no SAA errs most; the report opens with these and the verdict).
// The table must have been computed with keep_images. Returns the image files written.
// Written all or nothing through saagen's output layer (saagen/io/output.hpp): files saagen did not
// write are kept unless `force`.
// With `taa` (the table with its +taa rows and taa_images, TradeConfig::taa and keep_images), a
// "With TAA" section: the per-scene comparison (taa_comparisons) and DIR/taa_<scene>.png, a crop
// of the animation's last frame: the ground truth, none+taa, the best saagen configuration under
// TAA and the best engine form under TAA, at the alpha where none+taa errs most.
std::vector<std::string> write_report(const render::TradeTable& table, const CostTable* costs, const std::filesystem::path& dir,
                                      bool force = false, const render::TradeTable* taa = nullptr);
// The files write_report writes (to write them in one commit with a run's other outputs) and the
// image files among them.
struct ReportFiles {
  std::vector<OutputFile> outputs;
  std::vector<std::string> images;
};
ReportFiles report_files(const render::TradeTable& table, const CostTable* costs, const std::filesystem::path& dir,
                         const render::TradeTable* taa = nullptr);
// The paths write_report will write for a configuration, to check them before rendering.
std::vector<std::filesystem::path> report_paths(const render::TradeConfig& config, const std::filesystem::path& dir);

// A progress callback drawing a one-line bar on stderr ("\r[#####.....]  42%  ground truth sphere");
// when stderr is not a terminal, one line per stage instead ("[ 42%] ground truth sphere").
render::TradeProgressFn progress_bar();

// PNG bytes of 8-bit pixels (1: grey, 3: RGB) carrying saagen's output tag (io/output.hpp) with
// `what` after it, so that the output layer recognises the file as saagen's.
std::string encode_tagged_png(int width, int height, int channels, const std::vector<std::uint8_t>& pixels, std::string_view what);

}  // namespace saagen::report

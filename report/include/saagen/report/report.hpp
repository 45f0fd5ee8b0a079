// The speed/accuracy trade report: the ground-truth trade table of saagen::measure joined with the
// measured cost of each variant (bench_shading --json: lavapipe time ratio and optimized SPIR-V
// instruction delta), written as a self-contained directory (`saagen report -o DIR`: index.html,
// report.md, PNG sheets and strips, SVG plots).
//
// The report's other outputs have headers of their own, included here for the callers that use
// the whole report: summary.hpp (the per-configuration means and the config line), presets.hpp
// (`saagen bench --preset`), terminal.hpp (what `saagen bench` prints), trade_json.hpp (its
// --json), taa_summary.hpp (the trade under TAA), progress.hpp (the progress bar), png.hpp
// (saagen's tagged PNGs) and cost_table.hpp (the measured costs).
#pragma once

#include "saagen/io/output.hpp"
#include "saagen/measure/trade.hpp"
#include "saagen/report/comparison.hpp"
#include "saagen/report/cost_table.hpp"
#include "saagen/report/png.hpp"
#include "saagen/report/presets.hpp"
#include "saagen/report/progress.hpp"
#include "saagen/report/summary.hpp"
#include "saagen/report/taa_summary.hpp"
#include "saagen/report/terminal.hpp"
#include "saagen/report/trade_json.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace saagen::report {

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
std::vector<std::string> write_report(const measure::TradeTable& table, const CostTable* costs, const std::filesystem::path& dir,
                                      bool force = false, const measure::TradeTable* taa = nullptr);
// The files write_report writes (to write them in one commit with a run's other outputs) and the
// image files among them.
struct ReportFiles {
  std::vector<OutputFile> outputs;
  std::vector<std::string> images;
};
ReportFiles report_files(const measure::TradeTable& table, const CostTable* costs, const std::filesystem::path& dir,
                         const measure::TradeTable* taa = nullptr);
// The paths write_report will write for a configuration, to check them before rendering.
std::vector<std::filesystem::path> report_paths(const measure::TradeConfig& config, const std::filesystem::path& dir);

}  // namespace saagen::report

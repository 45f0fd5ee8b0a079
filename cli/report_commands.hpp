// The trade-off commands of the CLI: `saagen bench` prints the speed/accuracy table,
// `saagen report -o DIR` writes it as a self-contained report. Kept apart from main.cpp, which
// only registers and dispatches them.
#pragma once

#include <CLI/CLI.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace saagen::measure {
struct TradeConfig;
}

namespace saagen::cli {

// The trade table of one glTF asset, measured as `saagen bench --preset medium --scene ASSET
// --json` would (ground truths cached in cache_dir when not empty), in the JSON `saagen plan
// --trade-table` reads: what `saagen plan --gltf ASSET --measure` plans with. Progress to stderr.
std::string measure_asset_table(const std::string& asset, const std::string& cache_dir);

class ReportCommands {
 public:
  explicit ReportCommands(CLI::App& app);

  bool bench_requested() const { return bench_->parsed(); }
  bool report_requested() const { return report_->parsed(); }

  int run_bench() const;
  int run_report() const;

  struct Common {
    std::string preset = "full";
    std::string cost_json;  // bench_shading --json output
    std::string cache_dir;
    int threads = 0;
    // What the trade measures, when not the defaults: the kernel's sigma^2 and kappa, and the
    // scale of the prefiltered texture term.
    std::optional<double> sigma2, kappa;
    double prefilter_scale = 1.0;
    double prefilter_lod_bias = 1.0;  // measure::TradeConfig::prefilter_lod_bias
    bool force = false;
    // The +taa rows (TradeConfig::taa) and the resolve's options when not the defaults.
    bool taa = false;
    std::optional<double> taa_blend, taa_clip_gamma;
    std::optional<int> taa_sequence;
    bool taa_unweighted = false;  // resolve in linear radiance (no inverse-luminance weighting)
    // The animation's camera pan per frame, (right, up) pixels at its resolution, when not the
    // preset's (TradeConfig::pan_pixels_per_frame).
    std::vector<double> pan;
    // GPU families whose ISA statistics (Mesa's ACO on RADV null hardware) give the cost column:
    // "vega10,navi21"; the first family's figures rank the variants.
    std::string isa_families;
    // The scenes to measure instead of the preset's: standard scene names or glTF 2.0 assets
    // (.gltf / .glb paths), and the main resolution instead of the preset's (the animation's
    // at half of it).
    std::vector<std::string> scenes;
    int resolution = 0;
    // What plain ddx/ddy mean in the emulated 2x2 quads the filters read ("" : the preset's).
    std::string derivatives;
    // The frame the forward filters difference their half vectors in ("" : each pixel's tangent frame).
    std::string half_vector_frame;
    // Also measure the exact filtered GGX (Lobe::exact, rows VARIANT/exact): a measuring instrument.
    bool exact_lobe = false;
    // Every ground truth's strata per axis times this (its samples times its square): for
    // scenes whose sub-pixel highlights the preset's ground truth has not converged on.
    int truth_samples_scale = 1;
  };

 private:
  static void add_common(CLI::App* command, Common& common);
  // run_bench's parts: the flags that contradict each other, and the files the run writes.
  void check_bench_flags() const;
  std::vector<std::filesystem::path> bench_outputs(const measure::TradeConfig& config) const;

  CLI::App* bench_ = nullptr;
  Common bench_common_;
  std::string bench_json_;
  bool bench_every_case_ = false;
  bool bench_isa_only_ = false;            // the ISA tables only, no ground-truth rendering
  std::string bench_isa_table_;            // write the ISA statistics as JSON (the planner's table format)
  std::string bench_frames_;               // also write the animation clips behind every row
  std::string bench_frames_filter_ = ".";  // the clips (configuration ids, sanity:NAME) written
  std::string bench_report_;               // also write the report of the same table (as `report -o`)

  CLI::App* report_ = nullptr;
  Common report_common_;
  std::string report_directory_;
};

}  // namespace saagen::cli

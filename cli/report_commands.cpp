#include "report_commands.hpp"

#include "arguments.hpp"

#include "saagen/error.hpp"
#include "saagen/io/output.hpp"
#include "saagen/measure/assets.hpp"
#include "saagen/measure/gltf.hpp"
#include "saagen/report/findings.hpp"
#include "saagen/report/frames.hpp"
#include "saagen/report/report.hpp"
#include "saagen/report/sanity.hpp"
#ifdef SAAGEN_HAVE_ISA_COST
#include "saagen/report/isa_cost.hpp"
#endif

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace saagen::cli {
namespace {

std::optional<report::CostTable> load_costs(const std::string& path) {
  if (path.empty()) return std::nullopt;
  return report::load_cost_table(path);
}

// A cache that cannot be written would cache nothing, silently (e.g. /proc/self): the directory,
// or its nearest existing ancestor when it is still to be created, must take a new file. Probed
// by creating (and removing) one, which also holds for root, whom access() always answers yes.
void check_cache_writable(const std::string& cache_dir) {
  std::filesystem::path existing = std::filesystem::absolute(cache_dir);
  std::error_code error;
  while (!std::filesystem::exists(existing, error) && existing.has_parent_path() && existing.parent_path() != existing) {
    existing = existing.parent_path();
  }
  std::string probe = (existing / ".saagen-cache-probe-XXXXXX").string();
  const int fd = ::mkostemp(probe.data(), O_CLOEXEC);
  if (fd < 0) {
    throw Error(fmt::format("--cache {}: cannot write in {} ({}); pass a writable directory for the ground-truth cache", cache_dir,
                            existing.string(), std::generic_category().message(errno)));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

// A preset asset's scenes by the scene's name (measure/assets.hpp); empty for another name.
std::vector<measure::SceneId> preset_asset_scenes(const std::string& name) {
  try {
    return measure::register_preset_asset(name);
  } catch (const std::exception& error) {  // AssetMissing, GltfError, AssetError
    throw Error(fmt::format("--scene {}: {}", name, error.what()));
  }
}

// The scenes of --scene: a standard scene's name, a preset asset's scene name (ClearCoatTest,
// 2CylinderEngine, pmndrs-0014, ...), or a glTF 2.0 asset (loaded and registered,
// with its coat lobe's scene NAME-coat after it when it has clearcoat; a bad asset is one line
// naming the file and what is wrong, before anything renders).
std::vector<measure::SceneId> scene_ids(const std::vector<std::string>& names) {
  std::vector<measure::SceneId> ids;
  for (const std::string& name : names) {
    std::vector<measure::SceneId> found;
    if (const auto standard = measure::scene_from_name(name); standard && !measure::registered_scene(*standard)) {
      found.push_back(*standard);
    } else if (std::vector<measure::SceneId> asset = preset_asset_scenes(name); !asset.empty()) {
      found = std::move(asset);
    } else {
      const std::string extension = std::filesystem::path(name).extension().string();
      if (extension != ".gltf" && extension != ".glb" && extension != ".GLTF" && extension != ".GLB") {
        std::string known;
        for (measure::SceneId s : measure::all_scenes())
          known += std::string(known.empty() ? "" : ", ") + std::string(measure::scene_name(s));
        for (measure::SceneId s : measure::content_scenes()) known += ", " + std::string(measure::scene_name(s));
        for (const measure::PresetAsset& asset : measure::preset_assets()) known += ", " + asset.scene;
        throw Error(fmt::format("--scene {}: neither a scene ({}) nor a glTF 2.0 asset (.gltf or .glb)", name, known));
      }
      try {
        found = measure::register_gltf_scenes(name);
      } catch (const measure::GltfError& error) {
        throw Error(fmt::format("--scene {}", error.what()));
      }
    }
    for (measure::SceneId id : found)
      if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  }
  return ids;
}

// What each glTF scene of a run is made of (counts, materials, camera and light), for stdout.
std::string asset_summaries(const measure::TradeConfig& config) {
  std::string text;
  std::vector<const measure::GltfAsset*> printed;
  for (measure::SceneId id : config.scenes) {
    const auto asset = measure::gltf_asset_of(id);
    if (!asset || std::find(printed.begin(), printed.end(), asset.get()) != printed.end()) continue;
    printed.push_back(asset.get());
    text += asset->summary();
  }
  return text;
}

// How the ground truths were had: printed, not written into the table or the report, whose bytes
// must not change from one run of the same measurement to the next.
std::string ground_truth_line(const measure::TradeTable& table) {
  return fmt::format("ground truths: {} rendered in {:.1f} s, {} read from the cache\n", table.cache_misses, table.ground_truth_seconds,
                     table.cache_hits);
}

// Every file a run reads, which no output may be (compared by identity, not even with --force):
// the cost table, each glTF scene's files (the asset, its buffers and images) and the files in
// the ground-truth cache.
std::vector<std::filesystem::path> run_inputs(const ReportCommands::Common& common, const measure::TradeConfig& config) {
  std::vector<std::filesystem::path> inputs;
  if (!common.cost_json.empty()) inputs.emplace_back(common.cost_json);
  for (measure::SceneId id : config.scenes)
    if (const auto asset = measure::gltf_asset_of(id))
      for (const std::string& file : asset->files) inputs.emplace_back(file);
  if (!common.cache_dir.empty()) {
    std::error_code error;
    for (std::filesystem::directory_iterator entry(common.cache_dir, error), end; !error && entry != end; entry.increment(error))
      if (entry->is_regular_file(error)) inputs.push_back(entry->path());
  }
  return inputs;
}

// The ground-truth cache is written through the output layer: a temporary created exclusively
// beside the file, removed by a signal that ends the process (Ctrl-C, a file-size limit) or a
// failed write; a cache that cannot be written is only slower.
void write_cache_through_output_layer() {
  measure::set_ground_truth_cache_writer([](const std::filesystem::path& path, const std::string& bytes) {
    // A FIFO or device planted at the cache's own name goes (the output layer writes over no
    // special file); a link is replaced itself, never followed.
    std::error_code error;
    const auto status = std::filesystem::symlink_status(path, error);
    if (!error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) && !std::filesystem::is_symlink(status) &&
        !std::filesystem::is_directory(status))
      std::filesystem::remove(path, error);
    try {
      write_outputs({{path, bytes}}, /*force=*/true);  // the cache's own file names
    } catch (const Error&) {
    }
  });
}

// The trade table of a run. A degenerate measurement (a black or non-finite ground truth, a
// metric that is not finite) is an error naming the scene, not a verdict.
measure::TradeTable measure_trade(const measure::TradeConfig& config, const measure::AnimationFrameFn& on_frame = {}) {
  const measure::TradeTable table = [&] {
    try {
      return measure::compute_trade_table(config, report::progress_bar(), on_frame);
    } catch (const measure::TradeError& error) {
      throw Error(error.what());
    }
  }();
  for (const measure::TradeRow& row : table.rows) {
    const std::pair<const char*, double> metrics[] = {{"linear RMSE", row.rmse_linear},
                                                      {"display RMSE", row.rmse_tonemapped},
                                                      {"LDR-FLIP", row.flip_ldr},
                                                      {"HDR-FLIP", row.flip_hdr},
                                                      {"TDE", row.tde}};
    for (const auto& [metric, value] : metrics) {
      if (!std::isfinite(value)) {
        throw Error(fmt::format("scene {}: the {} of {} at alpha {} is {}; a measurement that is not finite gives no verdict",
                                measure::scene_name(row.scene), metric, measure::configuration_id(row), row.alpha, value));
      }
    }
  }
  return table;
}

// The GPU families of --isa, checked before anything is loaded or measured.
void check_isa_families(const std::string& families) {
#ifdef SAAGEN_HAVE_ISA_COST
  if (!families.empty()) report::parse_isa_families(families);
#else
  if (!families.empty()) {
    throw Error(
        fmt::format("--isa {}: this saagen was built without the Vulkan harness (SAAGEN_BUILD_HARNESS=OFF); rebuild with it", families));
  }
#endif
}

// --truth-samples-scale: every ground truth (main image and animation, the scenes' own sizes
// included) with `scale` times the strata per axis, scale^2 times the samples.
void scale_ground_truth_samples(int scale, measure::TradeConfig& config) {
  config.strata *= scale;
  config.flicker_strata *= scale;
  for (measure::TradeSceneSize& size : config.scene_sizes) {
    size.strata *= scale;
    size.flicker_strata *= scale;
  }
}

// The configuration of a run, its options checked before any rendering.
measure::TradeConfig configure(const ReportCommands::Common& common, bool keep_images) {
  if (common.threads < 0) throw Error(fmt::format("--threads {}: must be 0 (all cores) or a positive count", common.threads));
  if (!common.cache_dir.empty()) {
    std::error_code error;
    if (std::filesystem::exists(common.cache_dir, error) && !std::filesystem::is_directory(common.cache_dir, error)) {
      throw Error(fmt::format("--cache {}: exists and is not a directory; pass a directory for the ground-truth cache", common.cache_dir));
    }
    check_cache_writable(common.cache_dir);
    write_cache_through_output_layer();
  }
  measure::TradeConfig config = report::preset_config(common.preset);
  if (!common.scenes.empty()) {
    config.scenes = scene_ids(common.scenes);
    report::size_preset_assets(common.preset, config);
  } else {
    report::add_preset_assets(common.preset, config);
  }
  if (common.resolution > 0) {
    config.width = config.height = common.resolution;
    config.flicker_width = config.flicker_height = std::max(2, common.resolution / 2);
    // Every scene at --resolution, each keeping its ground truths' samples: the presets raise them
    // for the asset and glTF scenes, whose highlights a smaller image makes no larger.
    for (measure::TradeSceneSize& size : config.scene_sizes) {
      size.width = size.height = config.width;
      size.flicker_width = size.flicker_height = config.flicker_width;
    }
  }
  config.cache_dir = common.cache_dir;
  config.threads = common.threads;
  config.keep_images = keep_images;
  if (common.sigma2) config.params.sigma2 = *common.sigma2;
  if (common.kappa) config.params.kappa = *common.kappa;
  config.prefilter_scale = common.prefilter_scale;
  config.prefilter_lod_bias = common.prefilter_lod_bias;
  config.taa = common.taa;
  if (common.taa_blend) config.taa_options.blend = *common.taa_blend;
  if (common.taa_clip_gamma) config.taa_options.clip_gamma = *common.taa_clip_gamma;
  if (common.taa_sequence) config.taa_options.sequence_length = *common.taa_sequence;
  config.taa_options.luma_weighting = !common.taa_unweighted;
  if ((common.taa_blend || common.taa_clip_gamma || common.taa_sequence || common.taa_unweighted) && !common.taa)
    throw Error("--taa-blend, --taa-clip-gamma, --taa-sequence and --taa-unweighted set the TAA resolve: add --taa");
  if (!common.pan.empty()) config.pan_pixels_per_frame = {common.pan[0], common.pan[1]};
  if (!common.derivatives.empty()) config.derivative = common.derivatives == "fine" ? ref::Derivative::fine : ref::Derivative::coarse;
  if (common.half_vector_frame == "tangent") config.half_vector_frame = measure::HalfVectorFrame::tangent;
  if (common.exact_lobe) config.lobes.push_back(measure::Lobe::exact);
  scale_ground_truth_samples(common.truth_samples_scale, config);
  return config;
}

// The ISA statistics of `families` ("" measures nothing), printed as tables to `out`, and their
// table given to `costs`, whose first family's ratios are the primary cost column (cost_table.hpp).
std::optional<nlohmann::json> measure_isa(const std::string& families, std::optional<report::CostTable>& costs, std::ostream& out) {
  if (families.empty()) return std::nullopt;
#ifdef SAAGEN_HAVE_ISA_COST
  const std::vector<std::string> parsed = report::parse_isa_families(families);
  IsaTable table;
  try {
    table = report::measure_isa_costs(parsed, [](const std::string& step) { std::cerr << step << "\n"; });
  } catch (const Error&) {
    throw;
  } catch (const std::exception& error) {
    throw Error(fmt::format("--isa {}: {}", families, error.what()));
  }
  out << report::format_isa_table(table);
  if (!costs) costs.emplace();
  costs->isa = table;
  costs->isa_family = parsed.front();
  return report::isa_json(table);
#else
  (void)costs;
  (void)out;
  throw Error(
      fmt::format("--isa {}: this saagen was built without the Vulkan harness (SAAGEN_BUILD_HARNESS=OFF); rebuild with it", families));
#endif
}

// CLI::Range lets NaN through (every comparison with NaN is false), and a NaN sigma^2 renders every
// row alike with exit 0: a finite number in [low, high], nothing else.
CLI::Validator finite_range(double low, double high) {
  const std::string range = fmt::format("[{}, {}]", low, high);
  return CLI::Validator(
      [low, high, range](std::string& text) {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        const bool whole = !text.empty() && end == text.c_str() + text.size();
        if (!whole || !std::isfinite(value) || value < low || value > high) return fmt::format("not a finite number in {}", range);
        return std::string();
      },
      "FINITE in " + range);
}

}  // namespace

std::string measure_asset_table(const std::string& asset, const std::string& cache_dir) {
  ReportCommands::Common common;
  common.preset = "medium";
  common.scenes = {asset};
  common.cache_dir = cache_dir;
  const measure::TradeConfig config = configure(common, false);
  std::cerr << asset_summaries(config);
  const measure::TradeTable table = report::without_taa_rows(measure_trade(config));
  nlohmann::json json = report::trade_json(table, report::summarize(table), nullptr);
  json["sanity_checks"] = report::sanity_json(report::check_sanity(table));
  return json.dump();
}

namespace {

// The run: the preset, the cost tables, the cache and the threads.
void add_run_options(CLI::App* command, ReportCommands::Common& common) {
  command
      ->add_option(
          "--preset", common.preset,
          "full (256 px, 1024 spp, 32 frames, 7 scenes x 6 alphas x Fresnel), medium (128 px, 256 spp, 16 frames, no Fresnel) or quick")
      ->capture_default_str();
  command
      ->add_option(
          "--cost", common.cost_json,
          "Cost measured by `bench_shading --json FILE`: a GPU's time ratios at one light cost the verdict's decisions (else vega10's ISA model "
          "does); lavapipe's are a column only")
      ->check(value_given());
  command->add_option("--cache", common.cache_dir, "Directory caching ground-truth images between runs")->check(value_given());
  command->add_option("--threads", common.threads, "Render threads (0: all cores)")->check(value_given())->capture_default_str();
}

// What is measured of the filters: the kernel, the prefilter and the ISA cost model.
void add_filter_options(CLI::App* command, ReportCommands::Common& common) {
  command->add_option("--sigma2", common.sigma2, "Pixel-filter variance of the SAA kernel to measure (default 0.25)")
      ->check(finite_range(1e-6, 16.0));
  command->add_option("--kappa", common.kappa, "Kernel clamp to measure (default 0.18)")->check(finite_range(1e-6, 1.0));
  command->add_option("--prefilter-scale", common.prefilter_scale, "Scale of the prefiltered normal-map roughness to measure")
      ->check(finite_range(0.0, 4.0))
      ->capture_default_str();
  command
      ->add_option("--prefilter-lod-bias", common.prefilter_lod_bias,
                   "Levels by which the prefiltered rows (+hdrp, ...) sample the normal map and its bake coarser (0: the implicit LOD)")
      ->check(finite_range(0.0, 4.0))
      ->capture_default_str();
  command->add_option("--isa", common.isa_families,
                      "GPU families (comma-separated: vega10, navi21, navi10, polaris10) whose ISA statistics from Mesa's ACO "
                      "compiler (RADV null hardware, no GPU needed) give the cost column; the first family ranks the variants");
}

// The measurement under TAA (--taa) and its resolve.
void add_taa_options(CLI::App* command, ReportCommands::Common& common) {
  command->add_flag("--taa", common.taa,
                    "Also measure every configuration under TAA (rows CONFIGURATION+taa: Halton jitter, exact reprojection, "
                    "variance clipping; the animation's frames after a warm-up of one jitter cycle)");
  command->add_option("--taa-blend", common.taa_blend, "With --taa: the current frame's weight in the history (default 0.1)")
      ->check(finite_range(1e-3, 1.0));
  command
      ->add_option("--taa-clip-gamma", common.taa_clip_gamma,
                   "With --taa: the variance clipping box half-width in standard deviations (default 1)")
      ->check(finite_range(1e-3, 1e6));
  command->add_option("--taa-sequence", common.taa_sequence, "With --taa: Halton (2, 3) jitter positions per cycle (default 8)")
      ->check(CLI::Range(1, 256));
  command->add_flag("--taa-unweighted", common.taa_unweighted,
                    "With --taa: resolve in linear radiance instead of Karis's inverse-luminance weighting (x / (1 + x)), which "
                    "converges below a sub-pixel highlight's mean");
}

// The scenes, the animation and the ground truths.
void add_scene_options(CLI::App* command, ReportCommands::Common& common) {
  command
      ->add_option("--pan", common.pan,
                   "RIGHT,UP: the animation's camera pan per frame in pixels at its resolution instead of the preset's (0.11,0.37: "
                   "0.39 px per frame); e.g. 0.03,0.1 moves highlights slowly, 0.22,0.74 at 0.77 px per frame")
      ->expected(2)
      ->delimiter(',')
      ->check(finite_range(-8.0, 8.0));
  command->add_option("--scene", common.scenes,
                      "Measure these scenes instead of the preset's: a scene's name (sphere, torus-knot, ...; pmndrs-NNNN: that "
                      "@pmndrs/assets normal map on the sphere, pmndrs-NNNN-lodK: at implicit LOD K in 64 px images) or a glTF 2.0 asset "
                      "(.gltf or .glb: its meshes, normal and roughness textures, first camera or a view framed from its bounds, "
                      "KHR_lights_punctual light or a directional one); repeatable");
  command->add_option("--resolution", common.resolution, "Main image size in pixels instead of the preset's (the animation at half of it)")
      ->check(CLI::Range(4, 4096));
  command
      ->add_option("--derivatives", common.derivatives,
                   "What the filters' screen-space derivatives are: coarse (one difference per 2x2 quad, the default) or fine "
                   "(the difference within the pixel's own row and column: dFdxFine, ddx_fine, dpdxFine)")
      ->check(CLI::IsMember({"coarse", "fine"}));
  command
      ->add_option("--half-vector-frame", common.half_vector_frame,
                   "The frame the projected forward filters difference their half vectors in: transported (their "
                   "*_transported_fragment wrappers: world-space derivatives read in the pixel's frame without its turn about the "
                   "normal, so a tangent frame that twists from pixel to pixel adds nothing to the kernel; the default, which "
                   "saagen's plans call) or tangent (each quad pixel's own tangent frame, as the papers' listing: their "
                   "*_fragment wrappers)")
      ->check(CLI::IsMember({"tangent", "transported"}));
  command
      ->add_option("--truth-samples-scale", common.truth_samples_scale,
                   "Every ground truth with this many times the strata per axis (its square times the samples; e.g. 2: the medium "
                   "preset's glTF scenes at 16384 spp instead of 4096): where the sanity suite finds comparisons that have not "
                   "converged (a standing against no SAA that reverses once the bias of the ground truth's samples is taken out; "
                   "the verdict reads them as ties)")
      ->check(CLI::Range(1, 8));
  command->add_flag("--exact-lobe", common.exact_lobe,
                    "Also evaluate every filter's kernel with the exact filtered GGX (GGX convolved with the kernel by quadrature; rows "
                    "VARIANT/exact): what a closed-form lobe could reach. A measurement, not a BRDF saagen emits");
}

}  // namespace

void ReportCommands::add_common(CLI::App* command, Common& common) {
  add_run_options(command, common);
  add_filter_options(command, common);
  command->add_flag("--force", common.force, "Overwrite output files that saagen did not write");
  add_taa_options(command, common);
  add_scene_options(command, common);
}

namespace {

// The --frames directory: new, or empty (saagen writes many files into it; it never mixes them
// with a user's).
std::filesystem::path frames_directory(const std::string& directory, bool force) {
  std::error_code ec;
  const std::filesystem::path path(directory);
  if (directory.empty()) throw Error("--frames: the directory name is empty");
  if (std::filesystem::exists(path, ec) && !(std::filesystem::is_directory(path, ec) && std::filesystem::is_empty(path, ec)) && !force)
    throw Error(fmt::format("--frames {}: exists and is not an empty directory; name a new directory (or pass --force to write into it)",
                            directory));
  return path;
}

std::regex frames_filter(const std::string& pattern) {
  try {
    return std::regex(pattern, std::regex::ECMAScript);
  } catch (const std::regex_error& bad) {
    throw Error(fmt::format("--frames-filter '{}': not a regular expression ({})", pattern, bad.what()));
  }
}

}  // namespace

ReportCommands::ReportCommands(CLI::App& app) {
  bench_ = app.add_subcommand("bench", "Render the ground truths and print the speed/accuracy trade table of every variant");
  add_common(bench_, bench_common_);
  bench_->add_option("--json", bench_json_, "Also write the table as JSON (the format `saagen plan --trade-table` reads)")
      ->check(value_given());
  bench_
      ->add_option("--report", bench_report_,
                   "Also write the report of the same table into this directory, as `saagen report -o DIR` would (one "
                   "measurement for both)")
      ->check(value_given());
  bench_
      ->add_option("--frames", bench_frames_,
                   "Also write the animation clips behind every row into this new directory (DIR/index.json and one PNG per "
                   "clip, its frames stacked, in the display values the verdict reads), for an external video metric")
      ->check(value_given());
  bench_->add_option("--frames-filter", bench_frames_filter_,
                     "With --frames: only the clips whose configuration id (or sanity:NAME) matches this regular expression "
                     "(ECMAScript; e.g. '^(none|engine-.*|.*/tail|sanity:.*)$'); the ground truth's always");
  bench_->add_flag("--every-case", bench_every_case_, "Print every scene x alpha x Fresnel x variant row, not only the means");
  bench_->add_flag("--isa-only", bench_isa_only_, "With --isa: print the ISA statistics only (no ground-truth rendering)");
  bench_
      ->add_option("--isa-table", bench_isa_table_,
                   "With --isa: also write the ISA statistics as JSON (generator/data/isa_cost.json, the planner's table, is this "
                   "file for --isa vega10,navi21)")
      ->check(value_given());

  report_ =
      app.add_subcommand("report", "Write the trade report: index.html, report.md, PNG sheets, a cost-error plot per content and path");
  add_common(report_, report_common_);
  report_->add_option("--output,-o", report_directory_, "Report directory")->required();
}

void ReportCommands::check_bench_flags() const {
  if ((bench_isa_only_ || !bench_isa_table_.empty()) && bench_common_.isa_families.empty()) {
    throw Error("--isa-only and --isa-table need --isa FAMILY[,FAMILY] (e.g. --isa vega10,navi21)");
  }
  if (bench_isa_only_ && !bench_json_.empty()) {
    throw Error(fmt::format(
        "--json {}: --isa-only computes no trade table to write; drop --isa-only, or write the ISA statistics with --isa-table FILE",
        bench_json_));
  }
  if (bench_isa_only_ && !bench_report_.empty()) {
    throw Error(fmt::format("--report {}: --isa-only computes no trade table to report; drop --isa-only", bench_report_));
  }
  check_isa_families(bench_common_.isa_families);
}

// Every output together (never one file twice): the JSON, the ISA table and the report's files.
std::vector<std::filesystem::path> ReportCommands::bench_outputs(const measure::TradeConfig& config) const {
  std::vector<std::filesystem::path> outputs;
  if (!bench_json_.empty()) outputs.emplace_back(bench_json_);
  if (!bench_isa_table_.empty()) outputs.emplace_back(bench_isa_table_);
  if (!bench_report_.empty())
    for (const std::filesystem::path& path : report::report_paths(config, bench_report_)) outputs.push_back(path);
  return outputs;
}

namespace {

// The trade table's JSON (`plan --trade-table` reads it), with the rows and comparisons under TAA
// when measured, and the sanity suite's checks.
nlohmann::json bench_json(const measure::TradeTable& measured, const measure::TradeTable& table,
                          const std::vector<report::VariantSummary>& summary, const report::CostTable* cost_table,
                          const std::vector<report::SceneSanity>& sanity) {
  nlohmann::json json = report::trade_json(table, summary, cost_table);
  if (measured.config.taa) {
    json["taa_cases"] = report::taa_cases_json(measured);
    json["taa_by_content"] = report::taa_by_content_json(measured);
    json["decisions"]["taa_by_content"] = report::taa_decisions_json(measured);
    for (nlohmann::json& comparison : report::taa_comparisons_json(measured)) json["comparisons"].push_back(std::move(comparison));
  }
  json["sanity_checks"] = report::sanity_json(sanity);
  return json;
}

// The sanity suite, first: the instrument before anything it ranks (report/sanity.hpp).
void print_sanity(const std::vector<report::SceneSanity>& sanity) {
  if (sanity.empty()) return;
  std::cout << "\nSanity suite (results whose ranking is known; image error: LDR-FLIP per frame, video error: 10 - ColorVideoVDP's "
               "JOD of the clip; docs/TEMPORAL.md):\n"
            << report::format_sanity(sanity);
}

// The means, findings, frontier and (measured under TAA) the TAA summary of a table.
void print_tables(const measure::TradeTable& measured, const measure::TradeTable& table, const std::vector<report::VariantSummary>& summary,
                  const report::CostTable* cost_table, bool every_case) {
  if (every_case) std::cout << measure::format_trade_table(measured) << "\n";
  std::cout << report::format_summary(summary, cost_table);
  std::cout << fmt::format("(means over {} scenes x {} alphas without Fresnel; errors against the {}; cost: {})\n",
                           table.config.scenes.size(), table.config.alphas.size(), report::ground_truth_samples(table.config),
                           cost_table ? cost_table->describe() : std::string("none (pass --isa FAMILY and/or --cost FILE)"));
  std::cout << report::format_findings(table, cost_table);
  std::cout << report::format_frontier(table);
  if (measured.config.taa) std::cout << "\n" << report::format_taa_summary(measured);
}

}  // namespace

int ReportCommands::run_bench() const {
  // Inputs and outputs are checked first: a bad file or path fails before rendering.
  check_bench_flags();
  auto costs = load_costs(bench_common_.cost_json);
  const measure::TradeConfig config = configure(bench_common_, !bench_report_.empty());
  // Never over an input.
  check_output_paths(bench_outputs(config), bench_common_.force, run_inputs(bench_common_, config));
  const auto isa = measure_isa(bench_common_.isa_families, costs, std::cout);
  // Every output of the run is written in one commit, after every input has been read.
  std::vector<OutputFile> files;
  if (isa && !bench_isa_table_.empty()) files.push_back({bench_isa_table_, isa->dump(2) + "\n"});
  if (bench_isa_only_) {
    if (!files.empty()) write_outputs(files, bench_common_.force, run_inputs(bench_common_, config));
    return 0;
  }
  std::optional<report::ClipWriter> clips;
  if (!bench_frames_.empty()) clips.emplace(frames_directory(bench_frames_, bench_common_.force), frames_filter(bench_frames_filter_));
  std::cout << asset_summaries(config);
  measure::AnimationFrameFn on_frame;
  if (clips) on_frame = [&](const measure::AnimationFrame& frame) { clips->add(frame, config.frames); };
  measure::TradeTable measured = measure_trade(config, on_frame);
  if (costs) measured.decision_timing = costs->decision_timing();
  std::cout << ground_truth_line(measured);
  const std::vector<report::SceneSanity> sanity = report::check_sanity(measured);
  print_sanity(sanity);
  // The +taa rows have their own comparison (format_taa_summary): the summaries read frame 0.
  const measure::TradeTable table = report::without_taa_rows(measured);
  const auto summary = report::summarize(table);
  const report::CostTable* cost_table = costs ? &*costs : nullptr;
  print_tables(measured, table, summary, cost_table, bench_every_case_);
  if (!bench_json_.empty()) files.push_back({bench_json_, bench_json(measured, table, summary, cost_table, sanity).dump(2) + "\n"});
  std::size_t clip_files = 0;
  if (clips) {
    const std::vector<OutputFile> clip_outputs = clips->outputs();
    clip_files = clip_outputs.size() - 1;
    files.insert(files.end(), clip_outputs.begin(), clip_outputs.end());
  }
  std::optional<report::ReportFiles> report_output;
  if (!bench_report_.empty()) {
    report_output = report::report_files(table, cost_table, bench_report_, config.taa ? &measured : nullptr);
    files.insert(files.end(), report_output->outputs.begin(), report_output->outputs.end());
  }
  if (!files.empty()) write_outputs(files, bench_common_.force, run_inputs(bench_common_, config));
  if (report_output)
    std::cout << fmt::format("\nwrote {}/index.html, report.md and {} images\n", bench_report_, report_output->images.size());
  if (clips) std::cout << fmt::format("\nwrote {} animation clips and {}/index.json\n", clip_files, bench_frames_);
  // Last, what a reader needs first: what to use, by how much, and where it loses.
  std::cout << "\n" << report::format_verdict(table);
  // and where the ground truth cannot support it.
  if (const std::string unconverged = report::format_unconverged(sanity); !unconverged.empty()) std::cout << "\n" << unconverged;
  return 0;
}

int ReportCommands::run_report() const {
  check_output_named("--output", report_directory_);
  check_isa_families(report_common_.isa_families);
  auto costs = load_costs(report_common_.cost_json);
  const measure::TradeConfig config = configure(report_common_, true);
  check_output_paths(report::report_paths(config, report_directory_), report_common_.force, run_inputs(report_common_, config));
  measure_isa(report_common_.isa_families, costs, std::cerr);
  std::cout << asset_summaries(config);
  measure::TradeTable measured = measure_trade(config);
  if (costs) measured.decision_timing = costs->decision_timing();
  std::cout << ground_truth_line(measured);
  const measure::TradeTable table = report::without_taa_rows(measured);
  const report::ReportFiles files =
      report::report_files(table, costs ? &*costs : nullptr, report_directory_, config.taa ? &measured : nullptr);
  write_outputs(files.outputs, report_common_.force, run_inputs(report_common_, config));
  std::cout << fmt::format("wrote {}/index.html, report.md and {} images\n\n", report_directory_, files.images.size());
  if (config.taa) std::cout << report::format_taa_summary(measured) << "\n";
  std::cout << report::format_verdict(table);
  return 0;
}

}  // namespace saagen::cli

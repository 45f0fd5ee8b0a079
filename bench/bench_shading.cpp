// Measured shading cost of every SAA variant: one fragment kernel per
// variant and target shades a bumpy sphere with the GGX specular term, filtered through the
// variant's fragment wrapper, and is timed against the same shading without SAA in the same run.
//
//   build-bench/bench/bench_shading [--device NAME] [--quick] [--size N|WxH] [--lights N]
//                                   [--repetitions N] [--csv FILE] [--json FILE]
//
// Per target (glsl, hlsl) it prints: variant | median ms | median no-SAA ms of the rounds
// interleaved with it | ratio variant / no SAA (median of the per-round ratios, with quartiles) |
// ratio of the fastest rounds | optimized SPIR-V instructions of the variant shader minus the
// no-SAA shader's | mean per-pixel change and change of the mean of the shaded value | the
// paper's Table 2 ratios. Forward anisotropic variants shade with the matrix GGX BRDF, the others
// (and no SAA) with the axis-aligned one, so their cost includes the matrix BRDF's. --lights N
// shades N lights (shading_scene.hpp: a forward form filters and shades per light, a deferred form
// computes its roughness once per pixel), each ratio against no SAA with the same N lights.
//
// It exits non-zero with one line on stderr when a shader fails to compile or validate, when a
// shaded value on the sphere is non-finite or negative, or when a variant leaves the image
// (almost) unchanged, which would mean the filter is not wired in and the timings are meaningless.
#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/report/shading_scene.hpp"
#include "saagen/scene/cost_tables.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/compiler.hpp"
#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <saagen/harness/harness.hpp>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace {

namespace hx = saagen::harness;

// A failure that ends the bench with one line.
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using saagen::report::baseline_shading;
using saagen::report::body_with;
using saagen::report::paper_no_saa_ms;
using saagen::report::parameter_buffer;
using saagen::report::scene_parameters;
using saagen::report::variant_cases;
using saagen::report::VariantCase;

// ---------------------------------------------------------------------------------------------
// Options

struct Options {
  std::uint32_t width = 1000;
  std::uint32_t height = 1000;
  std::uint32_t repetitions = 15;
  std::uint32_t warmup = 2;
  std::uint32_t lights = 1;
  bool quick = false;
  std::string csv_path;
  std::string json_path;
  std::string device;
};

std::uint32_t parse_count(const std::string& flag, const std::string& text, std::uint32_t low, std::uint32_t high) {
  std::size_t used = 0;
  unsigned long value = 0;
  try {
    value = std::stoul(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || value < low || value > high) {
    throw Failure(fmt::format("{} wants an integer in [{}, {}], got '{}'", flag, low, high, text));
  }
  return static_cast<std::uint32_t>(value);
}

// "--size N" is N x N; "--size WxH" (e.g. 3840x2160, the 4K frame) is W x H.
std::pair<std::uint32_t, std::uint32_t> parse_size(const std::string& text) {
  const std::size_t cross = text.find('x');
  if (cross == std::string::npos) {
    const std::uint32_t side = parse_count("--size", text, 16, 8192);
    return {side, side};
  }
  return {parse_count("--size", text.substr(0, cross), 16, 8192), parse_count("--size", text.substr(cross + 1), 16, 8192)};
}

Options parse_options(int argc, char** argv) {
  Options options;
  options.device = hx::take_device_flag(argc, argv);
  std::optional<std::pair<std::uint32_t, std::uint32_t>> size;
  std::optional<std::uint32_t> repetitions;
  for (int index = 1; index < argc; ++index) {
    const std::string argument = argv[index];
    const auto value = [&]() -> std::string {
      if (index + 1 >= argc) throw Failure(fmt::format("{} needs a value", argument));
      return argv[++index];
    };
    if (argument == "--quick") {
      options.quick = true;
    } else if (argument == "--csv") {
      options.csv_path = value();
    } else if (argument == "--json") {
      options.json_path = value();
    } else if (argument == "--size") {
      size = parse_size(value());
    } else if (argument == "--repetitions") {
      repetitions = parse_count(argument, value(), 1, 1000);
    } else if (argument == "--lights") {
      options.lights = parse_count(argument, value(), 1, saagen::report::kMaxSceneLights);
    } else if (argument == "--help" || argument == "-h") {
      std::printf(
          "usage: bench_shading [--device NAME] [--quick] [--size N|WxH] [--lights N] [--repetitions N] [--csv FILE] [--json FILE]\n"
          "  --quick          smoke run: 128x128 pixels, 3 repetitions\n"
          "  --size N|WxH     framebuffer N x N or W x H, e.g. 3840x2160 (even; default 1000)\n"
          "  --lights N       directional lights per pixel, 1 to 64 (default 1); ratios are to no SAA with as many\n"
          "  --repetitions N  timed rounds per variant (default 15), after two warm-up rounds\n"
          "  --csv FILE       the table as CSV; --json FILE the same as JSON\n");
      std::exit(0);
    } else {
      throw Failure(fmt::format("unknown argument '{}' (see --help)", argument));
    }
  }
  if (options.quick) {
    options.width = options.height = 128;
    options.repetitions = 3;
    options.warmup = 1;
  }
  if (size) std::tie(options.width, options.height) = *size;
  if (repetitions) options.repetitions = *repetitions;
  if (options.width % 2 != 0 || options.height % 2 != 0) {
    throw Failure(fmt::format("--size must be even in both directions, got {}x{}", options.width, options.height));
  }
  return options;
}

// ---------------------------------------------------------------------------------------------
// Shaders

struct Shader {
  std::vector<std::uint32_t> spirv;  // optimized (what is timed and counted)
  std::size_t instructions = 0;
};

std::string first_line(const std::string& text) {
  std::size_t start = text.find_first_not_of(" \n\r\t");
  if (start == std::string::npos) return "(no log)";
  std::string line = text.substr(start, text.find('\n', start) - start);
  return line;
}

Shader build_shader(const std::string& target, const std::string& what, const saagen::EmittedFile& primary, const std::string& content,
                    const std::string& body, std::uint32_t width) {
  saagen::KernelRequest request;
  request.kind = saagen::KernelKind::fragment;
  request.body = body;
  request.output_stride = 1;
  request.width = width;
  saagen::CompileRequest compile;
  compile.language = saagen::builtin_target(target).language;
  compile.stage = saagen::ShaderStage::fragment;
  compile.sources = saagen::kernel_sources(saagen::Catalogue::builtin(), primary.file_name, content, request);
  const saagen::CompileResult compiled = saagen::compile_to_spirv(compile);
  if (!compiled.ok) throw Failure(fmt::format("{} {}: shader failed to compile: {}", target, what, first_line(compiled.log)));
  Shader shader;
  shader.spirv = saagen::optimize_spirv(compiled.spirv, saagen::ClientApi::vulkan);
  if (shader.spirv.empty()) throw Failure(fmt::format("{} {}: spirv-opt failed", target, what));
  if (const std::string problem = saagen::validate_spirv(shader.spirv, saagen::ClientApi::vulkan); !problem.empty()) {
    throw Failure(fmt::format("{} {}: optimized SPIR-V does not validate: {}", target, what, first_line(problem)));
  }
  shader.instructions = saagen::count_spirv_instructions(shader.spirv);
  return shader;
}

// ---------------------------------------------------------------------------------------------
// Runs and checks

struct ImageStats {
  std::size_t on_sphere = 0;
  double mean = 0.0;
};

ImageStats check_image(const std::string& target, const std::string& what, const std::vector<float>& values) {
  ImageStats stats;
  double sum = 0.0;
  for (std::size_t index = 0; index < values.size(); ++index) {
    const float value = values[index];
    if (value == -1.0f) continue;  // off the sphere
    if (!std::isfinite(value) || value < 0.0f) {
      throw Failure(fmt::format("{} {}: shaded value {} at pixel {} on the sphere", target, what, value, index));
    }
    ++stats.on_sphere;
    sum += value;
  }
  const double coverage = static_cast<double>(stats.on_sphere) / static_cast<double>(values.size());
  if (coverage < 0.3 || coverage > 0.95) {
    throw Failure(fmt::format("{} {}: the sphere covers {:.1f}% of the frame (expected 30-95%): broken scene or output binding", target,
                              what, 100.0 * coverage));
  }
  stats.mean = sum / static_cast<double>(stats.on_sphere);
  if (!(stats.mean > 0.0)) throw Failure(fmt::format("{} {}: the shaded image is black", target, what));
  return stats;
}

class Kernel {
 public:
  Kernel(hx::VulkanContext& context, const Shader& shader, std::uint32_t width, std::uint32_t height, const std::vector<float>& input) {
    hx::FragmentRun run;
    run.fragment.spirv = shader.spirv;
    run.width = width;
    run.height = height;
    run.color_formats = {VK_FORMAT_R32_SFLOAT};
    run.buffers = {hx::input_buffer(0, input), hx::output_buffer<float>(1, static_cast<std::size_t>(width) * height)};
    program_ = std::make_unique<hx::FragmentProgram>(context, run);
  }

  // One submission; returns its time (GPU timestamps when available, else host wall clock).
  double run_once(bool timestamps) {
    last_ = program_->run({.repetitions = 1, .gpu_timestamps = timestamps});
    const auto& samples = timestamps ? last_.timing.gpu_ms : last_.timing.host_ms;
    if (samples.empty()) throw Failure("the harness returned no timing sample");
    return samples.front();
  }
  std::vector<float> output() const { return last_.buffer_as<float>(1); }

 private:
  std::unique_ptr<hx::FragmentProgram> program_;
  hx::RunResult last_;
};

double percentile(std::vector<double> samples, double p) {
  if (samples.empty()) return std::nan("");
  std::sort(samples.begin(), samples.end());
  const double position = p * static_cast<double>(samples.size() - 1);
  const std::size_t below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, samples.size() - 1);
  return samples[below] + (samples[above] - samples[below]) * (position - static_cast<double>(below));
}

struct Row {
  std::string target;
  std::string variant;
  double ms = 0.0;           // median of the variant's samples
  double baseline_ms = 0.0;  // median of the baseline samples interleaved with them
  double ratio = 1.0;        // median of the per-round ratios
  double ratio_p25 = 1.0;
  double ratio_p75 = 1.0;
  double ms_min = 0.0;
  double baseline_ms_min = 0.0;
  double ratio_of_minima = 1.0;  // min variant ms / min no-SAA ms: robust when noise only adds time
  std::size_t instructions = 0;
  long delta_instructions = 0;
  double mean_change = 0.0;   // (mean variant - mean baseline) / mean baseline, over the sphere
  double pixel_change = 0.0;  // mean |variant - baseline| per sphere pixel / mean baseline
  std::optional<std::array<double, 2>> paper_range;
  std::optional<double> paper_sponza;
};

std::string format_anchor(const Row& row) {
  if (!row.paper_range) return "-";
  return fmt::format("x{:.2f}-{:.2f} (Sponza x{:.2f})", (*row.paper_range)[0], (*row.paper_range)[1], *row.paper_sponza);
}

void print_table(const std::string& target, const std::vector<Row>& rows, const char* time_source) {
  fmt::print("\n{} ({} ms, median)\n", target, time_source);
  const std::string header = fmt::format("{:<41} {:>8} {:>9} {:>20} {:>9} {:>8} {:>8} {:>8}  {}", "variant", "ms", "no-SAA ms",
                                         "ratio (p25-p75)", "min ratio", "dSPIR-V", "|d| px", "mean d", "paper Table 2");
  fmt::print("{}\n{}\n", header, std::string(header.size() + 10, '-'));
  for (const Row& row : rows) {
    const bool baseline = row.variant == "no-saa";
    fmt::print("{:<41} {:>8.2f} {:>9} {:>20} {:>9} {:>8} {:>8} {:>8}  {}\n", row.variant, row.ms,
               baseline ? std::string("-") : fmt::format("{:.2f}", row.baseline_ms),
               baseline ? std::string("1.000") : fmt::format("{:.3f} ({:.3f}-{:.3f})", row.ratio, row.ratio_p25, row.ratio_p75),
               baseline ? std::string("1.000") : fmt::format("{:.3f}", row.ratio_of_minima),
               baseline ? fmt::format("({})", row.instructions) : fmt::format("{:+d}", row.delta_instructions),
               baseline ? std::string("-") : fmt::format("{:.1f}%", 100.0 * row.pixel_change),
               baseline ? std::string("-") : fmt::format("{:+.1f}%", 100.0 * row.mean_change),
               baseline ? std::string("x1.00") : format_anchor(row));
  }
}

void write_csv(const std::string& path, const std::vector<Row>& rows, const Options& options, const std::string& device,
               const char* time_source) {
  std::ofstream out(path);
  if (!out) throw Failure(fmt::format("cannot write {}", path));
  out << "target,variant,ms_median,baseline_ms_median,ratio_median,ratio_p25,ratio_p75,ms_min,baseline_ms_min,ratio_of_minima,spirv_instructions,"
         "delta_spirv_instructions,pixel_change,mean_change,paper_ratio_low,paper_ratio_high,paper_ratio_sponza,width,height,"
         "repetitions,time_source,device\n";
  for (const Row& row : rows) {
    const auto optional_number = [](const auto& value, auto get) { return value ? fmt::format("{:.4f}", get(*value)) : std::string(); };
    std::string quoted_device;
    for (const char character : device) {
      if (character == '"') quoted_device += '"';
      quoted_device += character;
    }
    out << fmt::format("{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{},{},{:.5f},{:.5f},{},{},{},{},{},{},{},\"{}\"\n",
                       row.target, row.variant, row.ms, row.baseline_ms, row.ratio, row.ratio_p25, row.ratio_p75, row.ms_min,
                       row.baseline_ms_min, row.ratio_of_minima, row.instructions, row.delta_instructions, row.pixel_change,
                       row.mean_change, optional_number(row.paper_range, [](const auto& r) { return r[0]; }),
                       optional_number(row.paper_range, [](const auto& r) { return r[1]; }),
                       optional_number(row.paper_sponza, [](double v) { return v; }), options.width, options.height, options.repetitions,
                       time_source, quoted_device);
  }
  if (!out) throw Failure(fmt::format("cannot write {}", path));
}

void write_json(const std::string& path, const std::vector<Row>& rows, const Options& options, const std::string& device,
                const char* time_source) {
  nlohmann::json document;
  document["device"] = device;
  document["width"] = options.width;
  document["height"] = options.height;
  document["repetitions"] = options.repetitions;
  document["lights"] = options.lights;
  document["time_source"] = time_source;
  document["cost_model"] = saagen::kTimeCostModel;
  document["alpha"] = std::sqrt(scene_parameters(2, 2).front().values.front());
  nlohmann::json entries = nlohmann::json::array();
  for (const Row& row : rows) {
    nlohmann::json entry = {{"device", device.substr(0, device.find(" ("))},  // the name, as MeasuredTradeTable::device_name
                            {"shader", "forward"},
                            {"target", row.target},
                            {"variant", row.variant},
                            {"lights", options.lights},
                            {"cost_ratio", row.ratio},
                            {"ms_median", row.ms},
                            {"baseline_ms_median", row.baseline_ms},
                            {"ratio_p25", row.ratio_p25},
                            {"ratio_p75", row.ratio_p75},
                            {"ms_min", row.ms_min},
                            {"baseline_ms_min", row.baseline_ms_min},
                            {"ratio_of_minima", row.ratio_of_minima},
                            {"spirv_instructions", row.instructions},
                            {"delta_spirv_instructions", row.delta_instructions},
                            {"pixel_change", row.pixel_change},
                            {"mean_change", row.mean_change}};
    if (row.paper_range) {
      entry["paper_ratio_low"] = (*row.paper_range)[0];
      entry["paper_ratio_high"] = (*row.paper_range)[1];
      entry["paper_ratio_sponza"] = *row.paper_sponza;
    }
    entries.push_back(entry);
  }
  document["rows"] = entries;
  std::ofstream out(path);
  if (!out) throw Failure(fmt::format("cannot write {}", path));
  out << document.dump(2) << "\n";
  if (!out) throw Failure(fmt::format("cannot write {}", path));
}

// Counts the pixels whose screen derivatives of a buffer-loaded value are wrong: non-zero on
// lavapipe (Mesa 22.3), whose helper invocations read 0 from storage buffers.
std::size_t probe_helper_loads(hx::VulkanContext& context, const saagen::EmittedFile& host_file, std::uint32_t width,
                               std::uint32_t height) {
  const std::string body =
      "    real v = SAAGEN_LOAD(0);\n"
      "    SAAGEN_STORE(0, abs(ddx_fine(v * saagen_frag_coord.x) - v) + abs(ddy_fine(v * saagen_frag_coord.y) - v));\n";
  const Shader shader = build_shader("glsl", "helper-load probe", host_file, host_file.content, body, width);
  Kernel probe(context, shader, width, height, {1.0f});
  probe.run_once(false);
  std::size_t wrong = 0;
  for (const float value : probe.output()) wrong += value > 1e-3f || !std::isfinite(value) ? 1 : 0;
  return wrong;
}

// Below this mean per-pixel change (relative to the mean no-SAA value) a variant counts as "did
// nothing". NDF filtering roughly preserves the mean, so the mean itself is no test. The kernel
// shrinks with the pixel (the sphere's bumps span more pixels at a larger size): at 1000 x 1000
// the tail variants change 8 - 16 % per pixel, at 3840 x 2160 forward-aniso-projected/tail 1.9 %
// (NVIDIA H200), so the bar sits an order of magnitude below that; a filter that is not wired in
// changes nothing.
constexpr double minimum_pixel_change = 0.002;

// Prints whether helper invocations load buffers on this device (the kernels' derivatives of
// loaded values depend on it).
void report_helper_loads(hx::VulkanContext& context, const saagen::Catalogue& catalogue, const Options& options) {
  saagen::EmitOptions emit;
  emit.variants = {"brdf-ggx"};
  const std::size_t wrong = probe_helper_loads(context, saagen::emit_variants(catalogue, emit).front(), options.width, options.height);
  if (wrong == 0) {
    fmt::print("helper invocations: buffer loads ok (derivatives of loaded values are exact on every pixel)\n");
  } else {
    fmt::print(
        "helper invocations: buffer loads read 0 on this device ({} of {} pixels would get wrong derivatives "
        "of loaded values); the kernels substitute the parameters' literal values in those lanes\n",
        wrong, static_cast<std::size_t>(options.width) * options.height);
  }
}

// The timed rounds of a variant and the baseline, interleaved ABBA after the warm-up rounds.
struct InterleavedSamples {
  std::vector<double> variant_ms, baseline_ms, ratios;
};

InterleavedSamples time_interleaved(Kernel& baseline, Kernel& kernel, const Options& options, bool timestamps) {
  InterleavedSamples samples;
  for (std::uint32_t round = 0; round < options.warmup + options.repetitions; ++round) {
    double base_ms = 0.0, variant_ms = 0.0;
    if (round % 2 == 0) {
      base_ms = baseline.run_once(timestamps);
      variant_ms = kernel.run_once(timestamps);
    } else {
      variant_ms = kernel.run_once(timestamps);
      base_ms = baseline.run_once(timestamps);
    }
    if (round < options.warmup) continue;
    samples.variant_ms.push_back(variant_ms);
    samples.baseline_ms.push_back(base_ms);
    samples.ratios.push_back(variant_ms / base_ms);
  }
  return samples;
}

// The no-SAA image a variant's is compared with, and its statistics.
struct BaselineImage {
  std::vector<float> pixels;
  ImageStats stats;
};

// A variant's image against no SAA's: its relative change per sphere pixel and of the mean. Throws
// where the sphere's coverage differs or the filter changes too little to be wired in.
std::pair<double, double> image_change(const std::string& target, const std::string& variant, const std::vector<float>& image,
                                       const BaselineImage& baseline) {
  const ImageStats stats = check_image(target, variant, image);
  if (stats.on_sphere != baseline.stats.on_sphere) {
    throw Failure(
        fmt::format("{} {}: {} sphere pixels, the no-SAA image has {}", target, variant, stats.on_sphere, baseline.stats.on_sphere));
  }
  double absolute_change = 0.0;
  for (std::size_t index = 0; index < image.size(); ++index) {
    if (baseline.pixels[index] != -1.0f) absolute_change += std::abs(static_cast<double>(image[index]) - baseline.pixels[index]);
  }
  const double pixel_change = absolute_change / static_cast<double>(stats.on_sphere) / baseline.stats.mean;
  const double mean_change = (stats.mean - baseline.stats.mean) / baseline.stats.mean;
  if (pixel_change < minimum_pixel_change) {
    throw Failure(fmt::format("{} {}: the image differs from no SAA by only {:.3f}% per pixel: the filter is not wired in", target, variant,
                              100.0 * pixel_change));
  }
  return {pixel_change, mean_change};
}

// The ratios of Tokuyoshi & Kaplanyan 2019's Table 2 for a variant the paper timed.
void set_paper_anchor(const VariantCase& variant, Row& row) {
  if (!variant.paper_ms) return;
  std::array<double, 3> ratios_in_paper{};
  for (std::size_t scene = 0; scene < 3; ++scene) ratios_in_paper[scene] = (*variant.paper_ms)[scene] / paper_no_saa_ms[scene];
  row.paper_range = std::array<double, 2>{*std::min_element(ratios_in_paper.begin(), ratios_in_paper.end()),
                                          *std::max_element(ratios_in_paper.begin(), ratios_in_paper.end())};
  row.paper_sponza = ratios_in_paper[0];
}

Row timed_row(const std::string& target, const std::string& variant, const InterleavedSamples& samples) {
  Row row;
  row.target = target;
  row.variant = variant;
  row.ms = percentile(samples.variant_ms, 0.5);
  row.baseline_ms = percentile(samples.baseline_ms, 0.5);
  row.ratio = percentile(samples.ratios, 0.5);
  row.ratio_p25 = percentile(samples.ratios, 0.25);
  row.ratio_p75 = percentile(samples.ratios, 0.75);
  row.ms_min = *std::min_element(samples.variant_ms.begin(), samples.variant_ms.end());
  row.baseline_ms_min = *std::min_element(samples.baseline_ms.begin(), samples.baseline_ms.end());
  row.ratio_of_minima = row.ms_min / row.baseline_ms_min;
  return row;
}

// No SAA's row: the median and minimum of every baseline round timed beside the variants.
Row baseline_row(const std::string& target, const std::vector<double>& baseline_samples, std::size_t instructions) {
  Row row;
  row.target = target;
  row.variant = "no-saa";
  row.ms = percentile(baseline_samples, 0.5);
  row.baseline_ms = row.ms;
  row.ms_min = *std::min_element(baseline_samples.begin(), baseline_samples.end());
  row.baseline_ms_min = row.ms_min;
  row.instructions = instructions;
  return row;
}

// Every variant of one target timed against no SAA, no SAA's row first.
std::vector<Row> measure_target(hx::VulkanContext& context, const saagen::Catalogue& catalogue, const std::string& target,
                                const Options& options, bool timestamps) {
  saagen::EmitOptions emit;
  emit.target = target;
  const std::vector<saagen::EmittedFile> files = saagen::emit_variants(catalogue, emit);
  const auto file_of = [&](const std::string& id) -> const saagen::EmittedFile& {
    for (const auto& file : files) {
      if (file.marker.variants.size() == 1 && file.marker.variants.front() == id) return file;
    }
    throw Failure(fmt::format("{}: no emitted file for variant {}", target, id));
  };
  const saagen::EmittedFile& brdf = file_of("brdf-ggx");

  const Shader baseline_shader = build_shader(target, "no-saa", brdf, brdf.content,
                                              body_with(baseline_shading, options.width, options.height, options.lights), options.width);
  const std::vector<float> parameters = parameter_buffer(options.width, options.height, options.lights);
  Kernel baseline(context, baseline_shader, options.width, options.height, parameters);
  baseline.run_once(timestamps);
  BaselineImage baseline_image{baseline.output(), {}};
  baseline_image.stats = check_image(target, "no-saa", baseline_image.pixels);

  std::vector<Row> rows;
  std::vector<double> all_baseline_samples;
  for (const VariantCase& variant : variant_cases()) {
    const saagen::EmittedFile& file = file_of(catalogue_variant(variant));
    const Shader shader = build_shader(target, variant.id, file, file.content + "\n" + brdf.content,
                                       body_with(variant.shading, options.width, options.height, options.lights), options.width);
    Kernel kernel(context, shader, options.width, options.height, parameters);
    const InterleavedSamples samples = time_interleaved(baseline, kernel, options, timestamps);
    const auto [pixel_change, mean_change] = image_change(target, variant.id, kernel.output(), baseline_image);
    all_baseline_samples.insert(all_baseline_samples.end(), samples.baseline_ms.begin(), samples.baseline_ms.end());

    Row row = timed_row(target, variant.id, samples);
    row.instructions = shader.instructions;
    row.delta_instructions = static_cast<long>(shader.instructions) - static_cast<long>(baseline_shader.instructions);
    row.mean_change = mean_change;
    row.pixel_change = pixel_change;
    set_paper_anchor(variant, row);
    rows.push_back(row);
  }
  rows.insert(rows.begin(), baseline_row(target, all_baseline_samples, baseline_shader.instructions));
  return rows;
}

int run_bench(const Options& options) {
  const auto started = std::chrono::steady_clock::now();
  hx::VulkanContext context(hx::ContextOptions{.device_name = options.device});
  const hx::DeviceInfo& info = context.info();
  fmt::print("device: {}\n", info.summary());
  if (!info.fragment_stores_and_atomics) throw Failure("the device lacks fragmentStoresAndAtomics (fragment storage writes)");
  const bool timestamps = info.timestamps_supported();
  const char* time_source = timestamps ? "GPU timestamp" : "host wall-clock";
  fmt::print(
      "scene: bumpy GGX sphere, alpha 0.05, {}x{} px, {} light{}, {} warm-up + {} timed rounds per variant, "
      "baseline and variant interleaved (ABBA)\n",
      options.width, options.height, options.lights, options.lights == 1 ? "" : "s", options.warmup, options.repetitions);

  const saagen::Catalogue& catalogue = saagen::Catalogue::builtin();
  report_helper_loads(context, catalogue, options);
  std::vector<Row> all_rows;
  for (const std::string target : {"glsl", "hlsl"}) {
    const std::vector<Row> rows = measure_target(context, catalogue, target, options, timestamps);
    print_table(target, rows, time_source);
    all_rows.insert(all_rows.end(), rows.begin(), rows.end());
  }

  if (!options.csv_path.empty()) write_csv(options.csv_path, all_rows, options, info.summary(), time_source);
  if (!options.json_path.empty()) write_json(options.json_path, all_rows, options, info.summary(), time_source);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  fmt::print(
      "\nratio: median over rounds of variant ms / no-SAA ms measured back to back (p25-p75: quartiles)\n"
      "min ratio: fastest variant round / fastest no-SAA round\n"
      "dSPIR-V: optimized (spirv-opt -O) instructions minus the no-SAA shader's (its own count in parentheses)\n"
      "|d| px, mean d: mean per-pixel |change| of the specular value on the sphere, change of its mean (both relative\n"
      "  to the no-SAA mean); forward aniso variants shade with the matrix GGX BRDF, so they include its extra cost\n"
      "paper: Table 2 of Tokuyoshi & Kaplanyan 2019, ratio range over Sponza, Bistro, San Miguel (8K, RX Vega 56)\n"
      "total {:.1f} s\n",
      seconds);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_bench(parse_options(argc, argv));
  } catch (const std::exception& error) {
    std::string message = error.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    std::fprintf(stderr, "bench_shading: %s\n", message.c_str());
    return 1;
  }
}

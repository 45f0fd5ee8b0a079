// Cost of the deferred roughness-limiter pass: the emitted .spv of every pass
// (saagen/products/deferred_pass.hpp) runs on the harness device (lavapipe by default) over a G-buffer
// rendered by the issue-4 renderer (the bump_plane scene: every pixel on the surface), and is
// timed with GPU timestamps around the dispatch. A baseline shader with the same bindings reads
// the normal and roughness texels and writes the roughness unfiltered: the pass's cost above it is
// the SAA math and the quad operations. Also printed: the size of every pass module and of every
// variant's linkable SPIR-V library (saagen emit --target spirv).
//
//   build/bench/bench_deferred_pass [--device NAME] [--quick] [--size WxH] [--rounds N] [--json FILE]
//
// Rounds are interleaved (every pass once per round, after two warm-up rounds); each figure is
// the median over the rounds. Exits non-zero with one line on stderr when a module fails to
// compile or validate, or when a pass leaves the roughness unchanged everywhere (not wired in).
#include "support/deferred_pass_runner.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/measure/renderer.hpp"
#include "saagen/measure/scene.hpp"
#include "saagen/products/deferred_pass.hpp"
#include "saagen/products/spirv_library.hpp"
#include "saagen/report/shading_scene.hpp"
#include "saagen/validate/compiler.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <saagen/harness/harness.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Options {
  std::uint32_t width = 1920, height = 1080;
  int rounds = 15;
  std::string json;
};

double median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  return values.size() % 2 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

Options parse(int argc, char** argv) {
  Options options;
  for (int index = 1; index < argc; ++index) {
    const std::string argument = argv[index];
    const auto value = [&]() -> std::string {
      if (index + 1 >= argc) throw std::runtime_error(argument + " needs a value");
      return argv[++index];
    };
    if (argument == "--quick") {
      options.width = options.height = 256;
      options.rounds = 3;
    } else if (argument == "--size") {
      const std::string size = value();
      if (std::sscanf(size.c_str(), "%ux%u", &options.width, &options.height) != 2 || options.width < 2 || options.height < 2) {
        throw std::runtime_error("--size takes WxH, e.g. 1920x1080");
      }
    } else if (argument == "--rounds") {
      options.rounds = std::max(1, std::stoi(value()));
    } else if (argument == "--json") {
      options.json = value();
    } else {
      throw std::runtime_error("unknown argument " + argument + " (--device NAME, --quick, --size WxH, --rounds N, --json FILE)");
    }
  }
  return options;
}

struct Entry {
  std::string name;
  std::vector<std::uint32_t> spirv;
  bool tangents = false;
  std::unique_ptr<saagen::test::DeferredPassRunner> runner;
  std::vector<double> gpu_ms;
  std::vector<float> output;
};

// The G-buffer: bump_plane seen from above, cropped so that the surface fills the image; prints its
// size and coverage.
saagen::test::GBufferImages bump_plane_gbuffer(const Options& options) {
  const double megapixels = double(options.width) * options.height * 1e-6;
  const auto scene = saagen::measure::make_scene(saagen::measure::SceneId::bump_plane);
  const auto cropped = scene.with_camera(scene.camera().cropped(static_cast<int>(std::max(options.width, options.height)) / 2,
                                                                static_cast<int>(std::max(options.width, options.height))));
  const auto gbuffer = saagen::measure::render_gbuffer(cropped, static_cast<int>(options.width), static_cast<int>(options.height));
  saagen::test::GBufferImages images;
  images.width = options.width;
  images.height = options.height;
  std::size_t covered = 0;
  for (const auto& f : gbuffer.pixels) {
    covered += f.hit;
    const auto n = f.hit ? f.normal : saagen::ref::Vec3{};
    const auto t = f.hit ? f.tangent : saagen::ref::Vec3{};
    images.normal.insert(images.normal.end(), {float(n.x), float(n.y), float(n.z), 1.0f});
    images.tangent.insert(images.tangent.end(), {float(t.x), float(t.y), float(t.z), 1.0f});
    images.roughness.insert(images.roughness.end(), {0.01f, 0.0f, 0.0f, 0.0f});  // alpha = 0.1, alpha^2 domain
  }
  std::cout << fmt::format("G-buffer: bump_plane {}x{} ({:.2f} Mpx, {:.1f} % on the surface), {} rounds\n", options.width, options.height,
                           megapixels, 100.0 * double(covered) / double(gbuffer.pixels.size()), options.rounds);
  return images;
}

// The baseline (a copy pass) and every deferred pass saagen emits, validated.
std::vector<Entry> pass_entries() {
  std::vector<Entry> entries;
  saagen::CompileRequest request;
  request.stage = saagen::ShaderStage::compute;
  request.sources = {{"baseline.comp", saagen::report::deferred_copy_source("glsl")}};
  const auto compiled = saagen::compile_to_spirv(request);
  if (!compiled.ok) throw std::runtime_error("the baseline does not compile: " + compiled.log);
  entries.push_back({"baseline (copy)", compiled.spirv, false, nullptr, {}, {}});
  for (const saagen::DeferredPass& pass : saagen::emit_deferred_passes(saagen::Catalogue::builtin(), {})) {
    if (const std::string log = saagen::validate_spirv(pass.spirv, saagen::ClientApi::vulkan); !log.empty()) {
      throw std::runtime_error(pass.stem + ".spv is invalid: " + log);
    }
    entries.push_back({pass.kind.id, pass.spirv, pass.kind.tangents, nullptr, {}, {}});
  }
  return entries;
}

// Two warm-up rounds, then `rounds` timed rounds of every pass in turn; each keeps its last output.
void time_passes(saagen::harness::VulkanContext& context, const Options& options, const saagen::test::GBufferImages& images,
                 std::vector<Entry>& entries) {
  for (Entry& entry : entries) {
    entry.runner = std::make_unique<saagen::test::DeferredPassRunner>(context, entry.spirv, entry.tangents, VK_FORMAT_R32_SFLOAT,
                                                                      options.width, options.height);
    entry.runner->upload(images);
  }
  const saagen::DeferredPassConstants constants{options.width, options.height, 0, saagen::deferred_pass_abi::domain_alpha2};
  for (int round = -2; round < options.rounds; ++round) {
    for (Entry& entry : entries) {
      auto result = entry.runner->run(constants);
      if (round >= 0) entry.gpu_ms.push_back(result.gpu_ms.front());
      if (round == options.rounds - 1) entry.output = std::move(result.output);
    }
  }
}

// The mean alpha^2 a pass wrote; throws on a non-finite value, or where a pass (not the baseline)
// changed no pixel's roughness.
double checked_mean_output(const Entry& entry, bool baseline) {
  double mean = 0.0;
  std::size_t changed = 0;
  for (float value : entry.output) {
    if (!std::isfinite(value)) throw std::runtime_error(entry.name + ": non-finite output");
    mean += value;
    changed += value != 0.01f;
  }
  if (!baseline && changed == 0) throw std::runtime_error(entry.name + ": the roughness is unchanged everywhere");
  return mean / double(entry.output.size());
}

// Prints the passes' table and returns its JSON.
nlohmann::json report_passes(const Options& options, const std::vector<Entry>& entries) {
  const double megapixels = double(options.width) * options.height * 1e-6;
  const double baseline = median(entries.front().gpu_ms);
  std::cout << fmt::format("\n{:<26} {:>10} {:>10} {:>12} {:>12} {:>8} {:>7}  {}\n", "pass", "median ms", "ms / Mpx", "- baseline",
                           "min ms / Mpx", "bytes", "instr", "mean alpha^2 out");
  nlohmann::json passes = nlohmann::json::array();
  for (const Entry& entry : entries) {
    const double ms = median(entry.gpu_ms);
    const double lowest = *std::min_element(entry.gpu_ms.begin(), entry.gpu_ms.end());
    const double mean = checked_mean_output(entry, &entry == &entries.front());
    std::cout << fmt::format("{:<26} {:>10.3f} {:>10.3f} {:>12.3f} {:>12.3f} {:>8} {:>7}  {:.5f}\n", entry.name, ms, ms / megapixels,
                             (ms - baseline) / megapixels, lowest / megapixels, entry.spirv.size() * 4,
                             saagen::count_spirv_instructions(entry.spirv), mean);
    passes.push_back({{"pass", entry.name},
                      {"median_ms", ms},
                      {"ms_per_megapixel", ms / megapixels},
                      {"ms_per_megapixel_above_baseline", (ms - baseline) / megapixels},
                      {"min_ms_per_megapixel", lowest / megapixels},
                      {"spirv_bytes", entry.spirv.size() * 4},
                      {"spirv_instructions", saagen::count_spirv_instructions(entry.spirv)},
                      {"samples_ms", entry.gpu_ms}});
  }
  return passes;
}

// Prints the SPIR-V library modules' sizes and returns their JSON.
nlohmann::json report_libraries() {
  std::cout << fmt::format("\n{:<34} {:>8} {:>7} {:>8}\n", "SPIR-V library module", "bytes", "instr", "exports");
  nlohmann::json modules = nlohmann::json::array();
  for (const saagen::SpirvLibrary& library : saagen::emit_spirv_libraries(saagen::Catalogue::builtin(), {})) {
    std::cout << fmt::format("{:<34} {:>8} {:>7} {:>8}\n", library.file_name, library.words.size() * 4,
                             saagen::count_spirv_instructions(library.words), library.exports.size());
    modules.push_back({{"module", library.file_name},
                       {"bytes", library.words.size() * 4},
                       {"instructions", saagen::count_spirv_instructions(library.words)},
                       {"exports", library.exports.size()}});
  }
  return modules;
}

int run(int argc, char** argv) {
  saagen::harness::ContextOptions context_options;
  context_options.device_name = saagen::harness::take_device_flag(argc, argv);
  const Options options = parse(argc, argv);
  saagen::harness::VulkanContext context(context_options);
  std::cout << "device: " << context.info().summary() << "\n";
  if (!context.info().timestamps_supported()) throw std::runtime_error("the device has no timestamps");
  if (!context.info().subgroup.supports(VK_SUBGROUP_FEATURE_QUAD_BIT, VK_SHADER_STAGE_COMPUTE_BIT)) {
    throw std::runtime_error("the device has no subgroup quad operations in compute");
  }

  const saagen::test::GBufferImages images = bump_plane_gbuffer(options);
  std::vector<Entry> entries = pass_entries();
  time_passes(context, options, images, entries);
  nlohmann::json json = {
      {"device", context.info().summary()}, {"width", options.width}, {"height", options.height}, {"rounds", options.rounds}};
  json["passes"] = report_passes(options, entries);
  json["libraries"] = report_libraries();
  if (!options.json.empty()) {
    std::ofstream(options.json) << json.dump(2) << "\n";
    std::cout << "wrote " << options.json << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& error) {
    std::cerr << "bench_deferred_pass: " << error.what() << "\n";
    return 1;
  }
}

// Cost of geometric glint anti-aliasing: a fragment kernel shades a glinty sphere
// (saagen glint snippet, GLSL and HLSL) once with GGAA (glint_brdf_filtered_fragment: ddx/ddy of
// the projected half vector, two integer levels of the MIP-mapped dictionary blended) and once with the 2020
// baseline (glint_brdf_fragment: textureLod on a dictionary without MIPs), interleaved in one run
// on the harness device (lavapipe by default), as Chermain et al. 2021 Table 1 compares them.
//
//   build/bench/bench_glints [--device NAME] [--quick] [--size N] [--rounds N] [--max-anisotropy A]
//
// --max-anisotropy (glint_max_anisotropy, default 8): 1 makes every footprint isotropic (the
// ellipse a disc on the major axis: fewer cells, the level of the major axis).
//
// Prints per target: median ms of each, the median and quartiles of the per-round ratio GGAA /
// baseline (ABBA order), optimized SPIR-V instruction counts, the mean shaded value of both
// images, and the dictionary's memory with and without MIPs. Exits non-zero with one line when a
// shader does not compile or the image is empty or non-finite.
#include "support/glint_dictionary_binding.hpp"

#include "saagen/products/glints.hpp"
#include "saagen/validate/compiler.hpp"
#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <saagen/harness/harness.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace hx = saagen::harness;

// A bumpy unit sphere 3 units in front of the camera, filling ~70 % of the frame; directional
// light from the upper left. uv = the sphere's normal.xy (about 0.004 per pixel at 512 px): with
// ln density 16 the footprint's LOD is ~3-6 (tens to thousands of microfacets per pixel).
constexpr const char* scene_body = R"(    real2 ndc = saagen_frag_coord * (2.0 / {size}.0) - 1.0;
    real3 ray = normalize(real3(ndc.x * 0.42, -ndc.y * 0.42, -1.0));
    real3 centre = real3(0.0, 0.0, -3.0);
    real closest = dot(ray, centre);
    real discriminant = closest * closest - dot(centre, centre) + 1.0;
    bool hit = discriminant > 0.0;
    real3 position = (closest - sqrt(max(discriminant, 0.0))) * ray;
    real3 sphere_normal = normalize(position - centre);
    // Procedural bumps (about 6 px at 512 px): the half vector turns quickly, so GGAA filters.
    real3 gradient = cos(sphere_normal * 90.0);
    real3 normal = normalize(sphere_normal - 0.2 * (gradient - sphere_normal * dot(gradient, sphere_normal)));
    real3 tangent = real3(normal.z, 0.0, -normal.x) * rsqrt(max(normal.z * normal.z + normal.x * normal.x, 1e-12));
    real3 bitangent = cross(normal, tangent);
    real3 light = normalize(real3(-0.4, 0.5, 1.0));
    real3 view = -ray;
    real3 i_ts = real3(dot(light, tangent), dot(light, bitangent), dot(light, normal));
    real3 o_ts = real3(dot(view, tangent), dot(view, bitangent), dot(view, normal));
    real2 uv = sphere_normal.xy;
    real value = {call}(i_ts, o_ts, real2(0.0, 0.0), uv, real3(0.12, 0.12, 0.0), 16.0) * max(i_ts.z, 0.0);
    SAAGEN_STORE(0, hit ? value : -1.0);
)";

struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string body(const std::string& call, std::uint32_t size) {
  std::string text = scene_body;
  text.replace(text.find("{size}"), 6, std::to_string(size));
  text.replace(text.find("{call}"), 6, call);
  return text;
}

struct Shader {
  std::vector<std::uint32_t> spirv;
  std::size_t optimized_instructions = 0;
};

Shader compile(const std::string& target, const std::string& variant, const std::string& call, std::uint32_t size, double max_anisotropy) {
  saagen::EmitOptions options;
  options.target = target;
  options.variants = {variant};
  options.option_values["glint_max_anisotropy"] = max_anisotropy;
  const auto file = saagen::glints::emit(options).front();
  saagen::KernelRequest request;
  request.kind = saagen::KernelKind::fragment;
  request.body = body(call, size);
  request.output_stride = 1;
  request.width = size;
  const auto result =
      saagen::compile_to_spirv(saagen::kernel_compile_request(saagen::glints::catalogue(), file.file_name, file.content, request));
  if (!result.ok)
    throw Failure(fmt::format("{} {}: the kernel does not compile: {}", target, variant, result.log.substr(0, result.log.find('\n'))));
  return {result.spirv, saagen::count_spirv_instructions(saagen::optimize_spirv(result.spirv, saagen::ClientApi::vulkan))};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}
double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1) + 0.5)];
}

struct Image {
  double mean = 0.0;
  std::size_t lit = 0;
};

// Pixels whose value GGAA changes by more than 1e-4 relative: GGAA is wired in and filtering.
std::size_t changed(const std::vector<float>& a, const std::vector<float>& b) {
  std::size_t count = 0;
  for (std::size_t k = 0; k < a.size(); ++k) count += std::fabs(a[k] - b[k]) > 1e-4f * std::max(std::fabs(a[k]), std::fabs(b[k])) + 1e-12f;
  return count;
}

Image summarise(const std::vector<float>& values, const std::string& what) {
  Image image;
  std::size_t covered = 0;
  for (float v : values) {
    if (v == -1.0f) continue;
    if (!std::isfinite(v) || v < 0.0f) throw Failure(fmt::format("{}: a shaded value is {}", what, v));
    ++covered;
    image.mean += v;
    image.lit += v > 0.0f;
  }
  if (covered == 0 || image.lit == 0) throw Failure(fmt::format("{}: the sphere is missing or black", what));
  image.mean /= static_cast<double>(covered);
  return image;
}

struct Options {
  std::uint32_t size = 512, rounds = 12;
  double max_anisotropy = 8.0;
  std::string device;
};

// nullopt after printing the usage line for an unknown argument.
std::optional<Options> parse_options(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  Options o;
  for (std::size_t k = 0; k < args.size(); ++k) {
    if (args[k] == "--quick")
      o.size = 128, o.rounds = 3;
    else if (args[k] == "--size" && k + 1 < args.size())
      o.size = static_cast<std::uint32_t>(std::stoul(args[++k]));
    else if (args[k] == "--rounds" && k + 1 < args.size())
      o.rounds = static_cast<std::uint32_t>(std::stoul(args[++k]));
    else if (args[k] == "--device" && k + 1 < args.size())
      o.device = args[++k];
    else if (args[k] == "--max-anisotropy" && k + 1 < args.size())
      o.max_anisotropy = std::stod(args[++k]);
    else {
      std::cerr << "bench_glints: unknown argument '" << args[k]
                << "' (use --device NAME, --quick, --size N, --rounds N, --max-anisotropy A)\n";
      return std::nullopt;
    }
  }
  o.size &= ~1u;
  return o;
}

// One target's GGAA against the textureLod baseline: timed ABBA, both images checked, one line.
void bench_target(hx::VulkanContext& context, const std::string& target, const Options& o,
                  const saagen::glints::DictionaryTexture& with_mips, const saagen::glints::DictionaryTexture& without_mips) {
  const Shader ggaa = compile(target, "glints-ggaa", "glint_brdf_filtered_fragment", o.size, o.max_anisotropy);
  const Shader baseline = compile(target, "glints", "glint_brdf_fragment", o.size, o.max_anisotropy);
  const auto make_run = [&](const Shader& shader, const saagen::glints::DictionaryTexture& texture) {
    hx::FragmentRun run;
    run.fragment.spirv = shader.spirv;
    run.width = run.height = o.size;
    run.images = {saagen::test::glint_dictionary_binding(texture, 2)};
    run.buffers = {hx::input_buffer(0, std::vector<float>{0.0f}), hx::output_buffer<float>(1, std::size_t{o.size} * o.size)};
    return run;
  };
  hx::FragmentProgram ggaa_program(context, make_run(ggaa, with_mips));
  hx::FragmentProgram baseline_program(context, make_run(baseline, without_mips));
  const bool timestamps = context.info().timestamps_supported();
  std::vector<double> ggaa_ms, baseline_ms, ratios;
  hx::RunResult ggaa_result, baseline_result;
  const auto time = [&](hx::FragmentProgram& program, hx::RunResult& result) {
    result = program.run({.repetitions = 1, .gpu_timestamps = timestamps});
    return timestamps ? result.timing.gpu_ms.front() : result.timing.host_ms.front();
  };
  time(ggaa_program, ggaa_result);  // warm-up
  time(baseline_program, baseline_result);
  for (std::uint32_t round = 0; round < o.rounds; ++round) {
    double a = 0.0, b = 0.0;
    if (round % 2 == 0) {
      b = time(baseline_program, baseline_result);
      a = time(ggaa_program, ggaa_result);
    } else {
      a = time(ggaa_program, ggaa_result);
      b = time(baseline_program, baseline_result);
    }
    ggaa_ms.push_back(a);
    baseline_ms.push_back(b);
    ratios.push_back(a / b);
  }
  const Image ggaa_image = summarise(ggaa_result.buffer_as<float>(1), target + " GGAA");
  const Image baseline_image = summarise(baseline_result.buffer_as<float>(1), target + " baseline");
  const std::size_t filtered = changed(ggaa_result.buffer_as<float>(1), baseline_result.buffer_as<float>(1));
  if (filtered == 0) throw Failure(target + ": GGAA leaves the image unchanged; the timings would be meaningless");
  std::cout << fmt::format(
      "{}: GGAA {:.3f} ms, textureLod baseline {:.3f} ms; overhead {:+.1f} % (quartiles {:+.1f} .. {:+.1f} %; paper: +0.6 .. +4.2 % on an RTX 2080)\n"
      "{}:   optimized SPIR-V instructions: GGAA {}, baseline {} ({:+d}); mean shaded value GGAA {:.5f}, baseline {:.5f}; lit pixels {} / {}; "
      "pixels GGAA changes: {}\n",
      target, median(ggaa_ms), median(baseline_ms), 100.0 * (median(ratios) - 1.0), 100.0 * (quantile(ratios, 0.25) - 1.0),
      100.0 * (quantile(ratios, 0.75) - 1.0), target, ggaa.optimized_instructions, baseline.optimized_instructions,
      static_cast<long>(ggaa.optimized_instructions) - static_cast<long>(baseline.optimized_instructions), ggaa_image.mean,
      baseline_image.mean, ggaa_image.lit, baseline_image.lit, filtered);
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<Options> options = parse_options(argc, argv);
  if (!options) return 2;
  try {
    if (!options->device.empty()) setenv("SAAGEN_VK_DEVICE", options->device.c_str(), 1);
    hx::VulkanContext context;
    const auto dictionary = saagen::glints::generate_dictionary({});
    const auto with_mips = saagen::glints::dictionary_texture(dictionary, true);
    const auto without_mips = saagen::glints::dictionary_texture(dictionary, false);
    std::cout << fmt::format("device: {}; {} x {} pixels, {} rounds (ABBA); max anisotropy {}\n", context.info().name, options->size,
                             options->size, options->rounds, options->max_anisotropy);
    std::cout << fmt::format(
        "dictionary: N = 192, L = 16, R = 64, RGBA16F: {:.0f} KiB without MIPs, {:.0f} KiB with MIPs (+{:.1f} %)\n",
        saagen::glints::texture_bytes(without_mips) / 1024.0, saagen::glints::texture_bytes(with_mips) / 1024.0,
        100.0 * (double(saagen::glints::texture_bytes(with_mips)) / double(saagen::glints::texture_bytes(without_mips)) - 1.0));
    for (const std::string target : {"glsl", "hlsl"}) bench_target(context, target, *options, with_mips, without_mips);
  } catch (const std::exception& error) {
    std::cerr << "bench_glints: " << error.what() << "\n";
    return 1;
  }
  return 0;
}

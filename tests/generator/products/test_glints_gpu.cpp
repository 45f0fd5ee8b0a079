// The glints on a Vulkan device (lavapipe in CI): the dictionary bound as a sampled 1D array image
// with its MIP chain (RGBA16F, LINEAR/LINEAR/LINEAR, MIRRORED_REPEAT), read in compute shaders.
//   - GlintSamplerOnGpu: textureLod at integer levels (the only reads the snippets make) against
//     the software sampler of the reference, texel by texel; the energy of the filtered
//     distributions measured on the device.
//   - GlintSnippetOnGpu: the emitted glint functions (GLSL and HLSL; GGAA and the level-0
//     baseline; SDF, BRDF, LEAN) against the double-precision reference.
//
// Error bounds: the fp32 bound, the transcendental and cos / sin allowances and the sampler's
// freedom are derived in glint_support.hpp (shared with the WebGPU and WebGL2 suites). The GGAA
// lookup computes its LOD in the shader (log2 within the transcendental allowance) and reads the
// two integer levels around it with an explicit LOD, blending them itself. An explicit integer
// LOD with no bias is lambda exactly (Vulkan specification, "Scale Factor Operation,
// Level-of-Detail Operation and Image Level(s) Selection": lambda' = lambda_base + bias), and
// "Image Level(s) Selection" takes delta = lambda - floor(lambda) = 0, which quantising to any
// mipmapPrecisionBits leaves 0: one level alone, so the device's LOD rule, LOD accuracy and mip
// blend do not enter. What remains of the sampler's freedom is the texel coordinate to
// subTexelPrecisionBits ("Texel Coordinate Operations"; ref::glints::texture_level_range) and
// the RGBA16F format's rounding of the result (half_float_result: rounded either way to a half,
// "Numeric Representation and Computation" and "Floating-Point Format Conversions"; NVIDIA
// does, lavapipe and SwiftShader filter in fp32; docs/GLINTS.md). SwiftShader uses about 0.4 of
// the cos / sin allowance (1.9e-4), lavapipe 1e-7. On lavapipe a second, tighter check takes the
// exact sampler with the fp32 bound alone (lavapipe filters in fp32 with unquantised weights).
#include "support/glint_dictionary_binding.hpp"
#include "support/glint_support.hpp"

#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <iostream>
#include <random>
#include <saagen/harness/harness.hpp>

namespace {

namespace g = saagen::ref::glints;
namespace glint = saagen::test::glint;
namespace hx = saagen::harness;

hx::VulkanContext& gpu() {
  static hx::VulkanContext context;
  return context;
}

bool on_lavapipe() { return gpu().info().name.find("llvmpipe") != std::string::npos; }

// The tight checks take lavapipe's exact fp32 filter (no sub-texel quantisation, no half result):
// a lavapipe fact, said so where it is not run.
void say_no_lavapipe_check(const std::string& what) {
  std::cout << "[ skipped  ] " << what << " against the exact fp32 filter: a lavapipe fact, not checked on " << gpu().info().name
            << " (the specification's check above is)\n";
}

// The spec's sampler freedom on this device (its reported precision limits).
const g::SamplerTolerance& spec_tolerance() {
  static const g::SamplerTolerance tolerance = [] {
    const auto& limits = gpu().limits();
    g::SamplerTolerance t =
        g::vulkan_sampler_tolerance(static_cast<int>(limits.mipmapPrecisionBits), static_cast<int>(limits.subTexelPrecisionBits));
    t.half_float_result = true;  // the dictionary is RGBA16F (dictionary_binding)
    std::cout << fmt::format(
        "[ sampler  ] {}: mipmapPrecisionBits {} (not used: integer levels only), subTexelPrecisionBits {}: texel coordinate +-{}, "
        "result rounded either way to a half\n",
        gpu().info().name, limits.mipmapPrecisionBits, limits.subTexelPrecisionBits, t.texel_weight);
    return t;
  }();
  return tolerance;
}

// The default dictionary as a combined image sampler at (set 0, binding).
hx::ImageBinding dictionary_binding(std::uint32_t binding) {
  return saagen::test::glint_dictionary_binding(saagen::test::default_texture(), binding);
}

// ---------------------------------------------------------------------------------------------
// The sampler alone

struct Query {
  float u, layer, a, b;  // textureGrad: a = du/dx, b = du/dy; textureLod: a = lod, b = NaN
};

std::vector<float> run_queries(const std::vector<Query>& queries) {
  hx::ComputeRun run;
  run.shader = hx::shader_desc(hx::Language::glsl, hx::Stage::compute, R"(#version 450
layout(local_size_x = 64) in;
layout(set = 0, binding = 2) uniform sampler1DArray dictionary;
layout(std430, set = 0, binding = 0) readonly buffer Queries { vec4 queries[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Results { vec4 results[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  vec4 q = queries[i];
  results[i] = isnan(q.w) ? textureLod(dictionary, q.xy, q.z) : textureGrad(dictionary, q.xy, q.z, q.w);
}
)");
  run.images = {dictionary_binding(2)};
  run.buffers = {hx::input_buffer(0, queries), hx::output_buffer<float>(1, 4 * queries.size())};
  run.groups = {static_cast<std::uint32_t>(queries.size() / 64)};
  return hx::run_compute(gpu(), run).buffer_as<float>(1);
}

// The snippets read the dictionary with textureLod at integer levels only (q.a an integer, q.b NaN).
g::TexelRange reference_range(const Query& q, const g::SamplerTolerance& tolerance) {
  return g::texture_level_range(saagen::test::default_reference_texture(), q.u, q.layer, static_cast<int>(q.a), tolerance);
}

TEST(GlintSamplerOnGpu, TextureLodAtIntegerLevelsMatchesTheSoftwareSampler) {
  // The spec check on every device; on lavapipe also the tight check (its filter is exact fp32).
  const bool lavapipe = on_lavapipe();
  const auto& texture = saagen::test::default_reference_texture();
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Query> queries;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  while (queries.size() < 32768) {
    const float u = static_cast<float>(-2.5 + 5.0 * unit(random));
    const float layer = static_cast<float>(std::floor(768.0 * unit(random)));
    // Levels -1 .. 8: below 0 and above the last level (6) the sampler clamps an explicit LOD.
    const float level = static_cast<float>(std::floor(-1.0 + 10.0 * unit(random)));
    queries.push_back({u, layer, level, nan});
  }
  const auto got = run_queries(queries);
  // The same check without the format's rounding: what the half result adds on this device.
  g::SamplerTolerance unrounded_tolerance = spec_tolerance();
  unrounded_tolerance.half_float_result = false;
  std::vector<double> expected, bounds, spec_expected, spec_bounds, unrounded_expected, unrounded_bounds;
  for (const Query& q : queries) {
    const g::TexelRange range = reference_range(q, spec_tolerance());
    const g::TexelRange unrounded = reference_range(q, unrounded_tolerance);
    const g::Texel value = g::texture_level(texture, q.u, q.layer, static_cast<int>(q.a));
    // fp32: the rounding of u * width (a backward error of a few ulps of u).
    g::Texel spread{};
    for (double su : {-1.0, 1.0}) {
      const g::Texel perturbed = g::texture_level(texture, q.u * (1.0 + su * 0x1.0p-22), q.layer, static_cast<int>(q.a));
      for (int c = 0; c < 4; ++c) spread[c] = std::max(spread[c], std::fabs(perturbed[c] - value[c]));
    }
    for (int c = 0; c < 4; ++c) {
      const double fp32 = 2.0 * spread[c] + 2e-6 * std::fabs(value[c]) + 1e-9;
      expected.push_back(value[c]);
      bounds.push_back(fp32);
      glint::push_interval(spec_expected, spec_bounds, range.low[c], range.high[c], fp32);
      glint::push_interval(unrounded_expected, unrounded_bounds, unrounded.low[c], unrounded.high[c], fp32);
    }
  }
  const auto describe = [&](std::size_t i) {
    const Query& q = queries[i / 4];
    return fmt::format("u {} layer {} level {}", q.u, q.layer, q.a);
  };
  const auto spec = hx::compare_with_bounds(got, spec_expected, spec_bounds,
                                            "dictionary textureLod at integer levels (Vulkan spec sampler rules)", describe);
  // Not through compare_with_bounds: the run's "[ bound ]" totals count the checks made.
  std::pair<std::size_t, double> unrounded_failing_worst{0, 0.0};
  for (std::size_t i = 0; i < got.size(); ++i) {
    const double ratio = std::fabs(got[i] - unrounded_expected[i]) / unrounded_bounds[i];
    unrounded_failing_worst.first += ratio > 1.0;
    unrounded_failing_worst.second = std::max(unrounded_failing_worst.second, ratio);
  }
  std::cout << "[ sampler  ] spec: " << spec.summary() << "\n"
            << fmt::format("[ sampler  ] without the half rounding of the result: {} of {} failing, worst err {:.3g} x tol\n",
                           unrounded_failing_worst.first, got.size(), unrounded_failing_worst.second);
  EXPECT_EQ(spec.failing, 0u) << spec.summary();
  if (!lavapipe) return say_no_lavapipe_check("the sampler");
  const auto report =
      hx::compare_with_bounds(got, expected, bounds, "dictionary textureLod at integer levels (exact fp32 filter)", describe);
  double worst_abs = 0.0;
  for (std::size_t i = 0; i < got.size(); ++i) worst_abs = std::max(worst_abs, std::fabs(got[i] - expected[i]));
  std::cout << "[ sampler  ] device " << gpu().info().name << ", exact filter: " << report.summary() << "\n"
            << "[ sampler  ] max |device - reference| = " << worst_abs << " (texel values up to ~10)\n";
  EXPECT_EQ(report.failing, 0u) << report.summary();
}

TEST(GlintSamplerOnGpu, FilteredDistributionsIntegrateToOneOnTheDevice) {
  // Trapezoidal rule over u in [-1, 1], step 1/128 (exact for the linear reconstruction).
  const int steps = 256;
  const double lambdas[] = {-2.0, 0.0, 0.5, 1.7, 3.0, 4.4, 6.0, 8.0};
  const int layers[] = {0, 47, 48, 300, 719, 767};
  std::vector<Query> queries;
  for (double lambda : lambdas) {
    for (int layer : layers) {
      for (int k = 0; k <= steps; ++k) {
        const double g = std::exp2(lambda) / 64.0;
        queries.push_back(
            {static_cast<float>(-1.0 + 2.0 * k / steps), static_cast<float>(layer), static_cast<float>(g), static_cast<float>(-0.5 * g)});
      }
    }
  }
  while (queries.size() % 64 != 0) queries.push_back({0.0f, 0.0f, 0.0f, 0.0f});
  const auto got = run_queries(queries);
  const double range = saagen::test::default_dictionary().params.range();
  double worst = 0.0;
  std::size_t index = 0;
  for (std::size_t l = 0; l < std::size(lambdas); ++l) {
    for (std::size_t layer = 0; layer < std::size(layers); ++layer) {
      double sums[4] = {};
      for (int k = 0; k <= steps; ++k, ++index) {
        for (int c = 0; c < 4; ++c) sums[c] += (k == 0 || k == steps ? 0.5 : 1.0) * got[4 * index + c];
      }
      for (double sum : sums) worst = std::max(worst, std::fabs(range * sum * 2.0 / steps - 1.0));
    }
  }
  std::cout << "[ energy   ] on the device: max |integral - 1| of 192 filtered distributions (8 LODs from -2 to 8) = " << worst << "\n";
  EXPECT_LT(worst, 5e-4);  // the half rounding of the texels (see GlintDictionary.EveryDistributionIntegratesToOne)
}

// ---------------------------------------------------------------------------------------------
// The emitted functions

struct SnippetCase {
  std::string target;
  std::string variant;
  std::string function;
  glint::Options options;  // emission options other than the defaults (the reference gets the same)
};

void PrintTo(const SnippetCase& c, std::ostream* os) { *os << c.target << " " << c.function; }

class GlintSnippetOnGpu : public ::testing::TestWithParam<SnippetCase> {};

TEST_P(GlintSnippetOnGpu, MatchesTheDoublePrecisionReference) {
  const SnippetCase& c = GetParam();
  constexpr std::size_t count = 16384;
  const saagen::Catalogue& catalogue = saagen::glints::catalogue();
  const saagen::Function& function = *catalogue.find_function(c.function);

  saagen::EmitOptions options;
  options.target = c.target;
  options.variants = {c.variant};
  options.option_values = {{"glint_relative_area", c.options.relative_area}, {"glint_max_anisotropy", c.options.max_anisotropy}};
  const auto file = saagen::glints::emit(options).front();
  saagen::KernelRequest request;
  request.body = saagen::load_call_store_body(catalogue, c.function, request);
  const auto compiled = saagen::compile_to_spirv(saagen::kernel_compile_request(catalogue, file.file_name, file.content, request));
  ASSERT_TRUE(compiled.ok) << compiled.log;

  const std::vector<float> inputs = glint::packed_inputs(function, count);
  ASSERT_EQ(inputs.size(), count * request.input_stride);
  hx::ComputeRun run;
  run.shader.spirv = compiled.spirv;
  run.images = {dictionary_binding(2)};
  run.buffers = {hx::input_buffer(0, inputs), hx::output_buffer<float>(1, count * request.output_stride)};
  run.groups = {static_cast<std::uint32_t>(count / request.workgroup_size)};
  const auto got = hx::run_compute(gpu(), run).buffer_as<float>(1);

  // On lavapipe, the tight check: the exact sampler with the fp32 bound alone.
  const bool lavapipe = on_lavapipe();
  const glint::Comparison comparison = glint::core_comparison(c.function, c.options, inputs, count, request.input_stride, spec_tolerance());
  const std::vector<double>& expected = comparison.expected;
  const std::vector<double>& bounds = comparison.bounds;
  double worst_relative = 0.0;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    if (std::fabs(expected[k]) > 1e-3) worst_relative = std::max(worst_relative, std::fabs(got[k] - expected[k]) / std::fabs(expected[k]));
  }
  std::size_t nonzero = 0;
  for (double v : expected) nonzero += v != 0.0;
  // How tight the comparison is: quantiles of the relative error and of the relative bound over
  // the outputs above 1e-6 of the largest one.
  std::vector<double> relative_errors, relative_bounds;
  const double largest =
      *std::max_element(expected.begin(), expected.end(), [](double a, double b) { return std::fabs(a) < std::fabs(b); });
  for (std::size_t k = 0; k < expected.size(); ++k) {
    if (std::fabs(expected[k]) <= 1e-6 * std::fabs(largest)) continue;
    relative_errors.push_back(std::fabs(got[k] - expected[k]) / std::fabs(expected[k]));
    relative_bounds.push_back(bounds[k] / std::fabs(expected[k]));
  }
  const auto quantile = [](std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * (v.size() - 1))];
  };
  std::cout << fmt::format(
      "[ quantile ] relative error 50/99/99.9 %: {:.2e} {:.2e} {:.2e}; relative bound 50/99/99.9 %: {:.2e} {:.2e} {:.2e}\n",
      quantile(relative_errors, 0.5), quantile(relative_errors, 0.99), quantile(relative_errors, 0.999), quantile(relative_bounds, 0.5),
      quantile(relative_bounds, 0.99), quantile(relative_bounds, 0.999));
  const auto spec = hx::compare_with_bounds(got, comparison.spec_expected, comparison.spec_bounds,
                                            fmt::format("{} {} (Vulkan spec sampler rules)", c.target, c.function));
  std::cout << "[ spec     ] " << spec.summary() << "\n";
  EXPECT_EQ(spec.failing, 0u) << spec.summary();
  EXPECT_EQ(comparison.outside, 0u) << "the exact-LOD reference lies outside [low, high]: the lookups' bound is not monotone";
  EXPECT_GT(nonzero, expected.size() / 2);  // the inputs do hit lobes
  if (!lavapipe) return say_no_lavapipe_check(c.target + " " + c.function);
  const auto report =
      hx::compare_with_bounds(got, expected, bounds, fmt::format("{} {} (lavapipe: exact fp32 filter)", c.target, c.function));
  std::cout << "[ worst    ] " << report.summary() << "\n[ worst    ] max relative error (|expected| > 1e-3): " << worst_relative << "; "
            << nonzero << " of " << expected.size() << " outputs non-zero\n";
  EXPECT_EQ(report.failing, 0u) << report.summary();
}

// ---------------------------------------------------------------------------------------------
// The fragment wrappers: ddx/ddy taken in 2x2 quads (the harness's quad_compute kernel: subgroup
// quad operations stand in for the derivative instructions, fine differences as lavapipe's plain
// ddx), against the reference fed the same quad differences (glint::fragment_comparison).

TEST(GlintFragmentOnGpu, WrappersMatchTheReferenceFedTheSameQuads) {
  constexpr std::uint32_t width = 64, height = 64, pixels = width * height;
  const bool lavapipe = on_lavapipe();
  for (const std::string target : {"glsl", "hlsl"}) {
    for (const bool filtered : {true, false}) {
      saagen::EmitOptions options;
      options.target = target;
      options.variants = {filtered ? "glints-ggaa" : "glints"};
      const auto file = saagen::glints::emit(options).front();
      saagen::KernelRequest request;
      request.kind = saagen::KernelKind::quad_compute;
      request.body = filtered ? glint::wrapper_body : glint::baseline_wrapper_body;
      request.output_stride = filtered ? 2 : 1;
      request.width = width;
      request.plain_derivative = saagen::PlainDerivative::fine;
      const auto compiled =
          saagen::compile_to_spirv(saagen::kernel_compile_request(saagen::glints::catalogue(), file.file_name, file.content, request));
      ASSERT_TRUE(compiled.ok) << compiled.log;
      hx::ComputeRun run;
      run.shader.spirv = compiled.spirv;
      run.images = {dictionary_binding(2)};
      run.buffers = {hx::input_buffer(0, std::vector<float>{0.0f}), hx::output_buffer<float>(1, pixels * request.output_stride)};
      run.groups = {pixels / request.workgroup_size};
      const auto got = hx::run_compute(gpu(), run).buffer_as<float>(1);

      const glint::Comparison comparison =
          glint::fragment_comparison(filtered, width, height, saagen::ref::Derivative::fine, spec_tolerance());
      std::size_t nonzero = 0;
      for (double v : comparison.expected) nonzero += v > 0.0;
      const std::string what =
          fmt::format("{} {}", target, filtered ? "glint_brdf_filtered_fragment + _slope_fragment" : "glint_brdf_fragment");
      const auto spec =
          hx::compare_with_bounds(got, comparison.spec_expected, comparison.spec_bounds, what + " (Vulkan spec sampler rules)");
      std::cout << "[ fragment ] " << spec.summary() << "; " << nonzero << " of " << comparison.expected.size() << " non-zero\n";
      EXPECT_EQ(spec.failing, 0u) << spec.summary();
      EXPECT_GT(nonzero, comparison.expected.size() / 2);
      if (!lavapipe) continue;
      const auto report = hx::compare_with_bounds(got, comparison.expected, comparison.bounds, what + " (lavapipe: exact fp32 filter)");
      std::cout << "[ fragment ] " << report.summary() << "\n";
      EXPECT_EQ(report.failing, 0u) << report.summary();
    }
  }
}

std::vector<SnippetCase> snippet_cases() {
  std::vector<SnippetCase> cases;
  for (const std::string target : {"glsl", "hlsl"}) {
    cases.push_back({target, "glints", "glint_sdf", {}});
    cases.push_back({target, "glints", "glint_brdf", {}});
    cases.push_back({target, "glints-ggaa", "glint_sdf_filtered", {}});
    cases.push_back({target, "glints-ggaa", "glint_brdf_filtered", {}});
    cases.push_back({target, "glints-ggaa", "lean_roughness", {}});
  }
  // The relative area (half the cells empty) and a lower anisotropy clamp.
  cases.push_back({"glsl", "glints-ggaa", "glint_sdf_filtered", {.relative_area = 0.5, .max_anisotropy = 4.0}});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryFunction, GlintSnippetOnGpu, ::testing::ValuesIn(snippet_cases()), [](const auto& info) {
  const bool defaults = info.param.options.relative_area == 1.0 && info.param.options.max_anisotropy == 8.0;
  return info.param.target + "_" + info.param.function + (defaults ? "" : "_area_half_anisotropy_4");
});

}  // namespace

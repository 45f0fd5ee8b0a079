// Engines on the GPU devices (lavapipe, SwiftShader): the roughness-domain wrappers against the
// double-precision reference, their exact ends, and every preset compiled from a user shader
// through the shaderc include handler, run against the engine's own formula.
//
// Bound per element: |gpu - reference| <= 2e-5 * S + 2^-24 with S the scale of the roughness
// the error lives in (the output, or r' = 1 - s' for smoothness). The filter is a handful of
// products and sums of positive terms (relative error ~ n 2^-24, n <= 12); the conversions add
// two sqrt, which Vulkan lets inherit 1 / inversesqrt's 2 ulp plus the division's 2.5 ulp
// (Vulkan spec, "Precision and Operation of SPIR-V Instructions"), and r = a^(1/4) divides a
// relative error of a by 4. 2e-5 covers that with the same margin as test_gpu_core.cpp; 2^-24
// is the final 1 - r rounding of the smoothness domain.
#include "engine_forms.hpp"
#include "support/gpu_support.hpp"
#include "support/include_shaders.hpp"

#include "saagen/emit/engines.hpp"
#include "saagen/reference/saa.hpp"

#include <cmath>
#include <limits>
#include <ostream>
#include <random>

namespace {

namespace ref = saagen::ref;
using ref::RoughnessDomain;
using ref::Vec3;

constexpr std::uint32_t element_count = 65536;

RoughnessDomain reference_domain(const std::string& id) {
  if (id == "alpha") return RoughnessDomain::alpha;
  if (id == "perceptual") return RoughnessDomain::perceptual;
  if (id == "smoothness") return RoughnessDomain::smoothness;
  return RoughnessDomain::alpha2;
}

// Inputs: 7 floats (value, dn_dx, dn_dy). The first elements are the ends of the range; the
// rest are random values with derivative magnitudes log-uniform over 1e-4..10.
struct Batch {
  std::vector<float> inputs;
  std::size_t ends = 0;  // elements with an exactly known result
  std::vector<float> exact;
};

Batch make_batch(bool smoothness) {
  Batch batch;
  const float denormal = std::numeric_limits<float>::denorm_min() * 1000.0f;
  const float rough_end = smoothness ? 0.0f : 1.0f, smooth_end = smoothness ? 1.0f : 0.0f;
  const auto push = [&](float value, Vec3 dx, Vec3 dy) {
    for (double v : {static_cast<double>(value), dx.x, dx.y, dx.z, dy.x, dy.y, dy.z}) batch.inputs.push_back(static_cast<float>(v));
  };
  const Vec3 zero{0, 0, 0}, huge{10, 0, 0};
  // (input, derivatives) -> exact output with kappa = 1: the ends, the saturation bound, denormals.
  const std::vector<std::tuple<float, Vec3, float>> ends = {
      {smooth_end, zero, smooth_end},                               // roughness 0 stays exactly 0
      {rough_end, zero, rough_end},                                 // roughness 1 stays exactly 1
      {rough_end, huge, rough_end},                                 // saturated at 1
      {0.5f, huge, rough_end},                                      // the saturation bound: kernel 1 -> roughness 1
      {smoothness ? 1.0f - denormal : denormal, zero, smooth_end},  // underflows to alpha^2 = 0
  };
  for (const auto& [value, derivative, result] : ends) {
    push(value, derivative, derivative);
    batch.exact.push_back(result);
  }
  batch.ends = ends.size();
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  while (batch.inputs.size() < std::size_t{element_count} * 7) {
    const auto direction = [&](double m) {
      const double z = 2 * unit(random) - 1, phi = 6.283185307179586 * unit(random), r = std::sqrt(1 - z * z);
      return Vec3{m * r * std::cos(phi), m * r * std::sin(phi), m * z};
    };
    push(static_cast<float>(unit(random)), direction(std::pow(10.0, -4 + 5 * unit(random))),
         direction(std::pow(10.0, -4 + 5 * unit(random))));
  }
  return batch;
}

std::vector<float> run(const std::vector<std::uint32_t>& spirv, const std::vector<float>& inputs, std::uint32_t workgroup_size) {
  saagen::harness::ComputeRun compute;
  compute.shader.spirv = spirv;
  compute.buffers = {saagen::harness::input_buffer(0, inputs), saagen::harness::output_buffer<float>(1, element_count)};
  compute.groups = {element_count / workgroup_size, 1, 1};
  return saagen::harness::run_compute(saagen::test::gpu(), compute).buffer_as<float>(1);
}

struct DomainCase {
  const char* target;
  const char* domain;
  const char* variant;
};

// The parameter as ctest lists it (without a printer gtest prints the object's bytes, pointers
// included, so the test's name would change from run to run).
void PrintTo(const DomainCase& c, std::ostream* os) { *os << c.target << " " << c.domain << " " << c.variant; }

class DomainWrappersOnGpu : public ::testing::TestWithParam<DomainCase> {};

TEST_P(DomainWrappersOnGpu, MatchTheReferenceAndAreExactAtTheEnds) {
  const DomainCase& c = GetParam();
  const saagen::Domain kind = saagen::find_domain(c.domain).kind;
  const saagen::Catalogue& catalogue = saagen::domain_catalogue(saagen::Catalogue::builtin(), kind);
  saagen::EmitOptions options;
  options.target = c.target;
  options.variants = {c.variant};
  options.domain = kind;
  options.option_values = {{"sigma2", 0.25}, {"kappa", 1.0}};  // kappa 1: the saturation bound is reachable
  const saagen::EmittedFile file = saagen::emit_variants(saagen::Catalogue::builtin(), options).front();
  std::string core = c.variant;
  for (char& ch : core) ch = ch == '-' ? '_' : ch;
  const std::string wrapper = saagen::domain_function_name(core, kind);
  saagen::KernelRequest request;
  request.body = saagen::load_call_store_body(catalogue, wrapper, request);
  ASSERT_EQ(request.input_stride, 7u);
  const auto spirv = saagen::compile_to_spirv(saagen::kernel_compile_request(catalogue, file.file_name, file.content, request));
  ASSERT_TRUE(spirv.ok) << spirv.log;

  const bool smoothness = std::string(c.domain) == "smoothness";
  const Batch batch = make_batch(smoothness);
  const std::vector<float> got = run(spirv.spirv, batch.inputs, request.workgroup_size);
  for (std::size_t i = 0; i < batch.ends; ++i) EXPECT_EQ(got[i], batch.exact[i]) << "end case " << i;

  const RoughnessDomain domain = reference_domain(c.domain);
  const ref::Params params{0.25, 1.0};
  double worst_ratio = 0.0;
  std::size_t failures = 0;
  for (std::size_t i = batch.ends; i < element_count; ++i) {
    const float* in = batch.inputs.data() + 7 * i;
    const Vec3 dx{in[1], in[2], in[3]}, dy{in[4], in[5], in[6]};
    const double alpha2 = ref::alpha2_from_domain(domain, in[0]);
    const double filtered =
        std::string(c.variant) == "deferred-sum" ? ref::deferred_sum(params, alpha2, dx, dy) : ref::deferred_avg(params, alpha2, dx, dy);
    const double expected = ref::domain_from_alpha2(domain, filtered);
    const double scale = smoothness ? 1.0 - expected : std::fabs(expected);
    const double bound = 2e-5 * scale + 0x1p-24;
    const double error = std::fabs(got[i] - expected);
    worst_ratio = std::max(worst_ratio, error / bound);
    if (error > bound && ++failures <= 5) ADD_FAILURE() << "element " << i << ": gpu " << got[i] << " reference " << expected;
  }
  std::printf("%s %s %s: worst error / bound %.3g\n", c.target, c.variant, c.domain, worst_ratio);
  EXPECT_EQ(failures, 0u);
}

INSTANTIATE_TEST_SUITE_P(Domains, DomainWrappersOnGpu,
                         ::testing::Values(DomainCase{"glsl", "alpha", "deferred-sum"}, DomainCase{"glsl", "perceptual", "deferred-sum"},
                                           DomainCase{"glsl", "smoothness", "deferred-sum"}, DomainCase{"hlsl", "alpha", "deferred-avg"},
                                           DomainCase{"hlsl", "perceptual", "deferred-avg"},
                                           DomainCase{"hlsl", "smoothness", "deferred-avg"}),
                         [](const auto& info) {
                           std::string name = std::string(info.param.target) + "_" + info.param.domain + "_" + info.param.variant;
                           for (char& ch : name) ch = ch == '-' ? '_' : ch;
                           return name;
                         });

// Each preset from a user shader with `#include <saagen/PRESET.glsl>`, compiled by shaderc
// through the handler and run on the device, against the engine's own formula (engine_forms.hpp)
// evaluated in float64 on the same fp32 inputs, within the bound of the file comment.
class PresetOnGpu : public ::testing::TestWithParam<std::string> {};

TEST_P(PresetOnGpu, IncludedThroughShadercMatchesTheEngine) {
  const saagen::Preset& preset = saagen::find_preset(GetParam());
  std::string function = "saa_" + preset.variant;
  for (char& ch : function) ch = ch == '-' ? '_' : ch;
  if (preset.domain != saagen::Domain::alpha2) function = saagen::domain_function_name(function, preset.domain);
  const auto compiled =
      saagen::test::compile_with_shaderc(saagen::test::glsl_user_shader("#include <saagen/" + preset.id + ".glsl>", function, false), false,
                                         std::make_unique<saagen::ShadercIncluder>());
  ASSERT_TRUE(compiled.ok) << compiled.log;
  const bool smoothness = preset.domain == saagen::Domain::smoothness;
  const Batch batch = make_batch(smoothness);
  const std::vector<float> got = run(compiled.spirv, batch.inputs, 64);
  const saagen::test::EngineForm engine = saagen::test::engine_forms().at(preset.id);
  double worst = 0.0;
  std::size_t failures = 0;
  for (std::size_t i = 0; i < element_count; ++i) {
    const float* in = batch.inputs.data() + 7 * i;
    const double expected = engine(in[0], {in[1], in[2], in[3]}, {in[4], in[5], in[6]});
    const double error = std::fabs(got[i] - expected);
    worst = std::max(worst, error);
    const double scale = smoothness ? 1.0 - expected : std::fabs(expected);
    if (error > 2e-5 * scale + 0x1p-24 && ++failures <= 5) ADD_FAILURE() << "element " << i << ": gpu " << got[i] << " engine " << expected;
  }
  std::printf("preset %s through shaderc on the device: max |difference| %.3g (%s)\n", preset.id.c_str(), worst,
              std::string(saagen::to_string(preset.domain)).c_str());
  EXPECT_EQ(failures, 0u);
}

INSTANTIATE_TEST_SUITE_P(Presets, PresetOnGpu, ::testing::Values("hdrp", "filament", "filament-taa", "o3de", "bevy", "vsgl"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& ch : name) ch = ch == '-' ? '_' : ch;
                           return name;
                         });

}  // namespace

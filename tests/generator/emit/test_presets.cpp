// Engine presets and roughness domains on the double-precision reference.
//
// Each preset (templates/engines.json) is checked against an independent float64 implementation
// of that engine's formula, written here from the engine's own math (not from the templates), in
// the engine's roughness domain, over >= 10^5 inputs; the largest |difference| is printed and
// recorded. saagen's side is the reference filter (reference/saa.cpp) with the preset's sigma^2,
// kappa and variant, wrapped in the reference's domain conversions.
#include "engine_forms.hpp"

#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/measure/engines.hpp"
#include "saagen/products/output_validation.hpp"
#include "saagen/products/spirv_library.hpp"
#include "saagen/reference/saa.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/validation.hpp"
#ifdef SAAGEN_TEST_WEBGPU_RUNNER
#include "saagen/harness/webgpu.hpp"
#endif

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <random>

namespace {

namespace ref = saagen::ref;
using ref::RoughnessDomain;
using ref::Vec3;
using saagen::test::engine_forms;
using saagen::test::EngineForm;

RoughnessDomain reference_domain(const std::string& id) {
  if (id == "alpha") return RoughnessDomain::alpha;
  if (id == "perceptual") return RoughnessDomain::perceptual;
  if (id == "smoothness") return RoughnessDomain::smoothness;
  return RoughnessDomain::alpha2;
}

// saagen's side: the preset's variant on the reference, in the preset's domain.
double saagen_preset(const saagen::Preset& preset, double value, Vec3 du, Vec3 dv) {
  const ref::Params params{preset.sigma2, preset.kappa};
  const RoughnessDomain domain = reference_domain(std::string(saagen::to_string(preset.domain)));
  const double alpha2 = ref::alpha2_from_domain(domain, value);
  double filtered = 0.0;
  if (preset.variant == "deferred-sum")
    filtered = ref::deferred_sum(params, alpha2, du, dv);
  else if (preset.variant == "deferred-avg")
    filtered = ref::deferred_avg(params, alpha2, du, dv);
  else
    ADD_FAILURE() << "no reference dispatch for " << preset.variant;
  return ref::domain_from_alpha2(domain, filtered);
}

// Inputs: the roughness uniform in [0, 1] with both ends, derivative magnitudes log-uniform over
// 1e-4..10 (the kernel below, at and above every cap), random directions.
struct Input {
  double value;
  Vec3 du, dv;
};

std::vector<Input> inputs(std::size_t count) {
  std::mt19937_64 random(20261124);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto direction = [&] {
    const double z = 2.0 * unit(random) - 1.0, phi = 6.283185307179586 * unit(random), r = std::sqrt(1.0 - z * z);
    return Vec3{r * std::cos(phi), r * std::sin(phi), z};
  };
  std::vector<Input> all;
  for (std::size_t index = 0; index < count; ++index) {
    const double value = index % 50 == 0 ? 0.0 : index % 50 == 1 ? 1.0 : unit(random);
    const double m1 = std::pow(10.0, -4.0 + 5.0 * unit(random)), m2 = std::pow(10.0, -4.0 + 5.0 * unit(random));
    all.push_back({value, m1 * direction(), m2 * direction()});
  }
  return all;
}

}  // namespace

// Every preset named in the issue exists and points at a catalogue variant and domain.
TEST(Presets, EveryEngineHasAPreset) {
  for (const char* id : {"hdrp", "filament", "filament-taa", "o3de", "bevy", "vsgl"}) {
    const saagen::Preset& preset = saagen::find_preset(id);
    EXPECT_EQ(saagen::find_domain(saagen::to_string(preset.domain)).kind, preset.domain) << id;
    EXPECT_TRUE(saagen::Catalogue::builtin().find_variant(preset.variant)) << id;
  }
  EXPECT_THROW(saagen::find_preset("unreal"), saagen::Error);
}

// Same operations up to the order of a few roundings: the difference is a few ulps of the
// result's scale (values in [0, 1]); r = a^(1/4) divides a relative error of a by 4. 1e-15 is
// 4.5 ulp of 1 (2^-52 = 2.2e-16), the tolerance shared/REFERENCES.md states the equivalences at.
TEST(Presets, MatchTheEnginesFormulasInTheirDomain) {
  const auto forms = engine_forms();
  const std::vector<Input> all = inputs(200000);
  for (const saagen::Preset& preset : saagen::presets()) {
    ASSERT_TRUE(forms.count(preset.id)) << "no engine form written for preset " << preset.id;
    const EngineForm& engine = forms.at(preset.id);
    double worst = 0.0;
    for (const Input& input : all) {
      const double difference = std::fabs(saagen_preset(preset, input.value, input.du, input.dv) - engine(input.value, input.du, input.dv));
      worst = std::max(worst, difference);
    }
    std::printf("preset %-13s max |difference| %.3g in %s over %zu inputs\n", preset.id.c_str(), worst,
                std::string(saagen::to_string(preset.domain)).c_str(), all.size());
    ::testing::Test::RecordProperty("max_difference_" + preset.id, std::to_string(worst));
    EXPECT_LE(worst, 1e-15) << preset.id;
  }
}

// The trade report's engine rows (measure/engines.cpp) and the presets carry the same
// constants: the rows equal the presets' filters in alpha^2 (same operations, a few ulps).
TEST(Presets, AgreeWithTheTradeReportsEngineRows) {
  const std::vector<Input> all = inputs(100000);
  const saagen::Preset& hdrp_preset = saagen::find_preset("hdrp");
  const saagen::Preset& filament_preset = saagen::find_preset("filament");
  for (const Input& input : all) {
    const double alpha = input.value;
    ASSERT_NEAR(saagen::measure::hdrp_alpha2(alpha, input.du, input.dv),
                ref::deferred_sum({hdrp_preset.sigma2, hdrp_preset.kappa}, alpha * alpha, input.du, input.dv), 4e-16);
    ASSERT_NEAR(saagen::measure::filament_alpha2(alpha, input.du, input.dv),
                ref::deferred_sum({filament_preset.sigma2, filament_preset.kappa}, alpha * alpha, input.du, input.dv), 4e-16);
  }
}

// The conversions at the ends of the range: 0 and 1 exactly, denormals, the saturation bound,
// and a round trip through alpha^2 that gives back the value when the kernel is 0.
TEST(Domains, ExactAtTheEndsOfTheRange) {
  for (RoughnessDomain domain : {RoughnessDomain::alpha, RoughnessDomain::perceptual, RoughnessDomain::smoothness}) {
    const bool smooth = domain == RoughnessDomain::smoothness;
    // Roughness 0 and 1 (smoothness 1 and 0) map to alpha^2 0 and 1 and back, exactly.
    EXPECT_EQ(ref::alpha2_from_domain(domain, smooth ? 1.0 : 0.0), 0.0);
    EXPECT_EQ(ref::alpha2_from_domain(domain, smooth ? 0.0 : 1.0), 1.0);
    EXPECT_EQ(ref::domain_from_alpha2(domain, 0.0), smooth ? 1.0 : 0.0);
    EXPECT_EQ(ref::domain_from_alpha2(domain, 1.0), smooth ? 0.0 : 1.0);
    // The saturation bound: a filter output of exactly 1 is roughness 1 (smoothness 0).
    const ref::Params params{0.25, 1.0};
    const Vec3 huge{10.0, 0.0, 0.0};
    EXPECT_EQ(ref::domain_from_alpha2(domain, ref::deferred_sum(params, ref::alpha2_from_domain(domain, 0.5), huge, huge)),
              smooth ? 0.0 : 1.0);
    // Denormal alpha^2 (below DBL_MIN): finite, in [0, 1], monotone with 0.
    const double denormal = std::numeric_limits<double>::denorm_min();
    const double converted = ref::domain_from_alpha2(domain, denormal);
    EXPECT_TRUE(std::isfinite(converted));
    EXPECT_GE(converted, 0.0);
    EXPECT_LE(converted, 1.0);
    // A denormal value in the domain goes to alpha^2 0 (it underflows), never below.
    EXPECT_EQ(ref::alpha2_from_domain(domain, smooth ? 1.0 - 0x1p-53 : denormal), smooth ? 0x1p-212 : 0.0);
  }
}

// With a zero kernel the wrapper returns its input: sqrt(fl(x^2)) = x for correctly rounded
// arithmetic (no underflow), so alpha and r round-trip exactly; smoothness goes through 1 - s,
// exact for s in [0.5, 1] (Sterbenz) and within half an ulp of 1 below.
TEST(Domains, RoundTripWithoutKernelIsExact) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(1e-60, 1.0);
  const Vec3 zero{0.0, 0.0, 0.0};
  const ref::Params params;
  for (int i = 0; i < 100000; ++i) {
    const double value = unit(random);
    for (RoughnessDomain domain : {RoughnessDomain::alpha, RoughnessDomain::perceptual}) {
      ASSERT_EQ(ref::domain_from_alpha2(domain, ref::deferred_avg(params, ref::alpha2_from_domain(domain, value), zero, zero)), value);
    }
    const double back = ref::domain_from_alpha2(
        RoughnessDomain::smoothness, ref::deferred_avg(params, ref::alpha2_from_domain(RoughnessDomain::smoothness, value), zero, zero));
    if (value >= 0.5)
      ASSERT_EQ(back, value);
    else
      ASSERT_LE(std::fabs(back - value), 0x1p-53);
  }
}

TEST(Domains, UnknownNamesAreOneLine) {
  try {
    saagen::find_domain("linear");
    FAIL();
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(), "--domain 'linear' is not a roughness domain; use one of alpha2, alpha, perceptual, smoothness");
  }
}

// Every variant with roughness in and out, in every domain and output: each source target (and
// each target's half precision in the perceptual domain) emitted and compiled in-process
// (glslang, spirv-val), and the SPIR-V libraries linked-module-validated. Printed as the domain x
// output matrix: the number of files that validated, per cell. The deferred pass takes the domain
// as a run-time flag (one module for all four), run in every domain on both drivers by
// DeferredPassOnGpu.RoughnessDomainsChannelsAndUnormEncodings; the libraries' domain wrappers run
// linked by DomainLibraryOnGpu.
TEST(Domains, EveryConvertibleVariantValidatesInEveryDomainAndOutput) {
#ifdef SAAGEN_TEST_WEBGPU_RUNNER
  saagen::harness::install_webgpu_runner();  // the WGSL outputs validate through it, as the CLI's do
#endif
  const saagen::Catalogue& catalogue = saagen::Catalogue::builtin();
  std::map<std::string, std::map<std::string, std::size_t>> validated;  // domain -> output -> files
  std::vector<std::string> outputs = saagen::builtin_target_names();
  outputs.push_back("spirv");
  for (const saagen::RoughnessDomain& domain : saagen::roughness_domains()) {
    for (const std::string& target : saagen::builtin_target_names()) {
      for (const auto& [precision, form] : saagen::builtin_target(target).precisions) {
        if (saagen::is_half(precision) && domain.id != "perceptual") continue;
        saagen::EmitOptions options;
        options.target = target;
        options.domain = domain.kind;
        options.precision = precision;
        // alpha^2 is every variant's own domain: there every variant a SPIR-V library can hold.
        if (domain.to_alpha2.empty()) options.variants = saagen::spirv_library_variants(catalogue, {});
        for (const saagen::EmittedFile& file : saagen::emit_variants(catalogue, options)) {
          const saagen::FileValidation validation = saagen::validate_file(catalogue, file.file_name, file.content);
          EXPECT_TRUE(validation.ok()) << validation.summary();
          validated[domain.id][target] += validation.ok();
        }
      }
    }
    saagen::EmitOptions options;
    options.domain = domain.kind;
    for (const saagen::SpirvLibrary& library : saagen::emit_spirv_libraries(catalogue, options)) {
      const std::string bytes(reinterpret_cast<const char*>(library.words.data()), library.words.size() * 4);
      const saagen::FileValidation validation = saagen::validate_spirv_or_pass_file(catalogue, library.file_name, bytes);
      EXPECT_TRUE(validation.ok()) << validation.summary();
      validated[domain.id]["spirv"] += validation.ok();
    }
  }
  std::string header = "domain      ";
  for (const std::string& output : outputs) header += fmt::format("{:>7}", output);
  std::printf("[ matrix   ] files validated per roughness domain and output\n[ matrix   ] %s\n", header.c_str());
  for (const auto& [domain, per_output] : validated) {
    std::string line = fmt::format("{:<12}", domain);
    for (const std::string& output : outputs) {
      const auto cell = per_output.find(output);
      const std::size_t count = cell == per_output.end() ? 0 : cell->second;
      EXPECT_GT(count, 0u) << domain << " x " << output;
      line += fmt::format("{:>7}", count);
    }
    std::printf("[ matrix   ] %s\n", line.c_str());
  }
  std::printf(
      "[ matrix   ] deferred pass: one module per variant takes the domain as a run-time flag (alpha2 0, alpha 1, perceptual 2, "
      "smoothness 3), run in all four on both drivers by DeferredPassOnGpu.RoughnessDomainsChannelsAndUnormEncodings\n");
  EXPECT_EQ(validated.size(), 4u);
}

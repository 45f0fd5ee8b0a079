// Every core and evaluate function of every variant, for every target, runs on a
// Vulkan device (lavapipe) over 131072 inputs -- a structured grid over h_z, roughness,
// derivative magnitude and direction, then seeded random draws -- and is compared element by
// element with the double-precision reference evaluated on the same (fp32-rounded) inputs.
//
// Error bound per output, |gpu - reference| <= 2e-5 * S + 1e-30, where S is a magnitude scale:
//  - filters (sums of products, min, saturate, sqrt of sums of squares, one division in the
//    projected-space form): S = max(|f(x)|, |f|(|x|)), the function evaluated on the absolute
//    values of its derivative inputs. Running error analysis bounds the rounding error of such
//    expressions by gamma_n * |f|(|x|) with gamma_n ~ n * 2^-24; n <= 12 here gives ~7e-7. The
//    bound allows 2e-5: Vulkan lets division be 2.5 ulp and sqrt inherit inversesqrt's 2 ulp.
//  - BRDFs: S = |f| * (1 + c) where c is the conditioning: the eigenvalue ratio of the
//    roughness matrix (the determinant and the adjugate's quadratic form cancel by up to that
//    factor; inputs keep it <= 100), plus the Beckmann exponent e (exp amplifies a relative
//    error of e by e). Smith Lambda is a difference (-0.5 + ..., or Walter's fit whose
//    numerator has roots near a = 1.55), so its scale is the sum of the magnitudes of its terms.
#include "support/core_cases.hpp"
#include "support/gpu_support.hpp"

#include <algorithm>

namespace {

namespace ref = saagen::ref;
using saagen::Catalogue;
using namespace saagen::test::core;

struct CoreCase {
  std::string target;
  std::string variant;
  std::string function;
};

void PrintTo(const CoreCase& c, std::ostream* os) { *os << c.target << " " << c.function; }

class CoreOnGpu : public ::testing::TestWithParam<CoreCase> {};

TEST_P(CoreOnGpu, MatchesTheDoublePrecisionReference) {
  const CoreCase& c = GetParam();
  const saagen::Function& function = *Catalogue::builtin().find_function(c.function);
  const ref::Params params;  // the emission defaults: sigma2 = 0.25, kappa = 0.18
  static const std::vector<Scenario> all_scenarios = scenarios();

  saagen::KernelRequest request;
  request.body = saagen::load_call_store_body(Catalogue::builtin(), c.function, request);
  const auto file = saagen::test::emit_variant(c.target, c.variant);

  std::vector<float> inputs;
  inputs.reserve(std::size_t{element_count} * request.input_stride);
  for (std::size_t index = 0; index < all_scenarios.size(); ++index) pack_inputs(function, all_scenarios[index], index, params, inputs);
  ASSERT_EQ(inputs.size(), std::size_t{element_count} * request.input_stride);

  saagen::harness::ComputeRun run;
  run.shader.spirv = saagen::test::compile_kernel(file, request);
  run.buffers = {saagen::harness::input_buffer(0, inputs),
                 saagen::harness::output_buffer<float>(1, std::size_t{element_count} * request.output_stride)};
  run.groups = {element_count / request.workgroup_size, 1, 1};
  const auto result = saagen::harness::run_compute(saagen::test::gpu(), run);
  const auto got = result.buffer_as<float>(1);

  const auto reference = reference_functions(params).at(c.function);
  std::vector<double> expected, bound;
  for (std::uint32_t element = 0; element < element_count; ++element) {
    Inputs value_inputs(inputs.data() + std::size_t{element} * request.input_stride);
    Inputs scale_inputs(inputs.data() + std::size_t{element} * request.input_stride);
    const auto values = reference.value(value_inputs);
    auto scales = reference.scale(scale_inputs);
    ASSERT_EQ(values.size(), request.output_stride);
    for (std::size_t k = 0; k < values.size(); ++k) {
      expected.push_back(values[k]);
      bound.push_back(rounding_bound * std::max(std::fabs(values[k]), scales[std::min(k, scales.size() - 1)]) + 1e-30);
    }
  }
  const std::string what = fmt::format("{} {} ({})", c.target, c.function, c.variant);
  const auto report = saagen::harness::compare_with_bounds(got, expected, bound, what);
  std::cout << "[ worst    ] " << report.summary() << "\n";
  EXPECT_EQ(report.failing, 0u) << report.summary();
}

std::vector<CoreCase> core_cases() {
  std::vector<CoreCase> cases;
  for (const std::string target : {"glsl", "hlsl"}) {
    for (const saagen::Variant& variant : Catalogue::builtin().variants()) {
      for (const std::string& name : variant.functions) {
        if (!Catalogue::builtin().find_function(name)->fragment_only) cases.push_back({target, variant.id, name});
      }
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryFunction, CoreOnGpu, ::testing::ValuesIn(core_cases()), [](const auto& info) {
  std::string name = info.param.target + "_" + info.param.variant + "_" + info.param.function;
  for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
});

}  // namespace

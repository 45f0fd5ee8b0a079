// The fragment wrappers with derivatives taken as a GPU takes them. Each wrapper runs
//  1. in a fragment shader over a full-screen triangle (real ddx/ddy of a 2x2 quad), and
//  2. in a compute shader that emulates the quads with subgroup quad operations (the emitted
//     wrapper unchanged, its derivative intrinsics redirected to quad operations), with plain
//     ddx meaning coarse and then fine;
// on an analytic scene: a sphere under a directional light seen by an orthographic camera,
// whose normal, tangent frame and tangent-space directions are computed per pixel. The shader
// writes those fp32 fields next to the wrapper's result; the reference is fed the same fp32
// fields as 2x2 quads and the same derivative mode, in double precision.
//
// Bound per output: 16 ulps * sum_k |df/dx_k| |x_k| + 2e-5 |f| + 1e-30, the first-order
// componentwise condition bound over every fp32 input field component x_k of the four pixels of
// the quad that the wrapper reads (partials by finite differences of the reference). The
// shader's roundings before the differences (normalize, the frame change, the slope division:
// about 8 ulps mapped back to its inputs) act like input perturbations, which the quad
// differences then amplify; 16 ulps is twice that. 2e-5 |f| is the rounding of the filter
// itself (test_gpu_core).
//
// Scene parameters are literals in the shader, not buffer loads: lavapipe clips the full-screen
// triangle to the viewport and splits it along the diagonal, so diagonal quads run with helper
#include "support/gpu_support.hpp"
#include "support/wrapper_cases.hpp"

#include "saagen/reference/reference.hpp"

#include <map>

namespace {

namespace ref = saagen::ref;
using ref::Quad;
using ref::Vec2;
using ref::Vec3;
using saagen::Catalogue;
using namespace saagen::test::wrappers;

// The kernels' input buffer is bound but unused.
const std::vector<float> scene_parameters = {0.0f};

saagen::harness::CompareReport check_against_reference(const std::string& wrapper, std::uint32_t outputs_per_pixel,
                                                       const std::vector<float>& out, ref::Derivative mode, const std::string& what) {
  const WrapperComparison comparison = reference_with_bounds(wrapper, outputs_per_pixel, out, mode);
  return saagen::harness::compare_with_bounds(comparison.got, comparison.expected, comparison.bound, what);
}

// How the device evaluates a plain ddx in a fragment shader: Vulkan allows coarse or fine.
ref::Derivative device_plain_derivative(const saagen::EmittedFile& file) {
  saagen::KernelRequest request;
  request.kind = saagen::KernelKind::fragment;
  request.width = width;
  request.output_stride = 1;
  request.body = "    SAAGEN_STORE(0, ddx(saagen_frag_coord.x * saagen_frag_coord.y));\n";
  saagen::harness::FragmentRun run;
  run.fragment.spirv = saagen::test::compile_kernel(file, request);
  run.width = width;
  run.height = height;
  run.buffers = {saagen::harness::input_buffer(0, scene_parameters), saagen::harness::output_buffer<float>(1, width * height)};
  const auto out = saagen::harness::run_fragment(saagen::test::gpu(), run).buffer_as<float>(1);
  // Bottom-left pixel of the first quad: fine gives its own row's y (1.5), coarse the top row's (0.5).
  return out[width] == 1.5f ? ref::Derivative::fine : ref::Derivative::coarse;
}

struct WrapperCase {
  std::string target;
  std::string variant;
  std::string wrapper;
};

void PrintTo(const WrapperCase& c, std::ostream* os) { *os << c.target << " " << c.wrapper; }

class WrapperOnGpu : public ::testing::TestWithParam<WrapperCase> {
 protected:
  saagen::KernelRequest request(saagen::KernelKind kind, const saagen::Function& wrapper) const {
    saagen::KernelRequest r;
    r.kind = kind;
    r.width = width;
    r.output_stride = stride;
    r.body = std::string(scene_body) + wrapper_call(wrapper);
    return r;
  }
  void expect_match(const saagen::harness::CompareReport& report) const {
    std::cout << "[ worst    ] " << report.summary() << "\n";
    EXPECT_EQ(report.failing, 0u) << report.summary();
  }
};

TEST_P(WrapperOnGpu, FragmentShaderMatchesReferenceOnQuadDifferences) {
  const WrapperCase& c = GetParam();
  const saagen::Function& wrapper = *Catalogue::builtin().find_function(c.wrapper);
  const auto file = saagen::test::emit_variant(c.target, c.variant);
  static const ref::Derivative mode = device_plain_derivative(saagen::test::emit_variant("glsl", "deferred-sum"));

  saagen::harness::FragmentRun run;
  run.fragment.spirv = saagen::test::compile_kernel(file, request(saagen::KernelKind::fragment, wrapper));
  run.width = width;
  run.height = height;
  run.buffers = {saagen::harness::input_buffer(0, scene_parameters),
                 saagen::harness::output_buffer<float>(1, std::size_t{width} * height * stride)};
  const auto out = saagen::harness::run_fragment(saagen::test::gpu(), run).buffer_as<float>(1);
  const auto report = check_against_reference(
      c.wrapper, saagen::component_count(wrapper.return_type), out, mode,
      fmt::format("{} {} fragment (plain ddx {})", c.target, c.wrapper, mode == ref::Derivative::fine ? "fine" : "coarse"));
  expect_match(report);
}

TEST_P(WrapperOnGpu, QuadEmulatingComputeMatchesReferenceForCoarseAndFine) {
  const WrapperCase& c = GetParam();
  const saagen::Function& wrapper = *Catalogue::builtin().find_function(c.wrapper);
  const auto file = saagen::test::emit_variant(c.target, c.variant);
  ASSERT_TRUE(saagen::test::gpu().info().subgroup.supports(VK_SUBGROUP_FEATURE_QUAD_BIT, VK_SHADER_STAGE_COMPUTE_BIT))
      << "the device has no subgroup quad operations in compute: " << saagen::test::gpu().info().subgroup.describe();
  for (const auto plain : {saagen::PlainDerivative::coarse, saagen::PlainDerivative::fine}) {
    auto kernel = request(saagen::KernelKind::quad_compute, wrapper);
    kernel.plain_derivative = plain;
    saagen::harness::ComputeRun run;
    run.shader.spirv = saagen::test::compile_kernel(file, kernel);
    run.buffers = {saagen::harness::input_buffer(0, scene_parameters),
                   saagen::harness::output_buffer<float>(1, std::size_t{width} * height * stride)};
    run.groups = {width * height / kernel.workgroup_size, 1, 1};
    const auto out = saagen::harness::run_compute(saagen::test::gpu(), run).buffer_as<float>(1);
    const bool fine = plain == saagen::PlainDerivative::fine;
    const auto report = check_against_reference(
        c.wrapper, saagen::component_count(wrapper.return_type), out, fine ? ref::Derivative::fine : ref::Derivative::coarse,
        fmt::format("{} {} quad compute (plain ddx {})", c.target, c.wrapper, fine ? "fine" : "coarse"));
    expect_match(report);
  }
}

std::vector<WrapperCase> wrapper_cases() {
  std::vector<WrapperCase> cases;
  for (const std::string target : {"glsl", "hlsl"}) {
    for (const saagen::Variant& variant : Catalogue::builtin().variants()) {
      for (const std::string& name : variant.functions) {
        if (Catalogue::builtin().find_function(name)->role == saagen::FunctionRole::fragment) cases.push_back({target, variant.id, name});
      }
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryWrapper, WrapperOnGpu, ::testing::ValuesIn(wrapper_cases()), [](const auto& info) {
  std::string name = info.param.target + "_" + info.param.wrapper;
  for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
});

}  // namespace

// Kernels compile for every function, target and kind: the GPU harness depends on
// them, and this suite needs no Vulkan device.
#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

namespace {

using saagen::Catalogue;

saagen::CompileResult compile_kernel(const saagen::EmittedFile& file, const saagen::KernelRequest& request, saagen::ShaderStage stage) {
  auto compile = saagen::kernel_compile_request(Catalogue::builtin(), file.file_name, file.content, request);
  compile.stage = stage;
  return saagen::compile_to_spirv(compile);
}

std::vector<saagen::EmittedFile> all_files(const std::string& target) {
  saagen::EmitOptions options;
  options.target = target;
  return saagen::emit_variants(Catalogue::builtin(), options);
}

// A body calling a fragment wrapper with every argument derived from the pixel centre.
std::string wrapper_body(const saagen::Function& function) {
  std::string arguments;
  for (const saagen::Parameter& parameter : function.parameters) {
    if (!arguments.empty()) arguments += ", ";
    const std::string seed = "(saagen_frag_coord.x * 0.01 + saagen_frag_coord.y * 0.02 + SAAGEN_LOAD(0))";
    // Every component listed: the dialect does not splat a scalar (HLSL cannot).
    std::vector<std::string> components(saagen::component_count(parameter.type), seed);
    arguments += parameter.type == "real" ? seed : parameter.type + "(" + fmt::format("{}", fmt::join(components, ", ")) + ")";
  }
  std::string body = "    " + function.return_type + " saagen_result = " + function.name + "(" + arguments + ");\n";
  body += "    SAAGEN_STORE(0, saagen_result" + std::string(function.return_type == "real" ? "" : ".x") + ");\n";
  return body;
}

class KernelsPerTarget : public ::testing::TestWithParam<std::string> {};

TEST_P(KernelsPerTarget, EveryCoreAndEvaluateFunctionRunsInACompute) {
  int compiled = 0;
  for (const auto& file : all_files(GetParam())) {
    for (const std::string& name : saagen::public_functions(Catalogue::builtin(), file.marker.variants)) {
      const saagen::Function& function = *Catalogue::builtin().find_function(name);
      if (function.fragment_only) continue;
      saagen::KernelRequest request;
      request.body = saagen::load_call_store_body(Catalogue::builtin(), name, request);
      EXPECT_EQ(request.input_stride, [&] {
        std::uint32_t floats = 0;
        for (const auto& parameter : function.parameters) floats += saagen::component_count(parameter.type);
        return floats;
      }());
      const auto result = compile_kernel(file, request, saagen::ShaderStage::compute);
      EXPECT_TRUE(result.ok) << file.file_name << " " << name << ":\n" << result.log;
      ++compiled;
    }
  }
  // 4 forward + 7 deferred cores, deferred-aniso's covariance and 6 lighting functions (with and
  // without the texture covariance, and the lobe split per pixel and per light), 14 GGX + 6
  // Beckmann evaluators, 4 + 5 prefilter cores.
  EXPECT_EQ(compiled, 47);
}

TEST_P(KernelsPerTarget, EveryFragmentWrapperRunsInAFragmentShaderAndUnderQuadEmulation) {
  for (const auto& file : all_files(GetParam())) {
    for (const std::string& name : saagen::public_functions(Catalogue::builtin(), file.marker.variants)) {
      const saagen::Function& function = *Catalogue::builtin().find_function(name);
      if (!function.fragment_only) continue;
      for (const auto plain : {saagen::PlainDerivative::coarse, saagen::PlainDerivative::fine}) {
        saagen::KernelRequest request;
        request.body = wrapper_body(function);
        request.output_stride = 1;
        request.width = 64;
        request.plain_derivative = plain;
        request.kind = saagen::KernelKind::quad_compute;
        const auto quad = compile_kernel(file, request, saagen::ShaderStage::compute);
        EXPECT_TRUE(quad.ok) << file.file_name << " " << name << " (quad compute):\n" << quad.log;
        request.kind = saagen::KernelKind::fragment;
        const auto fragment = compile_kernel(file, request, saagen::ShaderStage::fragment);
        EXPECT_TRUE(fragment.ok) << file.file_name << " " << name << " (fragment):\n" << fragment.log;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Targets, KernelsPerTarget, ::testing::Values("glsl", "hlsl"));

TEST(Kernels, RejectOddWidthsAndUnmarkedFiles) {
  const auto file = all_files("glsl").front();
  saagen::KernelRequest request;
  request.kind = saagen::KernelKind::fragment;
  request.width = 63;
  EXPECT_THROW(saagen::kernel_sources(Catalogue::builtin(), file.file_name, file.content, request), saagen::Error);
  request.width = 64;
  EXPECT_THROW(saagen::kernel_sources(Catalogue::builtin(), "x.glsl", "float f;", request), saagen::Error);
}

}  // namespace

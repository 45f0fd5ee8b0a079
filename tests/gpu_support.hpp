// Shared plumbing for the suites that run emitted code on a Vulkan device (lavapipe by default):
// one context per process, kernels compiled through saagen's own glslang path, and an
// element-wise comparison against the double-precision reference with per-element bounds.
#pragma once

#include "saagen/catalogue.hpp"
#include "saagen/emitter.hpp"
#include "saagen/kernels.hpp"

#include <saagen/harness/harness.hpp>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace saagen::test {

// One device for the whole test binary. Device selection follows SAAGEN_VK_DEVICE; with no
// device at all this throws, and the test fails (never skips: CI must have lavapipe).
inline harness::VulkanContext& gpu() {
  static harness::VulkanContext context;
  return context;
}

inline EmittedFile emit_variant(const std::string& target, const std::string& variant) {
  EmitOptions options;
  options.target = target;
  options.variants = {variant};
  return emit_variants(Catalogue::builtin(), options).front();
}

inline std::vector<std::uint32_t> compile_kernel(const EmittedFile& file, const KernelRequest& request) {
  CompileRequest compile;
  compile.language = file.marker.target == "hlsl" ? SourceLanguage::hlsl : SourceLanguage::glsl;
  compile.stage = request.kind == KernelKind::fragment ? ShaderStage::fragment : ShaderStage::compute;
  compile.sources = kernel_sources(Catalogue::builtin(), file.file_name, file.content, request);
  const CompileResult result = compile_to_spirv(compile);
  if (!result.ok) throw std::runtime_error(file.file_name + ": kernel does not compile:\n" + result.log);
  return result.spirv;
}

// Element-wise check |got - expected| <= bound[i]. The worst element is the one with the
// largest ratio error / bound; its relative error is reported too.
struct BoundReport {
  std::size_t compared = 0;
  std::size_t failing = 0;
  std::size_t worst_index = 0;
  double worst_ratio = 0.0;
  double worst_got = 0.0;
  double worst_expected = 0.0;
  double max_relative_error = 0.0;  // over elements with |expected| > 1e-30
  std::string summary(const std::string& what) const {
    return fmt::format("{}: {} compared, {} failing; worst error/bound {:.3g} at #{} (got {:.9g}, expected {:.9g}); "
                       "max relative error {:.3g}",
                       what, compared, failing, worst_ratio, worst_index, worst_got, worst_expected, max_relative_error);
  }
};

inline BoundReport compare_with_bounds(const std::vector<float>& got, const std::vector<double>& expected,
                                       const std::vector<double>& bound) {
  BoundReport report;
  report.compared = expected.size();
  for (std::size_t index = 0; index < expected.size(); ++index) {
    const double value = got[index];
    const double error = std::fabs(value - expected[index]);
    const bool finite_match = std::isfinite(value) && std::isfinite(expected[index]);
    const double ratio = finite_match ? error / bound[index] : (value == expected[index] ? 0.0 : INFINITY);
    if (!(ratio <= 1.0)) ++report.failing;
    if (!(ratio <= report.worst_ratio)) {
      report.worst_ratio = ratio;
      report.worst_index = index;
      report.worst_got = value;
      report.worst_expected = expected[index];
    }
    if (finite_match && std::fabs(expected[index]) > 1e-30) {
      report.max_relative_error = std::max(report.max_relative_error, error / std::fabs(expected[index]));
    }
  }
  return report;
}

}  // namespace saagen::test

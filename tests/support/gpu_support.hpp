// Shared plumbing for the suites that run emitted code on a Vulkan device (lavapipe by default):
// one context per process, kernels compiled through saagen's own glslang path, and an
// element-wise comparison against the double-precision reference with per-element bounds.
#pragma once

#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <saagen/harness/harness.hpp>
#include <string>
#include <vector>

namespace saagen::test {

// One device for the whole test binary. Device selection follows SAAGEN_VK_DEVICE; with no
// device at all this throws, and the test fails (never skips: CI must have lavapipe).
inline harness::VulkanContext& gpu() {
  static harness::VulkanContext context;
  return context;
}

inline EmittedFile emit_variant(const std::string& target, const std::string& variant, const std::string& precision = "fp32",
                                bool guards = true) {
  EmitOptions options;
  options.target = target;
  options.variants = {variant};
  options.precision = saagen::parse_precision(precision);
  options.guards = guards;
  return emit_variants(Catalogue::builtin(), options).front();
}

inline std::vector<std::uint32_t> compile_kernel(const EmittedFile& file, const KernelRequest& request) {
  const CompileResult result = compile_to_spirv(kernel_compile_request(Catalogue::builtin(), file.file_name, file.content, request));
  if (!result.ok) throw std::runtime_error(file.file_name + ": kernel does not compile:\n" + result.log);
  return result.spirv;
}

}  // namespace saagen::test

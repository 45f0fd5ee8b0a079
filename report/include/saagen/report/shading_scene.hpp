// The shading scene of the cost measurements: one fragment kernel per SAA variant that shades a
// bumpy sphere with the GGX specular term, filtered through the variant's fragment wrapper, and
// the same shading without SAA. bench_shading times it (lavapipe or any Vulkan device) and
// `saagen bench --isa` compiles it on RADV's null-hardware devices (isa_cost.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace saagen::report {

// A parameter of the scene, in input-buffer order: dialect type, name, value per component.
struct SceneParameter {
  const char* type;
  const char* name;
  std::vector<float> values;
};
std::vector<SceneParameter> scene_parameters(std::uint32_t width, std::uint32_t height);
// The input buffer: every parameter's components, then a sentinel 1.0.
std::vector<float> parameter_buffer(std::uint32_t width, std::uint32_t height);

// Baseline (no SAA): the unfiltered alpha^2 through the axis-aligned GGX BRDF.
extern const char* const baseline_shade;

// Paper, Table 2 (Tokuyoshi & Kaplanyan 2019): forward shading at 8K in ms, for Sponza, Bistro
// and San Miguel, without SAA; VariantCase::paper_ms holds the same with each variant.
extern const std::array<double, 3> paper_no_saa_ms;

struct VariantCase {
  std::string id;
  std::string shade;  // dialect statements defining `real value`
  std::optional<std::array<double, 3>> paper_ms;
};
const std::vector<VariantCase>& variant_cases();
// The catalogue variant whose emitted file defines a case's wrapper: the id before a lobe suffix
// ("deferred-avg/tail" -> "deferred-avg"; the lobe's BRDF comes from brdf-ggx, always included).
std::string catalogue_variant(const VariantCase& variant);

// The kernel body (template dialect) shading with `shade` on a width x height framebuffer.
std::string body_with(const std::string& shade, std::uint32_t width, std::uint32_t height);

// The scene's fragment kernel for `target` (glsl, hlsl): the emitted `content` (named file_name)
// with `body`, compiled and optimized (spirv-opt -O, as shipped). Throws saagen::Error.
std::vector<std::uint32_t> scene_shader_spirv(const std::string& target, const std::string& file_name, const std::string& content,
                                              const std::string& body, std::uint32_t width);

// The deferred roughness-limiter pass's baseline, GLSL and HLSL: the passes' interface
// (deferred_pass_abi), the roughness copied; bench_deferred_pass times it, `saagen bench --isa`
// compiles it.
extern const char* const deferred_copy_glsl;
extern const char* const deferred_copy_hlsl;

}  // namespace saagen::report

// The shading scene of the cost measurements: one fragment kernel per SAA variant that shades a
// bumpy sphere with the GGX specular term, filtered through the variant's fragment wrapper, and
// the same shading without SAA. bench_shading times it (lavapipe or any Vulkan device) and
// `saagen bench --isa` compiles it on RADV's null-hardware devices (isa_cost.hpp).
//
// With N lights the kernel shades N directional lights and stores the sum of their BRDF values:
// a forward form filters each light's half vector and evaluates its lobe per light (N x (filter
// + BRDF)); a deferred form computes its roughness (or deferred-aniso's tensor) once per pixel,
// as its G-buffer side does, then evaluates its lobe per light (once + N x lobe); no SAA is N x
// the unfiltered BRDF. The per-pixel scene (ray, sphere, bumps, tangent frame) is paid once.
#pragma once

#include "saagen/scene/cost_tables.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen::report {

// A parameter of the scene, in input-buffer order: dialect type, name, value per component.
struct SceneParameter {
  const char* type;
  std::string name;
  std::vector<float> values;
};

// The most lights the scene shades: as many as a manifest's `lights` takes.
inline constexpr std::uint32_t kMaxSceneLights = static_cast<std::uint32_t>(kMaxLights);
// The light counts `saagen bench --isa` measures every configuration at.
inline constexpr std::array<std::uint32_t, 3> kMeasuredLightCounts = {1, 4, 16};
// Throws saagen::Error unless 1 <= lights <= kMaxSceneLights.
void check_light_count(std::uint32_t lights);

// The one-light parameters, then light_direction_1 ... light_direction_{lights-1} (distinct unit
// directions in front of the sphere), so the one-light offsets never move.
std::vector<SceneParameter> scene_parameters(std::uint32_t width, std::uint32_t height, std::uint32_t lights = 1);
// The input buffer: every parameter's components, then a sentinel 1.0.
std::vector<float> parameter_buffer(std::uint32_t width, std::uint32_t height, std::uint32_t lights = 1);

// How a kernel shades, in dialect statements: `per_pixel` once per pixel (a deferred form's
// G-buffer-side roughness `filtered` or tensor `tensor`; empty for forward forms and no SAA),
// then `per_light` for each light, defining `real value` from light_ws, i_ts, half_ts (that
// light's direction in world and tangent space, its half vector) and what per_pixel defined.
// `one_light`, where it is not empty, replaces both at one light: a deferred form's tail-preserving
// lobe in one pass, which the plan names there (its split per pixel and per light computes the
// same value, and the plan names it from 4 lights on; generator/scene/planner.cpp).
struct SceneShading {
  std::string per_pixel;
  std::string per_light;
  std::string one_light = {};
};

// A deferred form's shading after `filtered` (statements defining `real filtered`, its one alpha^2
// per pixel): per light the papers' GGX of it, or with `tail` saagen's tail-preserving lobe, its
// light-independent part (ggx_filtered_lobe_isotropic) once per pixel as a deferred lighting pass
// computes it, and at one light the lobe in one pass (ggx_brdf_filtered_axis).
SceneShading deferred_lobe_shading(const std::string& filtered, bool tail);

// Baseline (no SAA): the unfiltered alpha^2 through the axis-aligned GGX BRDF.
extern const SceneShading baseline_shading;

// Paper, Table 2 (Tokuyoshi & Kaplanyan 2019): forward shading at 8K in ms, for Sponza, Bistro
// and San Miguel, without SAA; VariantCase::paper_ms holds the same with each variant.
extern const std::array<double, 3> paper_no_saa_ms;

struct VariantCase {
  std::string id;
  SceneShading shading;
  std::optional<std::array<double, 3>> paper_ms;
};
const std::vector<VariantCase>& variant_cases();
// The catalogue variant whose emitted file defines a case's wrapper: the id before a lobe suffix
// ("deferred-avg/tail" -> "deferred-avg"; the lobe's BRDF comes from brdf-ggx, always included),
// without the transported wrappers' "-transported" ("forward-aniso-projected-transported/tail" ->
// "forward-aniso-projected").
std::string catalogue_variant(const VariantCase& variant);

// The kernel body (template dialect) shading `lights` lights with `shading` on a width x height
// framebuffer. The one-light body is the scene every committed one-light figure was measured on
// (per_pixel + per_light after the light's statements); with more lights each light is shaded in
// a block of its own and the kernel stores their sum.
std::string body_with(const SceneShading& shading, std::uint32_t width, std::uint32_t height, std::uint32_t lights = 1);

// The scene's fragment kernel for `target` (glsl, hlsl): the emitted `content` (named file_name)
// with `body`, compiled and optimized (spirv-opt -O, as shipped). Throws saagen::Error.
std::vector<std::uint32_t> scene_shader_spirv(const std::string& target, const std::string& file_name, const std::string& content,
                                              const std::string& body, std::uint32_t width);

// The deferred roughness-limiter pass's baseline written in target `target`: the section
// "baseline" of its deferred pass skeleton (targets/<language>/deferred_pass.*), the passes'
// interface (deferred_pass_abi) with the roughness copied; bench_deferred_pass times it, `saagen
// bench --isa` compiles it. Throws saagen::Error for a target without a deferred pass.
const char* deferred_copy_source(std::string_view target);

}  // namespace saagen::report

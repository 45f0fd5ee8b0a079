// The glint functions on the web backends (test_wgsl: WebGPU on Dawn for Node; test_webgl: WebGL2
// in headless Chromium), both on SwiftShader's Vulkan: the cases, the dictionary as the runners
// upload it, and the comparison with the double-precision reference of glint_support.hpp (the
// inputs, reference and fp32 / transcendental / cos-sin bounds of the Vulkan proofs in
// test_glints_gpu).
//
// The dictionary is a 2D array texture one texel high (neither API has 1D array textures; the
// emitted WGSL and GLSL ES sample it at v = 0.5), RGBA16F with its MIP chain, linear mag, min and
// mipmap filters, mirror-repeat addressing: the half bits of glints::dictionary_texture, exactly
// what the reference's software sampler reads. With gradients (g, 0) and (h, 0) and a height of
// one texel, a 2D image's LOD rules reduce to the 1D ones the reference implements: rho_max =
// max(|g|, |h|) width, and f_x <= sqrt(2) (|m_ux| + |m_vx|) = sqrt(2) |m_ux| (Vulkan 1.3, "Scale
// Factor Operation, Level-of-Detail Operation and Image Level(s) Selection"; GLSL ES 3.00 and
// OpenGL ES 3.0 section 3.8.10 allow the same approximation of rho).
//
// The sampler's precision: neither WebGPU nor WebGL2 states one; both run here on Vulkan (Dawn's
// Vulkan backend, ANGLE's), whose every implementation must report mipmapPrecisionBits >= 4 and
// subTexelPrecisionBits >= 4 (Vulkan 1.3, "Required Limits"). The bound takes those least
// values (lambda within 1/16 below and 1/2 + 1/16 above log2 rho, level weights and texel
// coordinates to 1/16), so that it holds for any Vulkan device under the browser, not only for
// the SwiftShader that runs it.
//
// The shader arithmetic: WGSL's accuracy table (section 15.7.4) is Vulkan's, so the fp32 and
// transcendental terms of glint_support.hpp apply to WebGPU as they are. GLSL ES 3.00 highp
// (section 4.5.1) gives log2 / exp2 / division / inversesqrt the same bounds, but leaves sin and
// cos with "undefined precision"; ANGLE compiles the shader to SPIR-V for Vulkan, whose 2^-11 in
// [-pi, pi] is the allowance taken (the same as WGSL's).
#pragma once

#include "glint_support.hpp"
#include "web_support.hpp"

#include "saagen/front/catalogue.hpp"
#include "saagen/products/glints.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace saagen::test::web_glints {

namespace g = saagen::ref::glints;

// Elements per core function: the first 4096 of test_glints_gpu's 16384 scenarios (every one of
// their patterns, which repeat with period 8 at most, is among them).
constexpr std::size_t elements = 4096;
// The wrappers' target, as test_glints_gpu's: 64 x 64 pixels.
constexpr std::uint32_t side = 64;
// The texture file the runners upload (WebGPU's format name; the WebGL2 runner maps it to RGBA16F).
constexpr const char* dictionary_file = "glint_dictionary.rgba16float";

inline const g::SamplerTolerance& sampler_tolerance() {
  static const g::SamplerTolerance tolerance = g::vulkan_sampler_tolerance(4, 4);
  return tolerance;
}

struct Case {
  std::string id;
  bool wrapper = false;
  std::string variant;
  std::string function;                                // core functions
  std::vector<std::string> wrappers;                   // wrappers: the fragment functions the body calls, one output each
  ref::Derivative derivative = ref::Derivative::fine;  // wrappers: what plain derivatives are taken as
};

// The body that calls a variant's wrappers (glint_support.hpp), in the order of their outputs.
inline std::vector<std::string> wrappers_of(const std::string& variant) {
  if (variant == "glints-ggaa") return {"glint_brdf_filtered_fragment", "glint_brdf_filtered_slope_fragment"};
  if (variant == "glints") return {"glint_brdf_fragment"};
  throw std::runtime_error("no wrapper body for the glint variant " + variant);
}

inline const char* wrapper_body(const std::string& variant) {
  return variant == "glints-ggaa" ? glint::wrapper_body : glint::baseline_wrapper_body;
}

// Every public glint function: each core one once (`core_prefix` + name), and each variant's
// wrappers together in one fragment case per derivative form (`prefix` + variant).
inline std::vector<Case> cases(const std::string& core_prefix, const std::vector<std::pair<std::string, ref::Derivative>>& wrapper_forms) {
  std::vector<Case> result;
  std::set<std::string> seen;
  for (const std::string variant : {"glints", "glints-ggaa"}) {
    const saagen::Variant& entry = *glints::catalogue().find_variant(variant);
    std::set<std::string> wrappers;
    for (const std::string& name : entry.functions) {
      const saagen::Function& function = *glints::catalogue().find_function(name);
      if (function.role == saagen::FunctionRole::fragment) {
        wrappers.insert(name);
      } else if (!function.fragment_only && seen.insert(name).second) {
        result.push_back({core_prefix + name, false, variant, name, {}, ref::Derivative::fine});
      }
    }
    const std::vector<std::string> body = wrappers_of(variant);
    if (wrappers != std::set<std::string>(body.begin(), body.end())) {
      throw std::runtime_error("the glint wrapper body of " + variant + " does not call every wrapper of the variant");
    }
    std::string id = variant;
    for (char& c : id) c = c == '-' ? '_' : c;
    for (const auto& [prefix, derivative] : wrapper_forms) result.push_back({prefix + id, true, variant, "", body, derivative});
  }
  return result;
}

// Writes the default dictionary's texture to `directory` (raw half texels, level after level,
// layer after layer) and returns its description for the runners' "texture" field.
inline nlohmann::json write_dictionary(const std::filesystem::path& directory) {
  const glints::DictionaryTexture& texture = default_texture();
  std::ofstream out(directory / dictionary_file, std::ios::binary);
  for (const auto& level : texture.levels) {
    out.write(reinterpret_cast<const char*>(level.data()), static_cast<std::streamsize>(level.size() * sizeof(std::uint16_t)));
  }
  return {{"file", dictionary_file},        {"format", "rgba16float"},         {"width", texture.width}, {"height", 1},
          {"layers", texture.layers},       {"levels", texture.levels.size()}, {"filter", "linear"},     {"mipmap_filter", "linear"},
          {"address_mode", "mirror-repeat"}};
}

// The reference of a case, over the outputs in the runner's order (element- or pixel-major).
inline glint::Comparison comparison(const Case& c, const std::vector<float>& inputs, std::size_t input_stride, ref::Derivative derivative) {
  if (c.wrapper) return glint::fragment_comparison(c.variant == "glints-ggaa", side, side, derivative, sampler_tolerance());
  return glint::core_comparison(c.function, {}, inputs, elements, input_stride, sampler_tolerance());
}

// One result line per function of the case: its outputs (`got`, `stride` per element or pixel,
// the function's first at `offset`) against the specification interval.
struct FunctionResult {
  std::string function;
  Worst worst;
  std::size_t nonzero = 0;
};

inline std::vector<FunctionResult> compare(const Case& c, const std::vector<float>& got, std::size_t got_stride,
                                           const glint::Comparison& reference) {
  const std::vector<std::string> functions = c.wrapper ? c.wrappers : std::vector<std::string>{c.function};
  const std::size_t outputs = reference.spec_expected.size() / (c.wrapper ? std::size_t{side} * side : elements);
  std::vector<FunctionResult> results;
  for (const std::string& function : functions) results.push_back({function, {}, 0});
  for (std::size_t k = 0; k < reference.spec_expected.size(); ++k) {
    const std::size_t element = k / outputs, output = k % outputs;
    FunctionResult& result = results[c.wrapper ? output : 0];
    result.worst.add(got.at(element * got_stride + output), reference.spec_expected[k], reference.spec_bounds[k]);
    result.nonzero += reference.expected[k] != 0.0;
  }
  return results;
}

}  // namespace saagen::test::web_glints

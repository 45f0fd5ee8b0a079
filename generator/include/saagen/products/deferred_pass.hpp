// The deferred roughness-limiter compute pass: complete, ready-to-dispatch compute
// shaders that read a normal G-buffer (and a tangent G-buffer for the tangent-frame forms) and
// a roughness G-buffer, and write the roughness filtered by one deferred variant's fragment
// wrapper -- the templates' Eq. 1 / 4 / 5 / Listing 3 / projected-space math, unchanged.
//
// One pass per fragment wrapper of the deferred variants (pass ids: deferred-previous,
// deferred-max, deferred-max-tangent-free, deferred-sum, deferred-avg, deferred-projected-space),
// emitted as GLSL 4.50 (`.comp`), HLSL (`.hlsl`, SM 6.0 wave intrinsics), SPIR-V 1.3 (`.spv`,
// compiled from the GLSL) and a C/C++ header (`.h`) that describes bindings and push constants
// and embeds the SPIR-V words. The shader is the emitted variant file plus the `deferred_pass`
// skeleton of the target table (targets/*.json) plus a body in the template dialect.
//
// Derivatives: a compute shader has no ddx/ddy, so lanes form 2x2 pixel quads (Vulkan's quad:
// four consecutive subgroup invocations) and the wrapper's derivative intrinsics are redirected
// to subgroup quad operations, exactly as in the quad-emulating kernels:
//   fine   ddx at (x, y) = v(x | 1, y) - v(x & ~1, y), ddy = v(x, y | 1) - v(x, y & ~1);
//   coarse one difference per quad, from the top-left pixel's row and column.
// The template's explicit ddx_fine/ddy_fine are always fine; `derivatives` chooses what plain
// ddx/ddy mean (fine by default, as on lavapipe and most desktop GPUs). This is
// ref::Derivative::fine / coarse of the CPU reference on the quads (x & ~1, y & ~1).
//
// Borders: a workgroup covers an 8 x 8 tile; lanes past the right or bottom edge (partial tiles,
// odd sizes) read the nearest edge texel (clamped coordinates) and write nothing. With an odd
// width the last column's quad partner is therefore a copy of it: ddx = 0 there (likewise ddy on
// the last row of an odd height). Frag coordinates stay the lane's own (x + 0.5, y + 0.5).
#pragma once

#include "saagen/front/catalogue.hpp"
#include "saagen/validate/kernels.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

// The resource interface shared by every pass (descriptor set 0).
namespace deferred_pass_abi {
inline constexpr std::uint32_t binding_normal = 0;     // sampled image: .xyz normal
inline constexpr std::uint32_t binding_roughness = 1;  // sampled image: roughness in channel roughness_channel
inline constexpr std::uint32_t binding_output = 2;     // storage image (r32f or r16f): filtered roughness
inline constexpr std::uint32_t binding_tangent = 3;    // sampled image: .xyz tangent, .w bitangent sign (tangent passes only)
inline constexpr std::uint32_t tile_size = 8;          // a workgroup covers tile_size x tile_size pixels
inline constexpr std::uint32_t local_size = 64;        // local_size_x; y = z = 1
// Push-constant flags: bits 0-1 the roughness domain, then the encodings.
inline constexpr std::uint32_t domain_alpha2 = 0;       // the G-buffer holds alpha^2
inline constexpr std::uint32_t domain_alpha = 1;        // alpha (GGX/Beckmann width)
inline constexpr std::uint32_t domain_perceptual = 2;   // perceptual roughness r, alpha = r^2
inline constexpr std::uint32_t domain_smoothness = 3;   // perceptual smoothness s = 1 - r (the order of roughness_domains())
inline constexpr std::uint32_t flag_normal_unorm = 4;   // normal stored as n * 0.5 + 0.5
inline constexpr std::uint32_t flag_tangent_unorm = 8;  // tangent .xyz stored as t * 0.5 + 0.5
}  // namespace deferred_pass_abi

// The push constants (16 bytes, compute stage), as laid out in every pass.
struct DeferredPassConstants {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t roughness_channel = 0;  // 0..3: r, g, b, a
  std::uint32_t flags = 0;              // domain | flag_*
};

struct DeferredPassKind {
  std::string id;         // deferred-sum
  std::string variant;    // the catalogue variant: deferred-sum (deferred-max for deferred-max-tangent-free)
  std::string wrapper;    // the fragment wrapper it runs: deferred_sum_fragment
  bool tangents = false;  // reads the tangent G-buffer (binding 3)
};

// Every pass the catalogue defines: one per fragment wrapper of a deferred variant, in order.
std::vector<DeferredPassKind> deferred_pass_kinds(const Catalogue& catalogue);

struct DeferredPassOptions {
  std::vector<std::string> passes;  // pass ids; empty: all
  std::string prefix = "saa_";
  std::map<std::string, double> option_values;  // sigma2, kappa
  bool guards = true;
  PlainDerivative derivatives = PlainDerivative::fine;
  std::string output_format = "r32f";  // storage image format of the output: r32f or r16f
};

// The complete compute shader of a pass in one target's language (<stem><deferred_pass_extension>).
struct DeferredPassSource {
  std::string target;     // the target table it is written in: glsl (GLSL 4.50, Vulkan), hlsl (HLSL, entry main)
  std::string file_name;  // saa_pass_deferred_sum.comp
  std::string text;
};

struct DeferredPass {
  DeferredPassKind kind;
  std::string stem;                         // saa_pass_deferred_sum
  std::vector<DeferredPassSource> sources;  // one per target with a deferred pass skeleton, in the targets' order
  std::vector<std::uint32_t> spirv;         // compiled from the spirv_library_source target's source, with the marker as OpModuleProcessed
  std::string header;                       // C/C++: bindings, push constants, dispatch, the SPIR-V words

  // The pass written in target `target`; throws saagen::Error when it has none.
  const std::string& source(std::string_view target) const;
  // (file name, bytes) of the outputs: the sources (<stem>.comp, <stem>.hlsl), <stem>.spv, <stem>.h.
  std::vector<std::pair<std::string, std::string>> files() const;
};

// Throws saagen::Error on an unknown pass id, a bad option, or a shader that does not compile
// (both the GLSL and the HLSL are compiled and spirv-validated).
std::vector<DeferredPass> emit_deferred_passes(const Catalogue& catalogue, const DeferredPassOptions& options);

}  // namespace saagen

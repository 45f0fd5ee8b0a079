// saagen as a shader-compiler plugin: `#include <saagen/...>` resolved to a snippet generated in
// memory. The name grammar (documented in examples/INTEGRATION.md):
//
//   saagen/<id>.<ext>[?<key>=<value>(&<key>=<value>)*]
//
//   <id>   a variant id (deferred-avg) or a preset id (hdrp: the engine's variant, sigma^2,
//          kappa and roughness domain)
//   <ext>  glsl, essl (gles) or hlsl: the target
//   keys   prefix, sigma2, kappa, preset, domain, precision (fp32, fp16, min16), guards (on, off)
//
// e.g. #include <saagen/deferred-avg.glsl?domain=perceptual&kappa=0.1>. glslang (and shaderc,
// which runs it) take any character but '>' and a newline in a <...> name, and any but '"' in a
// "..." one. Options given to a handler's constructor apply to every include; the name's win.
// A bad name or option is one line, the CLI's message after the name, reported by the compiler
// as its include failure.
#pragma once

#include "saagen/emit/emitter.hpp"

#include <optional>
#include <string>
#include <string_view>

namespace saagen {

struct IncludeOptions {
  std::string prefix = "saa_";
  std::optional<double> sigma2;
  std::optional<double> kappa;
  std::optional<std::string> preset;
  std::optional<std::string> domain;
  Precision precision = Precision::fp32;
  bool guards = true;
};

// True for names the handlers resolve: those starting with "saagen/".
bool is_saagen_include(std::string_view name);

// The include's emission options: `defaults` with the name's variant or preset and query applied.
// Throws saagen::Error "<name>: <what>; <what to do>".
EmitOptions include_emit_options(std::string_view name, const IncludeOptions& defaults);

// The emitted file an include name stands for (its content is the included text). Throws
// saagen::Error as include_emit_options does.
EmittedFile resolve_include(std::string_view name, const IncludeOptions& defaults);

}  // namespace saagen

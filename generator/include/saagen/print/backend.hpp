// One backend per source language: what the generator does differently per language beyond the
// language's syntax tables (targets/*.json): the printer of function bodies, the glslang front end
// that compiles it in process, and so how an emitted file of it is validated. Code outside the
// backends asks language_backend(language) rather than comparing languages.
#pragma once

#include "saagen/front/syntax_tree.hpp"
#include "saagen/target/language.hpp"

#include <optional>
#include <string>

namespace saagen {

// How glslang compiles a language in process (saagen/validate/compiler.hpp).
struct GlslangFrontEnd {
  bool hlsl = false;                // glslang's HLSL front end (else its GLSL one)
  int default_version = 450;        // the version of a source without a #version line
  bool named_entry_points = false;  // the entry function may have any name (GLSL's is always main)
};

// Prints a function body or glue from the typed tree in the target's language.
using BodyPrinter = std::string (*)(const dialect::Body& body, const TargetSyntax& target, const dialect::PrintOptions& options);

struct LanguageBackend {
  SourceLanguage language;
  BodyPrinter print_body;
  // Set for a language glslang compiles to SPIR-V, whose emitted files are validated in process
  // (glslang and spirv-val); empty for one that Tint validates through the WebGPU runner (WGSL).
  std::optional<GlslangFrontEnd> glslang;

  bool compiled_in_process() const { return glslang.has_value(); }
  // The front end; throws saagen::Error when glslang does not compile the language.
  const GlslangFrontEnd& front_end() const;
};

const LanguageBackend& language_backend(SourceLanguage language);

}  // namespace saagen

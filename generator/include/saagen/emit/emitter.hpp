// Emission: turns catalogue entries into self-contained include files for one target.
#pragma once

#include "saagen/front/catalogue.hpp"
#include "saagen/io/marker.hpp"
#include "saagen/target/target.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace saagen {

// The version written into every emitted file.
std::string_view version();

struct EmitOptions {
  OutputTarget target = OutputTarget::snippet("glsl");  // a table's snippets (emit_variants, emit_bundle) or spirv
  std::vector<std::string> variants;                    // empty: every variant
  std::string prefix = "saa_";
  std::map<std::string, double> option_values;  // e.g. {"sigma2", 0.25}; missing: the default
  Precision precision = Precision::fp32;        // a precision of the target table: fp32, fp16, min16 (HLSL)
  bool guards = true;                           // false: the unguarded paper form (for comparison)
  // Roughness domain of the emitted functions' roughness in and out (saagen/emit/engines.hpp):
  // alpha2 (the templates' own), alpha, perceptual or smoothness.
  Domain domain = Domain::alpha2;
  // A module language (WGSL) only: the module path that Bevy's shader imports (naga_oil) give the
  // file, written as `#define_import_path PATH`; empty: none (a plain WGSL module).
  std::string import_path{};
};

struct EmittedFile {
  std::string file_name;  // e.g. saa_deferred_sum.glsl
  std::string content;
  EmissionMarker marker;
};

// Throws saagen::Error unless `prefix` is a safe identifier prefix: [A-Za-z][A-Za-z0-9_]*,
// at most 32 characters, no "__", not starting with "gl_".
void validate_prefix(std::string_view prefix);

// Throws saagen::Error unless `path` is a naga_oil module path: identifiers joined by "::", at
// most 128 characters (EmitOptions::import_path).
void validate_import_path(std::string_view path);

// Resolves option values against the catalogue (defaults, range checks); throws saagen::Error
// naming the option and its allowed interval.
std::map<std::string, double> resolve_options(const Catalogue& catalogue, const std::map<std::string, double>& given);

// What a preset or explicit options ask for, checked and resolved the same way for the CLI,
// manifests, the include handlers and the C API. Explicit values win over the preset's.
struct EmitSettings {
  std::optional<std::string> preset;
  std::vector<std::string> variants;
  std::optional<double> sigma2;
  std::optional<double> kappa;
  std::optional<std::string> domain;
};
// Fills options.variants, option_values and domain from `settings`; throws saagen::Error (one
// line naming the option) for an unknown preset or domain, or a variant that has no roughness
// in and out under a domain other than alpha2.
void apply_settings(const Catalogue& catalogue, const EmitSettings& settings, EmitOptions& options);

// One file per requested variant, in catalogue order. Validates every input before emitting.
std::vector<EmittedFile> emit_variants(const Catalogue& catalogue, const EmitOptions& options);

// A bundle: one file holding exactly the dependency closure of the
// given public functions, drawn from several variants, with the same header, guards, marker
// and CORE_ONLY conventions as a per-variant file. File: <prefix><name>[_<precision>].<ext>.
struct BundleRequest {
  std::string name;                    // the file name's stem after the prefix, e.g. "scene"
  std::vector<std::string> functions;  // public functions: the roots of the closure
  std::vector<std::string> variants;   // the variants they come from (header and marker)
  std::vector<std::string> notes;      // header comment lines (what each material calls)
};
// Uses options.target, prefix, option_values, precision and guards (not options.variants).
EmittedFile emit_bundle(const Catalogue& catalogue, const EmitOptions& options, const BundleRequest& request);

// Public functions of the given variants, in order, without duplicates.
std::vector<std::string> public_functions(const Catalogue& catalogue, const std::vector<std::string>& variant_ids);

// The name an unprefixed template name gets in emitted code.
std::string prefixed_name(std::string_view prefix, std::string_view name);
// Macro spelling of the prefix: upper case ("saa_" -> "SAA_").
std::string macro_prefix(std::string_view prefix);

}  // namespace saagen

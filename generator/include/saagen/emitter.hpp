// Emission: turns catalogue entries into self-contained include files for one target.
#pragma once

#include "saagen/catalogue.hpp"
#include "saagen/target.hpp"

#include <map>
#include <string>
#include <vector>

namespace saagen {

// The version written into every emitted file.
std::string_view version();

struct EmitOptions {
  std::string target = "glsl";
  std::vector<std::string> variants;  // empty: every variant
  std::string prefix = "saa_";
  std::map<std::string, double> option_values;  // e.g. {"sigma2", 0.25}; missing: the default
};

// What one emitted file holds, as written in its marker line, so that a file on disk can be
// validated (and recognised as saagen's) without the options that produced it.
struct EmissionMarker {
  std::string target;
  std::vector<std::string> variants;
  std::string prefix;
  std::map<std::string, double> option_values;
};

struct EmittedFile {
  std::string file_name;  // e.g. saa_deferred_sum.glsl
  std::string content;
  EmissionMarker marker;
};

// Throws saagen::Error unless `prefix` is a safe identifier prefix: [A-Za-z][A-Za-z0-9_]*,
// at most 32 characters, no "__", not starting with "gl_".
void validate_prefix(std::string_view prefix);

// Resolves option values against the catalogue (defaults, range checks); throws saagen::Error
// naming the option and its allowed interval.
std::map<std::string, double> resolve_options(const Catalogue& catalogue, const std::map<std::string, double>& given);

// One file per requested variant, in catalogue order. Validates every input before emitting.
std::vector<EmittedFile> emit_variants(const Catalogue& catalogue, const EmitOptions& options);

// The marker line written into every emitted file, and its parser (nullopt when the text holds
// no marker: the file was not written by saagen).
std::string marker_line(const EmissionMarker& marker);
std::optional<EmissionMarker> find_marker(std::string_view content);

// Public functions of the given variants, in order, without duplicates.
std::vector<std::string> public_functions(const Catalogue& catalogue, const std::vector<std::string>& variant_ids);

// The name an unprefixed template name gets in emitted code.
std::string prefixed_name(std::string_view prefix, std::string_view name);
// Macro spelling of the prefix: upper case ("saa_" -> "SAA_").
std::string macro_prefix(std::string_view prefix);

}  // namespace saagen

// SPIR-V for users who cannot #include: linkable library modules and C/C++ headers
// that embed SPIR-V words.
//
// A library module holds one variant's core and evaluate functions (the GLSL emission compiled
// by glslang under <PREFIX>CORE_ONLY) with the Linkage capability, no entry point, and
// `OpDecorate %f LinkageAttributes "<emitted name>" Export` on every public function that takes
// no screen-space derivatives. Helpers stay internal (no linkage), so two libraries that share a
// helper link together. brdf-ggx and brdf-beckmann both export ndf_clamp_tau: they link together
// too, but a consumer that imports that name must link only one of them (the import would be
// ambiguous and the SPIRV-Tools linker refuses it).
//
// glslang cannot emit linkage from source, so the module is post-processed with SPIRV-Tools only:
// disassemble, edit the text (add the capability and decorations, drop the entry point and the
// `main` that called every function), assemble with the numeric ids preserved, then remove what
// only `main` used with the optimizer's dead-code passes, which keep exported functions.
//
// Calling convention (glslang's, and therefore the module's): every parameter is an
// OpTypePointer Function to its value type, the result is returned by value. A consumer's
// OpFunction declarations with `LinkageAttributes "<name>" Import` must use exactly these types;
// import_stub_functions() turns stub definitions compiled by glslang into such declarations.
#pragma once

#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/validate/compiler.hpp"
#include "saagen/validate/validation.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

// One function a library exports.
struct SpirvExport {
  std::string name;           // the linkage name: the emitted (prefixed) name, e.g. saa_deferred_sum
  std::string template_name;  // deferred_sum
  std::uint32_t id = 0;       // the OpFunction's result id in the module
  std::string spirv_type;     // e.g. "f32(ptr<Function, f32>, ptr<Function, vec3<f32>>, ...)"
};

struct SpirvLibrary {
  std::string file_name;    // saa_deferred_sum.spv
  std::string header_name;  // saa_deferred_sum.spv.h
  EmissionMarker marker;    // target "spirv", the variant, prefix, options, precision, guards
  std::vector<std::uint32_t> words;
  std::vector<SpirvExport> exports;
  nlohmann::json reflection;  // exported functions as in `saagen list --json`, plus their SPIR-V types
};

// One library per requested variant (options.variants; empty: every variant a module can hold,
// see spirv_library_variants, and in a roughness domain other than alpha2 those with a roughness
// in and out), in catalogue order. options.target is ignored (the GLSL emission is compiled);
// precision, guards, prefix, option values and the domain apply: in another domain the exports
// are the domain's wrappers, as `emit --domain` names them. Throws saagen::Error when a step
// fails (with the tool's message).
std::vector<SpirvLibrary> emit_spirv_libraries(const Catalogue& catalogue, const EmitOptions& options);

// The C/C++ header of a library: include guard, the marker line as a comment, the words as a
// `constexpr uint32_t` array (`static const` in C) with their count, and the reflection JSON as
// a string constant. Deterministic.
std::string spirv_library_header(const Catalogue& catalogue, const SpirvLibrary& library);

// Validates a library module: spirv-val with the universal SPIR-V 1.3 rules (Vulkan's rules
// reject the Linkage capability itself), the Linkage capability, no entry point, and an Export
// decoration for every name in `exports`. Empty string when valid, else the problems.
std::string validate_spirv_library(const std::vector<std::uint32_t>& words, const std::vector<std::string>& exports);

// Rewrites a module compiled by glslang so that its definitions of the named functions (matched
// by glslang's OpName "name(" + mangling) become declarations with
// `LinkageAttributes "name" Import`: bodies removed, declarations moved before every definition,
// the Linkage capability added. Throws saagen::Error when a name has no unique definition.
std::vector<std::uint32_t> import_stub_functions(const std::vector<std::uint32_t>& words, const std::vector<std::string>& names);

// GLSL stub definitions (bodies returning zero) of the given template functions under `prefix`,
// for a consumer shader compiled before import_stub_functions(). Types follow `precision`.
std::string glsl_import_stubs(const Catalogue& catalogue, const std::vector<std::string>& functions, std::string_view prefix,
                              Precision precision = Precision::fp32);

// Adds `OpModuleProcessed "<text>"` to a module (disassemble, insert, assemble with the ids
// preserved). Used to carry the saagen marker line (text ends with '\n') in binary outputs.
std::vector<std::uint32_t> add_module_processed(const std::vector<std::uint32_t>& words, std::string_view text);

// Adds `OpSourceExtension "<text>"` (valid in every SPIR-V version, ignored by drivers): how
// `saagen compile` tags its outputs as saagen's.
std::vector<std::uint32_t> add_source_extension(const std::vector<std::uint32_t>& words, std::string_view text);

// SPIR-V text of a module (spirv-dis, numeric ids), and back (spirv-as, numeric ids preserved).
// Throw saagen::Error with the tool's message on failure.
std::string disassemble_spirv(const std::vector<std::uint32_t>& words);
std::vector<std::uint32_t> assemble_spirv(const std::string& text);

// Little-endian bytes of the words (the .spv file), and back (throws unless the size is a
// multiple of 4 and the magic number is SPIR-V's).
std::string spirv_file_bytes(const std::vector<std::uint32_t>& words);
std::vector<std::uint32_t> spirv_words_from_bytes(std::string_view bytes);

// `<name>[] = { 0x07230203u, ... }` lines for a C/C++ header: 6 words per line, each line
// indented by two spaces.
std::string spirv_c_initializer(const std::vector<std::uint32_t>& words);
// `"..."` string literal lines holding `text` (quotes, backslashes and control characters
// escaped), one literal per line of text, for C and C++.
std::string c_string_literal_lines(std::string_view text);

// The variants `saagen emit --target spirv` puts in library modules: `named`, or every variant
// when empty, less those that read a resource (the glint dictionary), which a module cannot leave
// for its consumer to declare; naming one of those throws saagen::Error. Unknown ids are kept,
// for the emitter's own message.
std::vector<std::string> spirv_library_variants(const Catalogue& catalogue, const std::vector<std::string>& named);

}  // namespace saagen

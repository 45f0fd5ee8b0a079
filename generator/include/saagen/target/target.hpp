// Target syntax tables (targets/*.json): how the dialect's types, intrinsics and constant
// declarations are spelt in one target language, and the shader skeletons used to validate an
// emitted file. One table per target; no per-target copy of any formula.
#pragma once

#include "saagen/precision.hpp"
#include "saagen/target/language.hpp"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

struct ValidationSkeleton {
  std::string prologue;  // before the emitted file ({core_only_macro} is substituted)
  std::string epilogue;  // after it; {calls} receives one statement per function
};

// How the target spells a precision it can emit: type spellings that replace the defaults, a suffix for
// floating-point literals ("hf" for GLSL float16_t), a preamble (an #extension line), and
// whether the HLSL front end must enable native 16-bit types.
struct PrecisionForm {
  std::map<std::string, std::string, std::less<>> types;
  std::map<std::string, std::string, std::less<>> intrinsics;  // overrides; may use {prefix}
  std::string literal_suffix;
  std::string preamble;
  bool native_16bit = false;
  // Optional overrides of TargetSyntax::declaration_types, function_prologue and intrinsic_notes.
  std::map<std::string, std::string, std::less<>> declaration_types;
  std::optional<std::string> function_prologue;
  std::map<std::string, std::string, std::less<>> intrinsic_notes;
};

// How an emitted file is laid out (key "file_form": an object, or a section file under targets/
// holding one section per key; targets/preprocessor/include_file.txt for the C preprocessor
// languages). Placeholders: {guard} (a macro name), {core_only} (the <PREFIX>CORE_ONLY macro),
// {meaning} and {declaration} (a constant's comment and declaration), {path} (an import path).
struct FileForm {
  std::string definitions_open;     // before the file's definitions (an include guard)
  std::string definitions_close;    // after them
  std::string constant;             // one constant
  std::string function_open;        // before one function's comment and definition
  std::string function_close;       // after it
  std::string fragment_only_open;   // around function_open..function_close of a [fragment] function
  std::string fragment_only_close;  //
  std::string body_open;            // between a function's signature and its body
  std::string stage_note;           // header lines: how stages without derivatives use the file
  std::string import_path;          // optional: the import-path line; empty: the language has none
};

struct TargetSyntax {
  std::string name;
  std::string description;
  std::string file_extension;
  SourceLanguage language = SourceLanguage::named("glsl");
  std::map<std::string, std::string, std::less<>> types;
  // dialect intrinsic -> pattern with {0}, {1}, ... for the arguments
  std::map<std::string, std::string, std::less<>> intrinsics;
  std::string constant_declaration;  // with {type}, {name}, {value}
  // A function's signature and one parameter (keys "signature" and "parameter"; the C form by
  // default): {result} {name}({parameters}) and {type} {name}.
  std::string signature = "{result} {name}({parameters})";
  std::string parameter = "{type} {name}";
  // Key "module": the file is a self-contained module of a language without a preprocessor
  // (WGSL): no include guards, no CORE_ONLY macro; the language checks per entry point that
  // fragment-only functions are reached from fragment entry points only.
  bool module = false;
  FileForm file_form;
  // Optional (key "resources_after_file"): validation and kernel skeletons declare the resources
  // after the emitted file (a module opens with its enable directives) instead of before it.
  bool resources_after_file = false;
  // Optional (key "spirv_library_source"): the SPIR-V library modules are compiled from this
  // target's emission (spirv_library_target()).
  bool spirv_library_source = false;
  // Optional (key "deferred_pass"): the deferred pass skeleton's sections (prologue, resources,
  // tangent_resources, main, and baseline: the copy pass `saagen bench --isa` measures the passes
  // against); empty when the target has no deferred pass.
  std::map<std::string, std::string, std::less<>> deferred_pass;
  // With deferred_pass (key "deferred_pass_extension", required there): the pass file's extension
  // (".comp" for GLSL, as glslang names a compute shader by it).
  std::string deferred_pass_extension;

  // Files of this target are #included by other shaders (include guards, CORE_ONLY); false for a
  // self-contained module language (key "module": WGSL).
  bool has_includes() const { return !module; }
  // Resources are passed as parameters to the functions that read them (Resource::parameters)
  // instead of being named through the includer's declaration.
  bool passes_resources() const { return module; }
  // A body that assigns a parameter copies it into a local first (immutable parameters).
  bool copies_assigned_parameters() const { return module; }
  // An import path (FileForm::import_path) can be written into a file.
  bool takes_import_path() const { return !file_form.import_path.empty(); }
  // glslang compiles the target in process (it has validation clients); a language validated by
  // the WebGPU implementation (Tint) has none.
  bool compiled_in_process() const { return !validation_clients.empty(); }
  // Key "reserved_words": words a template local or parameter may not be called in this language
  // (keywords, reserved words, built-ins the printer emits); the printer appends '_' to such a name.
  std::vector<std::string> reserved_words;
  // Optional (key "declaration_types"): the spelling of a type where it declares something
  // (parameters, return types, constants) when it differs from a constructor's, as in GLSL ES,
  // where a declaration carries a precision qualifier ("highp float") and a constructor cannot.
  std::map<std::string, std::string, std::less<>> declaration_types;
  // Optional: statements opening every emitted function body (GLSL ES default-precision
  // statements, which are scoped to the body and so leave the includer's defaults alone).
  std::string function_prologue;
  // Optional (key "intrinsic_notes"): a note for the header of every file one of whose functions
  // uses the intrinsic (how the target approximates what it lacks).
  std::map<std::string, std::string, std::less<>> intrinsic_notes;
  std::vector<ClientApi> validation_clients;
  // The stage that validates the file under <PREFIX>CORE_ONLY (key "core_stage"; compute unless
  // the target has no compute shaders).
  ShaderStage core_validation_stage = ShaderStage::compute;
  ValidationSkeleton fragment_skeleton;
  ValidationSkeleton compute_skeleton;
  // Skeletons that run emitted functions over buffers ("compute", "quad_compute",
  // "fragment"); see saagen/validate/kernels.hpp.
  std::map<std::string, ValidationSkeleton, std::less<>> kernel_skeletons;
  std::map<Precision, PrecisionForm> precisions;  // fp32 (the default), fp16, ...
  // Resources that some templates sample (optional key "resources"; the glint dictionary of
  // templates/glints/): the intrinsics that read one, and the declaration that validation and
  // kernel skeletons put before an emitted file whose functions use them ({macro_prefix} is
  // substituted by with_prefix). Emitted files never declare resources: the includer does.
  // In a module language (WGSL), a resource is passed, not named by a macro: "parameters" are
  // appended to every function that reads it directly or through a callee, "arguments" to every
  // call of such a function inside the file, and "caller_arguments" (the declaration's names) to
  // the calls of the validation and kernel glue.
  struct Resource {
    std::vector<std::string> intrinsics;
    std::string declaration;
    std::string parameters;
    std::string arguments;
    std::string caller_arguments;
  };
  std::map<std::string, Resource, std::less<>> resources;
  // Optional (key "glue_names"): how the skeletons spell the names glue calls (saagen/print/glue.hpp)
  // where they differ from the glue's: a language without macros defines functions instead.
  std::map<std::string, std::string, std::less<>> glue_names;

  // This target with the types, literal suffix and preamble of `precision`; throws
  // saagen::Error naming the precisions the target has when it has no such precision.
  TargetSyntax with_precision(Precision precision) const;
  // The precisions the table defines, fp32 first.
  std::vector<Precision> precision_kinds() const;
  // Replaces {prefix} and {macro_prefix} in the intrinsic patterns and the preamble (precision
  // helpers are emitted under the emission's prefix).
  TargetSyntax with_prefix(std::string_view prefix, std::string_view macro_prefix) const;
  // The declaration spelling of a dialect type (declaration_types, else types).
  const std::string& declaration_type(const std::string& dialect_type) const;
  // The fp32 spellings of the dialect types, whatever the precision (intrinsic patterns of a
  // narrower precision widen with {wide_type}; set by parse).
  std::map<std::string, std::string, std::less<>> wide_types;
  std::string literal_suffix;  // set by with_precision
  std::string preamble;        // set by with_precision
  bool native_16bit = false;   // set by with_precision

  // Parses one table; throws saagen::Error naming `source_name` on a missing or wrong key.
  static TargetSyntax parse(std::string_view json_text, std::string_view source_name);
};

// The sections of a skeleton source file under targets/ (e.g. "glsl/validate_fragment.glsl"):
// a line "// saagen-section: NAME" starts section NAME, which holds the lines up to the next
// such line; text before the first one is the file's own comment. Throws saagen::Error naming
// `source` (the table that names the file) when the file is not embedded in this build.
std::map<std::string, std::string, std::less<>> skeleton_sections(std::string_view file, std::string_view source);

// The tables compiled into this build, by name ("glsl", "hlsl").
const TargetSyntax& builtin_target(std::string_view name);
const TargetSyntax* find_builtin_target(std::string_view name);  // null when there is no such table
std::vector<std::string> builtin_target_names();
// The built-in table the SPIR-V library modules are compiled from (key "spirv_library_source");
// throws saagen::Error unless exactly one table has it.
const TargetSyntax& spirv_library_target();
// The built-in tables with a deferred pass skeleton, in name order.
std::vector<const TargetSyntax*> deferred_pass_targets();
// The built-in tables that compile for Vulkan in process (a "vulkan" validation client), in name
// order: what ISA statistics and the glint validation measure.
std::vector<const TargetSyntax*> vulkan_targets();
// The language of a shader file with extension `extension` (".hlsl"): the language of the
// built-in table whose files carry it, GLSL for any other extension (.vert, .frag, .comp).
SourceLanguage source_language_of_extension(std::string_view extension);

// Maps unprefixed template names (functions, constants) to the names they get in the output.
using NameMap = std::map<std::string, std::string, std::less<>>;

// An intrinsic's pattern (the tables' "intrinsics": "mix({0}, {1}, {2})") with {N} replaced by
// arguments[N]; throws saagen::Error when the pattern names an argument that is not there.
std::string expand_pattern(const std::string& pattern, const std::vector<std::string>& arguments);

// `text` with every `key` replaced by `value`: the placeholders of patterns and skeletons.
std::string substitute(std::string text, std::string_view key, std::string_view value);
// {real}, {real2}, {real3} and {real4} replaced by the target's spellings of those types (the
// skeletons of a precision declare their glue in it).
std::string substitute_type_placeholders(std::string text, const TargetSyntax& target);

// Appends `suffix` to every floating-point literal in `code` (numbers with '.' or an exponent);
// comments are left alone. Used for half-precision literals (1.0hf).
std::string suffix_float_literals(std::string_view code, std::string_view suffix);

}  // namespace saagen

#include "saagen/target/target.hpp"

#include "table_keys.hpp"

#include "saagen/error.hpp"
#include "saagen/front/dialect.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>

namespace saagen {
namespace embedded {
const std::map<std::string, std::string_view>& files();
}

namespace {

using Json = nlohmann::json;

const Json& require(const Json& object, const char* key, std::string_view source) {
  return table_keys::require(object, key, source, "target");
}

std::string require_string(const Json& object, const char* key, std::string_view source) {
  return table_keys::require_string(object, key, source, "target");
}

// A skeleton is either inline ({"prologue": ..., "epilogue": ...}) or, readable, the name of a
// source file under targets/ whose sections hold the two parts (see skeleton_sections).
ValidationSkeleton parse_skeleton(const Json& value, std::string_view source) {
  if (value.is_string()) {
    const auto sections = skeleton_sections(value.get<std::string>(), source);
    const auto section = [&](const char* name) {
      const auto found = sections.find(name);
      if (found == sections.end()) throw Error(fmt::format("{}: skeleton {} has no section '{}'", source, value.get<std::string>(), name));
      return found->second;
    };
    return {section("prologue"), section("epilogue")};
  }
  return {require_string(value, "prologue", source), require_string(value, "epilogue", source)};
}

// The sections of a value that is either an object of strings or the name of a section file
// under targets/ (skeleton_sections); every key of `required` must be there.
std::map<std::string, std::string, std::less<>> parse_sections(const Json& value, const char* key, std::vector<const char*> required,
                                                               std::vector<const char*> optional, std::string_view source) {
  std::map<std::string, std::string, std::less<>> sections;
  if (value.is_string()) {
    sections = skeleton_sections(value.get<std::string>(), source);
  } else if (value.is_object()) {
    for (const auto& [name, text] : value.items()) {
      if (!text.is_string()) throw Error(fmt::format("{}: '{}.{}' must be a string", source, key, name));
      sections[name] = text.get<std::string>();
    }
  } else {
    throw Error(fmt::format("{}: '{}' must be an object of strings or the name of a section file under targets/", source, key));
  }
  for (const char* name : required) {
    if (!sections.count(name)) throw Error(fmt::format("{}: '{}' needs a section '{}'", source, key, name));
  }
  for (const auto& section : sections) {
    const std::string& name = section.first;  // not a structured binding: clang 14 cannot capture one
    const auto known = [&](const std::vector<const char*>& names) {
      return std::any_of(names.begin(), names.end(), [&](const char* known_name) { return name == known_name; });
    };
    if (!known(required) && !known(optional)) throw Error(fmt::format("{}: '{}' has an unknown section '{}'", source, key, name));
  }
  return sections;
}

FileForm parse_file_form(const Json& value, std::string_view source) {
  auto sections = parse_sections(value, "file_form",
                                 {"definitions_open", "definitions_close", "constant", "function_open", "function_close",
                                  "fragment_only_open", "fragment_only_close", "body_open", "stage_note"},
                                 {"import_path"}, source);
  return {sections["definitions_open"],    sections["definitions_close"], sections["constant"],
          sections["function_open"],       sections["function_close"],    sections["fragment_only_open"],
          sections["fragment_only_close"], sections["body_open"],         sections["stage_note"],
          sections["import_path"]};
}

ClientApi parse_client(const std::string& name, std::string_view source) {
  if (name == "vulkan") return ClientApi::vulkan;
  if (name == "opengl") return ClientApi::opengl;
  if (name == "opengl_es") return ClientApi::opengl_es;
  throw Error(fmt::format("{}: validation client '{}' is not vulkan, opengl or opengl_es", source, name));
}

ShaderStage parse_core_stage(const Json& validation, std::string_view source) {
  if (!validation.contains("core_stage")) return ShaderStage::compute;
  const std::string name = require_string(validation, "core_stage", source);
  if (name == "compute") return ShaderStage::compute;
  if (name == "vertex") return ShaderStage::vertex;
  throw Error(fmt::format("{}: validation core_stage '{}' is not compute or vertex", source, name));
}

// Reads the optional "intrinsic_notes": intrinsic -> note text.
void read_notes(const Json& object, std::map<std::string, std::string, std::less<>>& out, std::string_view source) {
  if (!object.contains("intrinsic_notes")) return;
  for (const auto& [intrinsic, note] : object.at("intrinsic_notes").items()) {
    if (!note.is_string()) throw Error(fmt::format("{}: 'intrinsic_notes.{}' must be a string", source, intrinsic));
    out[intrinsic] = note.get<std::string>();
  }
}

// Reads an optional object of strings keyed by dialect type; every key must be a known type.
void read_type_spellings(const Json& object, const char* key, const std::map<std::string, std::string, std::less<>>& known,
                         std::map<std::string, std::string, std::less<>>& out, std::string_view source) {
  if (!object.contains(key)) return;
  for (const auto& [type, spelling] : object.at(key).items()) {
    if (!known.count(type)) throw Error(fmt::format("{}: '{}' spells unknown type '{}'", source, key, type));
    if (!spelling.is_string()) throw Error(fmt::format("{}: '{}.{}' must be a string", source, key, type));
    out[type] = spelling.get<std::string>();
  }
}

}  // namespace

std::map<std::string, std::string, std::less<>> skeleton_sections(std::string_view file, std::string_view source) {
  static constexpr std::string_view marker = "// saagen-section: ";
  const std::string path = "targets/" + std::string(file);
  const auto& files = embedded::files();
  const auto found = files.find(path);
  if (found == files.end())
    throw Error(fmt::format("{}: skeleton file {} is not in this build; add it under targets/ and rebuild", source, path));
  std::map<std::string, std::string, std::less<>> sections;
  std::string* current = nullptr;  // the text before the first marker is the file's own comment
  const std::string_view text = found->second;
  for (std::size_t begin = 0; begin < text.size();) {
    auto end = text.find('\n', begin);
    end = end == std::string_view::npos ? text.size() : end + 1;
    const std::string_view line = text.substr(begin, end - begin);
    if (line.starts_with(marker)) {
      std::string name(line.substr(marker.size()));
      while (!name.empty() && (name.back() == '\n' || name.back() == '\r' || name.back() == ' ')) name.pop_back();
      if (sections.count(name)) throw Error(fmt::format("{}: section '{}' appears twice", path, name));
      current = &sections[name];
    } else if (current) {
      *current += line;
    }
    begin = end;
  }
  return sections;
}

namespace {

// One entry of a target's "precisions": its type spellings (of types the target spells), intrinsic
// patterns, literal suffix, preamble (inline or from a skeleton file's section) and notes.
PrecisionForm parse_precision_form(const Json& entry, const std::string& name,
                                   const std::map<std::string, std::string, std::less<>>& target_types, std::string_view source) {
  PrecisionForm precision;
  for (const auto& [type, spelling] : require(entry, "types", source).items()) {
    if (!target_types.count(type)) throw Error(fmt::format("{}: precision {} spells unknown type '{}'", source, name, type));
    precision.types[type] = spelling.get<std::string>();
  }
  for (const auto& [intrinsic, pattern] : require(entry, "intrinsics", source).items()) {
    precision.intrinsics[intrinsic] = pattern.get<std::string>();
  }
  precision.literal_suffix = require_string(entry, "literal_suffix", source);
  if (entry.contains("preamble_file")) {
    const auto sections = skeleton_sections(require_string(entry, "preamble_file", source), source);
    if (!sections.count("preamble")) throw Error(fmt::format("{}: the preamble file of {} has no section 'preamble'", source, name));
    precision.preamble = sections.at("preamble");
  } else {
    precision.preamble = require_string(entry, "preamble", source);
  }
  precision.native_16bit = entry.value("native_16bit", false);
  read_type_spellings(entry, "declaration_types", target_types, precision.declaration_types, source);
  if (entry.contains("function_prologue")) precision.function_prologue = require_string(entry, "function_prologue", source);
  read_notes(entry, precision.intrinsic_notes, source);
  return precision;
}

// One entry of a target's "resources"; a module target's also needs the parameters and arguments
// it is passed through.
TargetSyntax::Resource parse_resource(const Json& entry, const std::string& name, bool module, std::string_view source) {
  TargetSyntax::Resource resource;
  for (const Json& intrinsic : require(entry, "intrinsics", source)) resource.intrinsics.push_back(intrinsic.get<std::string>());
  resource.declaration = require_string(entry, "declaration", source);
  resource.parameters = entry.value("parameters", "");
  resource.arguments = entry.value("arguments", "");
  resource.caller_arguments = entry.value("caller_arguments", "");
  if (module && (resource.parameters.empty() || resource.arguments.empty() || resource.caller_arguments.empty())) {
    throw Error(fmt::format("{}: resource {} of a module target needs 'parameters', 'arguments' and 'caller_arguments'", source, name));
  }
  return resource;
}

// The target's name, description, file extension, language and whether it is a module.
void read_identity(const Json& json, TargetSyntax& target, std::string_view source) {
  target.name = require_string(json, "name", source);
  target.description = require_string(json, "description", source);
  target.file_extension = require_string(json, "file_extension", source);
  const std::string language = require_string(json, "language", source);
  const auto parsed_language = source_language(language);
  if (!parsed_language) {
    throw Error(fmt::format("{}: language '{}' has no table targets/{}/language.json in this build; the languages are {}", source, language,
                            language, fmt::join(language_names(), ", ")));
  }
  target.language = *parsed_language;
  target.module = json.value("module", false);
}

// How the dialect is spelled: signatures, reserved words, types (every dialect type), intrinsics,
// constants, declaration types, the function prologue and the intrinsics' notes.
void read_spellings(const Json& json, TargetSyntax& target, std::string_view source) {
  if (json.contains("signature")) target.signature = require_string(json, "signature", source);
  if (json.contains("parameter")) target.parameter = require_string(json, "parameter", source);
  if (json.contains("reserved_words")) {
    for (const Json& word : json.at("reserved_words")) target.reserved_words.push_back(word.get<std::string>());
  }
  for (const auto& [key, value] : require(json, "types", source).items()) target.types[key] = value.get<std::string>();
  for (const std::string& type : dialect::type_names()) {
    if (!target.types.count(type)) throw Error(fmt::format("{}: 'types' has no spelling for dialect type '{}'", source, type));
  }
  target.wide_types = target.types;
  for (const auto& [key, value] : require(json, "intrinsics", source).items()) target.intrinsics[key] = value.get<std::string>();
  target.constant_declaration = require_string(json, "constant_declaration", source);
  read_type_spellings(json, "declaration_types", target.types, target.declaration_types, source);
  if (json.contains("function_prologue")) target.function_prologue = require_string(json, "function_prologue", source);
  read_notes(json, target.intrinsic_notes, source);
}

// The emitted file's form (an include guard unless a module) and the deferred pass's sections.
void read_file_forms(const Json& json, TargetSyntax& target, std::string_view source) {
  target.file_form = parse_file_form(require(json, "file_form", source), source);
  if (!target.module && target.file_form.definitions_open.empty()) {
    throw Error(fmt::format("{}: a target with includes needs an include guard ('file_form.definitions_open')", source));
  }
  target.resources_after_file = json.value("resources_after_file", false);
  target.spirv_library_source = json.value("spirv_library_source", false);
  if (json.contains("deferred_pass")) {
    target.deferred_pass = parse_sections(json.at("deferred_pass"), "deferred_pass",
                                          {"prologue", "resources", "tangent_resources", "main", "baseline"}, {}, source);
    target.deferred_pass_extension = require_string(json, "deferred_pass_extension", source);
  }
}

// How an emitted file is validated: the core stage, the clients and the skeletons it is compiled in.
void read_validation(const Json& json, TargetSyntax& target, std::string_view source) {
  const Json& validation = require(json, "validation", source);
  target.core_validation_stage = parse_core_stage(validation, source);
  for (const Json& client : require(validation, "clients", source)) {
    target.validation_clients.push_back(parse_client(client.get<std::string>(), source));
  }
  target.fragment_skeleton = parse_skeleton(require(validation, "fragment", source), source);
  target.compute_skeleton = parse_skeleton(require(validation, "compute", source), source);
  for (const auto& [kind, skeleton] : require(json, "kernels", source).items()) {
    target.kernel_skeletons[kind] = parse_skeleton(skeleton, source);
  }
}

// The precisions the target emits (fp32 required), its glue names and its resources.
void read_precisions_and_resources(const Json& json, TargetSyntax& target, std::string_view source) {
  for (const auto& [name, entry] : require(json, "precisions", source).items()) {
    const auto kind = precision_named(name);
    if (!kind) throw Error(fmt::format("{}: unknown precision '{}' in 'precisions'; use one of {}", source, name, precision_id_list()));
    target.precisions[*kind] = parse_precision_form(entry, name, target.types, source);
  }
  if (!target.precisions.count(Precision::fp32)) throw Error(fmt::format("{}: 'precisions' needs an fp32 entry", source));
  if (json.contains("glue_names")) {
    for (const auto& [name, spelling] : json.at("glue_names").items()) {
      if (!spelling.is_string()) throw Error(fmt::format("{}: 'glue_names.{}' must be a string", source, name));
      target.glue_names[name] = spelling.get<std::string>();
    }
  }
  if (json.contains("resources")) {
    for (const auto& [name, entry] : json.at("resources").items())
      target.resources[name] = parse_resource(entry, name, target.module, source);
  }
}

}  // namespace

TargetSyntax TargetSyntax::parse(std::string_view json_text, std::string_view source) {
  Json json;
  try {
    json = Json::parse(json_text);
  } catch (const Json::parse_error& error) {
    throw Error(fmt::format("{}: {}", source, error.what()));
  }
  TargetSyntax target;
  read_identity(json, target, source);
  read_spellings(json, target, source);
  read_file_forms(json, target, source);
  read_validation(json, target, source);
  read_precisions_and_resources(json, target, source);
  return target;
}

namespace {
const std::map<std::string, TargetSyntax, std::less<>>& builtin_targets() {
  static const auto targets = [] {
    std::map<std::string, TargetSyntax, std::less<>> table;
    for (const auto& [name, text] : embedded::files()) {
      // targets/<name>.json; a language's own table is targets/<language>/language.json.
      if (!name.starts_with("targets/") || !name.ends_with(".json") || name.find('/', 8) != std::string::npos) continue;
      TargetSyntax target = TargetSyntax::parse(text, name);
      table.emplace(target.name, std::move(target));
    }
    return table;
  }();
  return targets;
}
}  // namespace

const TargetSyntax& builtin_target(std::string_view name) {
  const auto& targets = builtin_targets();
  const auto found = targets.find(name);
  if (found == targets.end()) {
    throw Error(fmt::format("unknown target '{}'; choose one of: {}", name, fmt::join(builtin_target_names(), ", ")));
  }
  return found->second;
}

const TargetSyntax& spirv_library_target() {
  std::vector<const TargetSyntax*> sources;
  for (const auto& [name, target] : builtin_targets()) {
    if (target.spirv_library_source) sources.push_back(&target);
  }
  if (sources.size() != 1)
    throw Error(fmt::format("{} target tables are the SPIR-V library's source (spirv_library_source); one must be", sources.size()));
  return *sources.front();
}

std::vector<const TargetSyntax*> deferred_pass_targets() {
  std::vector<const TargetSyntax*> targets;
  for (const auto& [name, target] : builtin_targets()) {
    if (!target.deferred_pass.empty()) targets.push_back(&target);
  }
  return targets;
}

std::vector<const TargetSyntax*> vulkan_targets() {
  std::vector<const TargetSyntax*> targets;
  for (const auto& [name, target] : builtin_targets()) {
    const auto& clients = target.validation_clients;
    if (std::find(clients.begin(), clients.end(), ClientApi::vulkan) != clients.end()) targets.push_back(&target);
  }
  return targets;
}

SourceLanguage source_language_of_extension(std::string_view extension) {
  if (extension.starts_with('.')) extension.remove_prefix(1);
  for (const auto& [name, target] : builtin_targets()) {
    if (target.file_extension == extension) return target.language;
  }
  return SourceLanguage::named("glsl");
}

const TargetSyntax* find_builtin_target(std::string_view name) {
  const auto& targets = builtin_targets();
  const auto found = targets.find(name);
  return found == targets.end() ? nullptr : &found->second;
}

std::vector<std::string> builtin_target_names() {
  std::vector<std::string> names;
  for (const auto& [name, target] : builtin_targets()) names.push_back(name);
  return names;
}

std::vector<Precision> TargetSyntax::precision_kinds() const {
  std::vector<Precision> kinds;
  for (const auto& [kind, form] : precisions) kinds.push_back(kind);
  return kinds;
}

TargetSyntax TargetSyntax::with_precision(Precision precision) const {
  const auto found = precisions.find(precision);
  if (found == precisions.end()) {
    throw Error(fmt::format("target {} has no precision '{}'; choose one of: {}", name, to_string(precision),
                            fmt::join(precision_names(precision_kinds()), ", ")));
  }
  TargetSyntax result = *this;
  for (const auto& [type, spelling] : found->second.types) result.types[type] = spelling;
  for (const auto& [intrinsic, pattern] : found->second.intrinsics) result.intrinsics[intrinsic] = pattern;
  result.literal_suffix = found->second.literal_suffix;
  result.preamble = found->second.preamble;
  result.native_16bit = found->second.native_16bit;
  for (const auto& [type, spelling] : found->second.declaration_types) result.declaration_types[type] = spelling;
  if (found->second.function_prologue) result.function_prologue = *found->second.function_prologue;
  for (const auto& [intrinsic, note] : found->second.intrinsic_notes) result.intrinsic_notes[intrinsic] = note;
  return result;
}

const std::string& TargetSyntax::declaration_type(const std::string& dialect_type) const {
  const auto found = declaration_types.find(dialect_type);
  return found != declaration_types.end() ? found->second : types.at(dialect_type);
}

std::string substitute(std::string text, std::string_view key, std::string_view value) {
  for (auto position = text.find(key); position != std::string::npos; position = text.find(key, position + value.size())) {
    text.replace(position, key.size(), value);
  }
  return text;
}

std::string substitute_type_placeholders(std::string text, const TargetSyntax& target) {
  for (const char* type : {"real", "real2", "real3", "real4"})
    text = substitute(std::move(text), fmt::format("{{{}}}", type), target.types.at(type));
  return text;
}

namespace {
std::string replace_placeholders(std::string text, std::string_view prefix, std::string_view macro_prefix) {
  for (const auto& [key, value] : {std::pair<std::string_view, std::string_view>{"{prefix}", prefix}, {"{macro_prefix}", macro_prefix}}) {
    for (auto position = text.find(key); position != std::string::npos; position = text.find(key, position + value.size())) {
      text.replace(position, key.size(), value);
    }
  }
  return text;
}
}  // namespace

TargetSyntax TargetSyntax::with_prefix(std::string_view prefix, std::string_view macro_prefix) const {
  TargetSyntax result = *this;
  for (auto& [intrinsic, pattern] : result.intrinsics) pattern = replace_placeholders(pattern, prefix, macro_prefix);
  result.preamble = replace_placeholders(result.preamble, prefix, macro_prefix);
  for (auto& [name, resource] : result.resources) resource.declaration = replace_placeholders(resource.declaration, prefix, macro_prefix);
  return result;
}

std::string suffix_float_literals(std::string_view code, std::string_view suffix) {
  if (suffix.empty()) return std::string(code);
  std::string out;
  for (const dialect::Token& token : dialect::tokenize(code)) {
    out += token.text;
    const bool is_float = token.kind == dialect::TokenKind::number && token.text.find_first_of(".eE") != std::string_view::npos &&
                          std::isdigit(static_cast<unsigned char>(token.text.back()));
    if (is_float) out += suffix;
  }
  return out;
}

std::string expand_pattern(const std::string& pattern, const std::vector<std::string>& arguments) {
  std::string result;
  for (std::size_t index = 0; index < pattern.size(); ++index) {
    const char c = pattern[index];
    const auto close = pattern.find('}', index);
    if (c == '{' && close != std::string::npos) {
      const std::string slot = pattern.substr(index + 1, close - index - 1);
      if (!slot.empty() && std::all_of(slot.begin(), slot.end(), ::isdigit)) {
        const std::size_t argument = std::stoul(slot);
        if (argument >= arguments.size()) throw Error(fmt::format("intrinsic pattern '{}' needs argument {{{}}}", pattern, argument));
        result += arguments[argument];
        index = close;
        continue;
      }
    }
    result += c;
  }
  return result;
}

}  // namespace saagen

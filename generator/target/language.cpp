#include "saagen/target/language.hpp"

#include "table_keys.hpp"

#include "saagen/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <map>

namespace saagen {
namespace embedded {
const std::map<std::string, std::string_view>& files();
}

namespace {

using Json = nlohmann::json;

std::string required_string(const Json& object, const char* key, std::string_view source) {
  return table_keys::require_string(object, key, source, "language");
}

GlslangFrontEnd parse_front_end(const Json& table, std::string_view source) {
  if (!table.contains("glslang") || !table.at("glslang").is_object())
    throw Error(fmt::format("{}: a language glslang validates needs the object 'glslang' (front_end, default_version, named_entry_points)",
                            source));
  const Json& glslang = table.at("glslang");
  const std::string front_end = required_string(glslang, "front_end", source);
  if (front_end != "glsl" && front_end != "hlsl")
    throw Error(fmt::format("{}: glslang's front_end is 'glsl' or 'hlsl', not '{}'", source, front_end));
  if (!glslang.contains("default_version") || !glslang.at("default_version").is_number_integer())
    throw Error(fmt::format("{}: glslang's 'default_version' must be an integer", source));
  if (!glslang.contains("named_entry_points") || !glslang.at("named_entry_points").is_boolean())
    throw Error(fmt::format("{}: glslang's 'named_entry_points' must be true or false", source));
  return {.hlsl = front_end == "hlsl",
          .default_version = glslang.at("default_version").get<int>(),
          .named_entry_points = glslang.at("named_entry_points").get<bool>()};
}

// The folder of a language table targets/<language>/language.json, or nothing for another file.
std::optional<std::string_view> language_folder(std::string_view path) {
  constexpr std::string_view folder = "targets/", file = "/language.json";
  if (!path.starts_with(folder) || !path.ends_with(file) || path.size() <= folder.size() + file.size()) return std::nullopt;
  const std::string_view name = path.substr(folder.size(), path.size() - folder.size() - file.size());
  if (name.find('/') != std::string_view::npos) return std::nullopt;
  return name;
}

// Every targets/<language>/language.json of this build, by name.
const std::map<std::string, Language, std::less<>>& builtin_languages() {
  static const auto languages = [] {
    std::map<std::string, Language, std::less<>> table;
    for (const auto& [path, text] : embedded::files()) {
      const std::optional<std::string_view> folder = language_folder(path);
      if (!folder) continue;
      Language language = Language::parse(text, path);
      if (language.name != *folder) throw Error(fmt::format("{}: its name is its folder's, '{}', not '{}'", path, *folder, language.name));
      const std::string name = language.name;
      table.emplace(name, std::move(language));
    }
    return table;
  }();
  return languages;
}

}  // namespace

Language Language::parse(std::string_view json_text, std::string_view source) {
  const Json table = Json::parse(json_text, nullptr, false);
  if (table.is_discarded() || !table.is_object()) throw Error(fmt::format("{}: not a JSON object", source));
  Language language;
  language.name = required_string(table, "name", source);
  language.description = required_string(table, "description", source);
  language.printer = required_string(table, "printer", source);
  language.table = std::string(source);
  const std::string validator = required_string(table, "validator", source);
  if (validator == "glslang")
    language.glslang = parse_front_end(table, source);
  else if (validator != "tint")
    throw Error(fmt::format("{}: 'validator' is 'glslang' or 'tint', not '{}'", source, validator));
  return language;
}

const GlslangFrontEnd& Language::front_end() const {
  if (!glslang) throw Error(fmt::format("{} is not compiled by glslang; Tint validates it through the WebGPU runner", name));
  return *glslang;
}

std::optional<SourceLanguage> source_language(std::string_view name) {
  const auto& languages = builtin_languages();
  const auto found = languages.find(name);
  if (found == languages.end()) return std::nullopt;
  return SourceLanguage(&found->second);
}

SourceLanguage SourceLanguage::named(std::string_view name) {
  if (const auto language = source_language(name)) return *language;
  throw Error(fmt::format("no language '{}' in this build (its table targets/{}/language.json); the languages are {}", name, name,
                          fmt::join(language_names(), ", ")));
}

std::vector<std::string> language_names() {
  std::vector<std::string> names;
  for (const auto& [name, language] : builtin_languages()) names.push_back(name);
  return names;
}

}  // namespace saagen

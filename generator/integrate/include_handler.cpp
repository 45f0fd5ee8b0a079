// Include names to emitted snippets (saagen/integrate/include_handler.hpp).
#include "saagen/integrate/include_handler.hpp"

#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/io/marker.hpp"
#include "saagen/target/target.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <memory>

namespace saagen {
namespace {

constexpr std::string_view include_root = "saagen/";
constexpr std::string_view query_keys = "prefix, sigma2, kappa, preset, domain, precision, guards";

// The CLI's number rule (cli/arguments.hpp): a whole decimal number.
double parse_number(std::string_view key, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double value = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || std::isspace(static_cast<unsigned char>(text.front()))) {
    throw Error(fmt::format("--{} '{}': not a number; pass a decimal number", key, text));
  }
  return value;
}

// The built-in target whose files carry `extension` (glsl, essl for gles, hlsl). Module languages
// (WGSL) have no #include for a handler to serve.
OutputTarget target_of_extension(std::string_view extension) {
  std::vector<std::string> known;
  for (const std::string& name : builtin_target_names()) {
    if (!builtin_target(name).has_includes()) continue;
    const std::string& target_extension = builtin_target(name).file_extension;
    if (target_extension == extension) return OutputTarget::snippet(name);
    known.push_back("." + target_extension);
  }
  throw Error(fmt::format("unknown extension '.{}'; use {}", extension, fmt::join(known, ", ")));
}

struct ParsedName {
  std::string id;       // variant or preset
  OutputTarget target;  // a snippet of glsl, gles or hlsl
  IncludeOptions options;
};

void apply_query_pair(std::string_view pair, IncludeOptions& options) {
  const auto equals = pair.find('=');
  if (equals == std::string_view::npos || equals == 0) {
    throw Error(fmt::format("'{}' is not key=value; use {}", pair, query_keys));
  }
  const std::string key(pair.substr(0, equals));
  const std::string value(pair.substr(equals + 1));
  if (key == "prefix")
    options.prefix = value;
  else if (key == "sigma2")
    options.sigma2 = parse_number(key, value);
  else if (key == "kappa")
    options.kappa = parse_number(key, value);
  else if (key == "preset")
    options.preset = value;
  else if (key == "domain")
    options.domain = value;
  else if (key == "precision")
    options.precision = parse_precision(value, "precision");
  else if (key == "guards" && (value == "on" || value == "off"))
    options.guards = value == "on";
  else if (key == "guards")
    throw Error(fmt::format("guards '{}': use on or off", value));
  else
    throw Error(fmt::format("unknown option '{}'; use {}", key, query_keys));
}

ParsedName parse_name(std::string_view name, const IncludeOptions& defaults) {
  if (!is_saagen_include(name)) throw Error(fmt::format("not a saagen include; name saagen/<variant or preset>.<glsl|essl|hlsl>"));
  ParsedName parsed{{}, {}, defaults};
  std::string_view path = name.substr(include_root.size());
  const auto question = path.find('?');
  std::string_view query = question == std::string_view::npos ? std::string_view() : path.substr(question + 1);
  path = path.substr(0, question);
  const auto dot = path.rfind('.');
  if (dot == std::string_view::npos || dot == 0) {
    throw Error(fmt::format("'{}' has no extension; name saagen/<variant or preset>.<glsl|essl|hlsl>", path));
  }
  parsed.id = std::string(path.substr(0, dot));
  parsed.target = target_of_extension(path.substr(dot + 1));
  while (!query.empty()) {
    const auto ampersand = query.find('&');
    apply_query_pair(query.substr(0, ampersand), parsed.options);
    query = ampersand == std::string_view::npos ? std::string_view() : query.substr(ampersand + 1);
  }
  return parsed;
}

EmitOptions emit_options_for(const ParsedName& parsed) {
  const Catalogue& catalogue = Catalogue::builtin();
  EmitSettings settings{parsed.options.preset, {}, parsed.options.sigma2, parsed.options.kappa, parsed.options.domain};
  if (catalogue.find_variant(parsed.id)) {
    settings.variants = {parsed.id};
  } else {
    bool is_preset = false;
    for (const Preset& preset : presets()) is_preset = is_preset || preset.id == parsed.id;
    if (!is_preset) {
      throw Error(fmt::format("'{}' is neither a variant nor a preset; run `saagen list` for the variants, presets are {}", parsed.id,
                              preset_ids()));
    }
    if (settings.preset && *settings.preset != parsed.id) {
      throw Error(fmt::format("preset={} contradicts the preset '{}' the name asks for; name one", *settings.preset, parsed.id));
    }
    settings.preset = parsed.id;
  }
  EmitOptions options;
  options.target = parsed.target;
  options.prefix = parsed.options.prefix;
  options.precision = parsed.options.precision;
  options.guards = parsed.options.guards;
  apply_settings(catalogue, settings, options);
  return options;
}

}  // namespace

bool is_saagen_include(std::string_view name) { return name.substr(0, include_root.size()) == include_root; }

EmitOptions include_emit_options(std::string_view name, const IncludeOptions& defaults) {
  try {
    return emit_options_for(parse_name(name, defaults));
  } catch (const Error& error) {
    throw Error(fmt::format("{}: {}", name, error.what()));
  }
}

EmittedFile resolve_include(std::string_view name, const IncludeOptions& defaults) {
  const EmitOptions options = include_emit_options(name, defaults);
  try {
    return emit_variants(Catalogue::builtin(), options).front();
  } catch (const Error& error) {
    throw Error(fmt::format("{}: {}", name, error.what()));
  }
}

}  // namespace saagen

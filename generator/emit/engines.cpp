// Roughness domains and engine presets (saagen/emit/engines.hpp): read from templates/engines.json,
// composed from templates/05-domains.saa. No formula here: a wrapper's body is two calls.
#include "saagen/emit/engines.hpp"

#include "saagen/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

namespace saagen {
namespace embedded {
const std::map<std::string, std::string_view>& files();
}

namespace {

constexpr std::string_view data_file = "templates/engines.json";

struct EngineData {
  std::vector<RoughnessDomain> domains;
  std::vector<Preset> presets;
};

std::string text_field(const nlohmann::json& entry, const char* key, bool required = true) {
  if (!entry.contains(key)) {
    if (required) throw Error(fmt::format("{}: an entry lacks '{}'", data_file, key));
    return {};
  }
  return entry.at(key).get<std::string>();
}

Domain preset_domain(const std::string& id) {
  const auto domain = domain_named(id);
  if (!domain) throw Error(fmt::format("{}: a preset's domain '{}' is not alpha2, alpha, perceptual or smoothness", data_file, id));
  return *domain;
}

const EngineData& engine_data() {
  static const EngineData data = [] {
    const auto& files = embedded::files();
    const auto found = files.find(std::string(data_file));
    if (found == files.end()) throw Error(fmt::format("{} is not built in", data_file));
    const auto json = nlohmann::json::parse(found->second);
    EngineData result;
    for (const auto& entry : json.at("domains")) {
      const std::string id = text_field(entry, "id");
      const auto kind = domain_named(id);
      // The order is the deferred pass's flag values (saagen/domain.hpp).
      if (!kind || static_cast<std::size_t>(*kind) != result.domains.size()) {
        throw Error(fmt::format("{}: domain '{}' is not the next of alpha2, alpha, perceptual, smoothness", data_file, id));
      }
      result.domains.push_back({*kind, id, text_field(entry, "parameter"), text_field(entry, "meaning"), text_field(entry, "engines"),
                                text_field(entry, "to_alpha2", false), text_field(entry, "from_alpha2", false)});
    }
    for (const auto& entry : json.at("presets")) {
      result.presets.push_back({text_field(entry, "id"), text_field(entry, "engine"), text_field(entry, "variant"),
                                entry.at("sigma2").get<double>(), entry.at("kappa").get<double>(),
                                preset_domain(text_field(entry, "domain")), text_field(entry, "normal"), text_field(entry, "form")});
    }
    return result;
  }();
  return data;
}

// The wrapper of one function, as template source: same role, parameters and meanings, with the
// roughness parameter and the result in `domain`.
std::string wrapper_source(const Function& function, const RoughnessDomain& domain) {
  const bool per_axis = function.return_type != "real";
  const std::string& x = domain.parameter;
  std::ostringstream out;
  out << fmt::format("@function {}\n", domain_function_name(function.name, domain.kind));
  out << fmt::format("role: {}\n", to_string(function.role));
  out << fmt::format("cite: {} with roughness in and out as {} (saagen domain conversion)\n", function.name, domain.meaning);
  out << fmt::format("returns: {} | the filtered roughness as {}{}\n", function.return_type, domain.meaning, per_axis ? ", per axis" : "");
  out << fmt::format("param: {} {} | {}{}\n", function.return_type, x, domain.meaning, per_axis ? ", per axis" : "");
  std::vector<std::string> arguments;
  for (std::size_t index = 1; index < function.parameters.size(); ++index) {
    const Parameter& parameter = function.parameters[index];
    out << fmt::format("param: {} {} | {}\n", parameter.type, parameter.name, parameter.meaning);
    arguments.push_back(parameter.name);
  }
  const std::string rest = arguments.empty() ? "" : ", " + fmt::format("{}", fmt::join(arguments, ", "));
  out << "{\n";
  if (per_axis) {
    out << fmt::format("    real2 filtered = {}(real2({}({}.x), {}({}.y)){});\n", function.name, domain.to_alpha2, x, domain.to_alpha2, x,
                       rest);
    out << fmt::format("    return real2({}(filtered.x), {}(filtered.y));\n", domain.from_alpha2, domain.from_alpha2);
  } else {
    out << fmt::format("    return {}({}({}({}){}));\n", domain.from_alpha2, function.name, domain.to_alpha2, x, rest);
  }
  out << "}\n\n";
  return out.str();
}

std::string domain_text(const RoughnessDomain& domain, const Variant& variant) {
  return fmt::format("in and out {} (converted around the alpha^2 filter: {})", domain.meaning, variant.domain);
}

Catalogue build_domain_catalogue(const Catalogue& base, const RoughnessDomain& domain) {
  std::string wrappers;
  for (const Variant& variant : base.variants()) {
    for (const std::string& name : variant.functions) {
      const Function& function = *base.find_function(name);
      if (takes_and_returns_roughness(function) &&
          wrappers.find("@function " + domain_function_name(name, domain.kind) + "\n") == std::string::npos) {
        wrappers += wrapper_source(function, domain);
      }
    }
  }
  std::vector<TemplateSource> sources = base.sources();
  sources.push_back({fmt::format("saagen-domain-{}.saa", domain.id), wrappers});
  const Catalogue extended = Catalogue::parse(sources);
  std::vector<Variant> variants;
  for (Variant variant : base.variants()) {
    if (variant_has_roughness_io(base, variant)) {
      variant.domain = domain_text(domain, variant);
      for (std::string& name : variant.functions) {
        if (takes_and_returns_roughness(*base.find_function(name))) name = domain_function_name(name, domain.kind);
      }
    }
    variants.push_back(std::move(variant));
  }
  return extended.with_variants(std::move(variants));
}

}  // namespace

const std::vector<RoughnessDomain>& roughness_domains() { return engine_data().domains; }

std::string domain_ids() {
  std::vector<std::string> ids;
  for (const RoughnessDomain& domain : roughness_domains()) ids.push_back(domain.id);
  return fmt::format("{}", fmt::join(ids, ", "));
}

const RoughnessDomain& find_domain(std::string_view id, std::string_view option) {
  for (const RoughnessDomain& domain : roughness_domains()) {
    if (domain.id == id) return domain;
  }
  throw Error(fmt::format("{} '{}' is not a roughness domain; use one of {}", option, id, domain_ids()));
}

const RoughnessDomain& roughness_domain(Domain domain) { return roughness_domains().at(static_cast<std::size_t>(domain)); }

const std::vector<Preset>& presets() { return engine_data().presets; }

std::string preset_ids() {
  std::vector<std::string> ids;
  for (const Preset& preset : presets()) ids.push_back(preset.id);
  return fmt::format("{}", fmt::join(ids, ", "));
}

const Preset& find_preset(std::string_view id, std::string_view option) {
  for (const Preset& preset : presets()) {
    if (preset.id == id) return preset;
  }
  throw Error(fmt::format("{} '{}' is not a preset; use one of {}", option, id, preset_ids()));
}

bool takes_and_returns_roughness(const Function& function) {
  return !function.parameters.empty() && function.parameters.front().name == "alpha2" &&
         (function.return_type == "real" || function.return_type == "real2") && function.parameters.front().type == function.return_type;
}

bool variant_has_roughness_io(const Catalogue& catalogue, const Variant& variant) {
  return std::any_of(variant.functions.begin(), variant.functions.end(), [&](const std::string& name) {
    const Function* function = catalogue.find_function(name);
    return function && takes_and_returns_roughness(*function);
  });
}

std::string domain_function_name(std::string_view function, Domain domain) { return fmt::format("{}_{}", function, to_string(domain)); }

const Catalogue& domain_catalogue(const Catalogue& catalogue, Domain domain_kind) {
  const RoughnessDomain& domain = roughness_domain(domain_kind);
  if (domain.to_alpha2.empty()) return catalogue;
  // One extended catalogue per (catalogue, domain): the built-in templates, or those plus the
  // glint templates (whose functions take no alpha^2 and stay as they are).
  static std::mutex mutex;
  static std::map<std::pair<const Catalogue*, Domain>, std::unique_ptr<Catalogue>> cache;
  const std::lock_guard lock(mutex);
  const auto key = std::make_pair(&catalogue, domain.kind);
  auto found = cache.find(key);
  if (found == cache.end()) found = cache.emplace(key, std::make_unique<Catalogue>(build_domain_catalogue(catalogue, domain))).first;
  return *found->second;
}

}  // namespace saagen

#include "saagen/emit/listing.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/emit/engines.hpp"
#include "saagen/target/resources.hpp"
#include "saagen/target/target.hpp"

#include <algorithm>

namespace saagen {
namespace {

using Json = nlohmann::json;

Json type_spellings(const std::string& dialect_type) {
  Json spellings = Json::object();
  for (const std::string& target : builtin_target_names()) spellings[target] = builtin_target(target).declaration_type(dialect_type);
  return spellings;
}

Json function_json(const Function& function, std::string_view prefix) {
  Json parameters = Json::array();
  for (const Parameter& parameter : function.parameters) {
    parameters.push_back({{"name", parameter.name},
                          {"type", parameter.type},
                          {"target_types", type_spellings(parameter.type)},
                          {"meaning", parameter.meaning}});
  }
  return {{"name", function.name},
          {"emitted_name", prefixed_name(prefix, function.name)},
          {"role", std::string(to_string(function.role))},
          {"fragment_only", function.fragment_only},
          {"cite", function.cite},
          {"returns",
           {{"type", function.return_type}, {"target_types", type_spellings(function.return_type)}, {"meaning", function.return_meaning}}},
          {"parameters", parameters}};
}

// The resources a variant's functions read (the glint dictionary): per target the declaration
// that the including shader provides in the validation skeletons, as an example of the binding.
Json resources_json(const Catalogue& catalogue, const Variant& variant, std::string_view prefix) {
  Json resources = Json::array();
  std::vector<std::string> names;
  Json declarations = Json::object();
  Json passed = Json::object();
  for (const std::string& target_name : builtin_target_names()) {
    const TargetSyntax target = builtin_target(target_name).with_prefix(prefix, macro_prefix(prefix));
    for (const std::string& name : resources_used(target, catalogue, variant.functions)) {
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
      const TargetSyntax::Resource& resource = target.resources.find(name)->second;
      declarations[name][target_name] = resource.declaration;
      // A module language passes the resource to the functions that read it.
      if (target.passes_resources()) passed[name][target_name] = resource.parameters;
    }
  }
  for (const std::string& name : names) {
    resources.push_back({{"name", name}, {"example_declaration", declarations[name]}, {"parameters", passed.value(name, Json::object())}});
  }
  return resources;
}

// The precisions of the built-in targets (fp32 first): what a variant without a `precisions:`
// list may be emitted in, each target offering its own (`targets` in list --json).
std::vector<std::string> every_precision() {
  std::vector<Precision> kinds = {Precision::fp32};
  for (const std::string& target : builtin_target_names()) {
    for (const Precision kind : builtin_target(target).precision_kinds()) {
      if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) kinds.push_back(kind);
    }
  }
  return precision_names(kinds);
}

}  // namespace

nlohmann::json catalogue_json(const Catalogue& base_catalogue, std::string_view prefix, Domain domain) {
  const Catalogue& catalogue = domain_catalogue(base_catalogue, domain);
  Json variants = Json::array();
  for (const Variant& variant : catalogue.variants()) {
    const bool converts = variant_has_roughness_io(base_catalogue, *base_catalogue.find_variant(variant.id));
    if (domain != Domain::alpha2 && !converts) continue;
    Json variant_domains = Json::array();
    for (const RoughnessDomain& roughness : roughness_domains()) {
      if (converts || roughness.to_alpha2.empty()) variant_domains.push_back(roughness.id);
    }
    Json functions = Json::array();
    for (const std::string& name : variant.functions) functions.push_back(function_json(*catalogue.find_function(name), prefix));
    variants.push_back({{"id", variant.id},
                        {"summary", variant.summary},
                        {"paper", variant.paper},
                        {"equation", variant.equation},
                        {"render_path", std::string(to_string(variant.path))},
                        {"needs_tangents", variant.needs_tangents},
                        {"domain", variant.domain},
                        {"resources", resources_json(catalogue, variant, prefix)},
                        {"precisions", variant.precisions.empty() ? every_precision() : precision_names(variant.precisions)},
                        {"roughness_domains", variant_domains},
                        {"functions", functions}});
  }
  Json options = Json::array();
  for (const Constant& constant : catalogue.constants()) {
    if (constant.option.empty()) continue;
    options.push_back({{"name", constant.option},
                       {"constant", prefixed_name(prefix, constant.name)},
                       {"default", constant.value},
                       {"range", constant.range->describe()},
                       {"meaning", constant.meaning}});
  }
  Json domains = Json::array();
  for (const RoughnessDomain& roughness : roughness_domains()) {
    domains.push_back({{"id", roughness.id}, {"meaning", roughness.meaning}, {"engines", roughness.engines}});
  }
  Json preset_list = Json::array();
  for (const Preset& preset : presets()) {
    preset_list.push_back({{"id", preset.id},
                           {"engine", preset.engine},
                           {"variant", preset.variant},
                           {"sigma2", preset.sigma2},
                           {"kappa", preset.kappa},
                           {"domain", to_string(preset.domain)},
                           {"normal", preset.normal},
                           {"form", preset.form}});
  }
  return {{"saagen_version", std::string(version())},
          {"prefix", std::string(prefix)},
          {"roughness_domain", to_string(domain)},
          {"domains", domains},
          {"presets", preset_list},
          {"core_only_macro", macro_prefix(prefix) + "CORE_ONLY"},
          {"targets", builtin_target_names()},
          {"options", options},
          {"variants", variants}};
}

}  // namespace saagen

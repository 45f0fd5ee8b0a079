#include "saagen/listing.hpp"

#include "saagen/emitter.hpp"
#include "saagen/target.hpp"

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
          {"returns", {{"type", function.return_type}, {"target_types", type_spellings(function.return_type)}, {"meaning", function.return_meaning}}},
          {"parameters", parameters}};
}

}  // namespace

nlohmann::json catalogue_json(const Catalogue& catalogue, std::string_view prefix) {
  Json variants = Json::array();
  for (const Variant& variant : catalogue.variants()) {
    Json functions = Json::array();
    for (const std::string& name : variant.functions) functions.push_back(function_json(*catalogue.find_function(name), prefix));
    variants.push_back({{"id", variant.id},
                        {"summary", variant.summary},
                        {"paper", variant.paper},
                        {"equation", variant.equation},
                        {"render_path", std::string(to_string(variant.path))},
                        {"needs_tangents", variant.needs_tangents},
                        {"domain", variant.domain},
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
  return {{"saagen_version", std::string(version())},
          {"prefix", std::string(prefix)},
          {"core_only_macro", macro_prefix(prefix) + "CORE_ONLY"},
          {"targets", builtin_target_names()},
          {"options", options},
          {"variants", variants}};
}

}  // namespace saagen

// Glue printed from the typed tree (saagen/print/glue.hpp): one printer path for template bodies
// and for the statements the harness skeletons wrap around them.
#include "saagen/error.hpp"
#include "saagen/front/syntax_tree.hpp"
#include "saagen/print/glue.hpp"
#include "saagen/target/resources.hpp"

#include <fmt/format.h>

#include <map>

namespace saagen {
namespace {

dialect::Type dialect_type(const std::string& name) {
  const auto type = dialect::Type::from_name(name);
  if (!type) throw Error(fmt::format("glue: unknown dialect type '{}'", name));
  return *type;
}

}  // namespace

std::string print_glue(const TargetSyntax& target, const Catalogue& catalogue, std::string_view code, const NameMap& names,
                       const GlueSymbols& symbols) {
  std::map<std::string, dialect::FunctionSignature, std::less<>> functions;
  for (const Function& function : catalogue.functions()) functions[function.name] = signature_of(function);
  for (const GlueSymbols::Callable& callable : symbols.functions) {
    dialect::FunctionSignature& signature = functions[callable.name];
    if (!callable.result.empty()) signature.result = dialect_type(callable.result);
    for (const std::string& type : callable.parameters) signature.parameters.emplace_back(dialect_type(type), "");
  }
  std::map<std::string, dialect::Type, std::less<>> constants;
  for (const Constant& constant : catalogue.constants()) constants[constant.name] = dialect_type(constant.type);
  dialect::FunctionSignature glue;  // no result; the skeleton's variables are its parameters
  for (const auto& [name, type] : symbols.variables) glue.parameters.emplace_back(dialect_type(type), name);

  const dialect::SourcePlace place{"saagen-glue", 1, "glue"};
  dialect::Body body = dialect::parse_body(code, place);
  dialect::check_body(body, glue, {&functions, &constants, nullptr}, place);
  NameMap spellings = names;
  for (const auto& [name, spelling] : target.glue_names) spellings[name] = spelling;
  const auto resource_arguments = resource_lists(target, catalogue, &TargetSyntax::Resource::caller_arguments);
  return dialect::print_body(body, target, {&spellings, true, &resource_arguments, nullptr});
}

}  // namespace saagen

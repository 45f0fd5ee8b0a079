#include "saagen/validation.hpp"

#include "saagen/dialect.hpp"
#include "saagen/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/target.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace saagen {
namespace {

// A dialect expression of the given type built from the shader's input vector, so that the
// compiler cannot fold the call away.
std::string argument_for(const std::string& type) {
  // Constructors convert explicitly, which half-precision GLSL requires.
  if (type == "real") return "real(saagen_seed.x)";
  if (type == "real2") return "real2(saagen_seed.xy)";
  if (type == "real3") return "real3(saagen_seed.xyz)";
  if (type == "real4") return "real4(saagen_seed)";
  if (type == "int") return "int(saagen_seed.x)";
  if (type == "bool") return "(saagen_seed.x > 0.5)";
  throw Error(fmt::format("no validation argument for type '{}'", type));
}

// A dialect expression reducing a value of the given type to one real.
std::string reduce(const std::string& type, const std::string& value) {
  if (type == "real") return value;
  if (type == "real2") return fmt::format("dot({}, real2(1.0, 1.0))", value);
  if (type == "real3") return fmt::format("dot({}, real3(1.0, 1.0, 1.0))", value);
  if (type == "real4") return fmt::format("dot({}, real4(1.0, 1.0, 1.0, 1.0))", value);
  if (type == "int") return fmt::format("real({})", value);
  if (type == "bool") return fmt::format("(({}) ? 1.0 : 0.0)", value);
  throw Error(fmt::format("no reduction for type '{}'", type));
}

std::string calls_in_dialect(const Catalogue& catalogue, const std::vector<std::string>& functions, ShaderStage stage) {
  std::string calls;
  for (const std::string& name : functions) {
    const Function& function = *catalogue.find_function(name);
    if (stage == ShaderStage::compute && function.fragment_only) continue;
    std::vector<std::string> arguments;
    for (const Parameter& parameter : function.parameters) arguments.push_back(argument_for(parameter.type));
    calls += fmt::format("    acc += {};\n", reduce(function.return_type, fmt::format("{}({})", name, fmt::join(arguments, ", "))));
  }
  return calls;
}

std::string substitute(std::string text, std::string_view key, const std::string& value) {
  for (auto position = text.find(key); position != std::string::npos; position = text.find(key, position + value.size())) {
    text.replace(position, key.size(), value);
  }
  return text;
}

std::string client_name(ClientApi client) {
  return client == ClientApi::vulkan ? "vulkan" : client == ClientApi::opengl ? "opengl" : "opengl_es";
}
std::string stage_name(ShaderStage stage) {
  return stage == ShaderStage::compute ? "compute" : stage == ShaderStage::fragment ? "fragment" : "vertex";
}

}  // namespace

std::vector<std::string> resources_used(const TargetSyntax& target, const Catalogue& catalogue, const std::vector<std::string>& roots) {
  if (target.resources.empty()) return {};
  std::vector<std::string> used;
  for (const Function* function : catalogue.closure(roots)) {
    const auto tokens = dialect::tokenize(function->body);
    for (std::size_t index = 0; index < tokens.size(); ++index) {
      if (tokens[index].kind == dialect::TokenKind::identifier && !dialect::is_member_access(tokens, index)) {
        used.emplace_back(tokens[index].text);
      }
    }
  }
  std::vector<std::string> names;
  for (const auto& [name, resource] : target.resources) {
    const bool needed = std::any_of(resource.intrinsics.begin(), resource.intrinsics.end(), [&](const std::string& intrinsic) {
      return std::find(used.begin(), used.end(), intrinsic) != used.end();
    });
    if (needed) names.push_back(name);
  }
  return names;
}

std::string resource_declarations(const TargetSyntax& target, const Catalogue& catalogue, const std::vector<std::string>& roots) {
  std::string declarations;
  for (const std::string& name : resources_used(target, catalogue, roots)) declarations += target.resources.find(name)->second.declaration;
  return declarations;
}

bool FileValidation::ok() const {
  return !checks.empty() && std::all_of(checks.begin(), checks.end(), [](const ValidationCheck& check) { return check.ok; });
}

std::string FileValidation::summary() const {
  std::vector<std::string> names;
  for (const ValidationCheck& check : checks) {
    if (!check.ok) {
      std::string log = check.log.substr(0, check.log.find('\n'));
      return fmt::format("FAIL {} ({}): {}", file_name, check.name, log);
    }
    names.push_back(check.name);
  }
  return fmt::format("OK   {} ({})", file_name, fmt::join(names, ", "));
}

std::vector<SourcePiece> validation_sources(const Catalogue& catalogue, const EmissionMarker& marker,
                                            const std::string& file_name, const std::string& content, ShaderStage stage) {
  const TargetSyntax target =
      builtin_target(marker.target).with_precision(marker.precision).with_prefix(marker.prefix, macro_prefix(marker.prefix));
  const ValidationSkeleton& skeleton = stage == ShaderStage::compute ? target.compute_skeleton : target.fragment_skeleton;
  auto functions = public_functions(catalogue, marker.variants);
  if (!marker.functions.empty()) {  // a bundle: exactly its public functions
    for (const std::string& name : marker.functions) {
      if (!catalogue.find_function(name)) throw Error(fmt::format("{}: the marker names unknown function '{}'", file_name, name));
    }
    functions = marker.functions;
  }

  NameMap names;
  for (const std::string& name : functions) names[name] = prefixed_name(marker.prefix, name);
  const std::string calls = translate(target, calls_in_dialect(catalogue, functions, stage), names);

  const std::string core_only = macro_prefix(marker.prefix) + "CORE_ONLY";
  std::vector<SourcePiece> pieces;
  const std::string prologue = substitute(skeleton.prologue, "{core_only_macro}", core_only);
  if (!prologue.empty()) pieces.push_back({"saagen-validation-prologue", prologue});
  const std::string resources = resource_declarations(target, catalogue, functions);
  if (!resources.empty()) pieces.push_back({"saagen-validation-resources", resources});
  pieces.push_back({file_name, content});
  pieces.push_back({"saagen-validation-main", substitute(skeleton.epilogue, "{calls}", calls)});
  return pieces;
}

FileValidation validate_file(const Catalogue& catalogue, const std::string& file_name, const std::string& content) {
  const auto marker = find_marker(content);
  if (!marker) throw Error(fmt::format("{}: no saagen marker line; this file was not written by `saagen emit`", file_name));
  const TargetSyntax target = builtin_target(marker->target).with_precision(marker->precision);

  FileValidation validation{file_name, {}};
  for (ClientApi client : target.validation_clients) {
    for (ShaderStage stage : {ShaderStage::fragment, ShaderStage::compute}) {
      CompileRequest request;
      request.language = target.language;
      // The core-only check runs in a stage without derivatives: compute, or vertex for GLSL ES 3.00.
      request.stage = stage == ShaderStage::compute ? target.core_validation_stage : stage;
      request.client = client;
      request.hlsl_native_16bit = target.native_16bit;
      request.sources = validation_sources(domain_catalogue(catalogue, marker->domain), *marker, file_name, content, stage);
      const CompileResult result = compile_to_spirv(request);
      validation.checks.push_back({client_name(client) + " " + stage_name(request.stage), result.ok, result.log, result.spirv.size()});
    }
  }
  return validation;
}

}  // namespace saagen

#include "saagen/kernels.hpp"

#include "saagen/error.hpp"
#include "saagen/target.hpp"
#include "saagen/validation.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace saagen {
namespace {

std::string_view kind_name(KernelKind kind) {
  switch (kind) {
    case KernelKind::compute: return "compute";
    case KernelKind::quad_compute: return "quad_compute";
    case KernelKind::fragment: return "fragment";
  }
  return "compute";
}

std::string substitute(std::string text, std::string_view key, const std::string& value) {
  for (auto position = text.find(key); position != std::string::npos; position = text.find(key, position + value.size())) {
    text.replace(position, key.size(), value);
  }
  return text;
}

const char* const swizzle = "xyzw";

// The target's name for a dialect intrinsic: "ddx_fine" -> "dFdxFine" in GLSL.
std::string intrinsic_name(const TargetSyntax& target, const std::string& dialect_name) {
  const auto found = target.intrinsics.find(dialect_name);
  if (found == target.intrinsics.end()) return dialect_name;
  return found->second.substr(0, found->second.find('('));
}

}  // namespace

std::uint32_t component_count(const std::string& dialect_type) {
  if (dialect_type == "real" || dialect_type == "int" || dialect_type == "bool") return 1;
  if (dialect_type == "real2") return 2;
  if (dialect_type == "real3") return 3;
  if (dialect_type == "real4") return 4;
  throw Error(fmt::format("no component count for type '{}'", dialect_type));
}

std::string load_call_store_body(const Catalogue& catalogue, const std::string& function_name, KernelRequest& request) {
  const Function* function = catalogue.find_function(function_name);
  if (!function) throw Error(fmt::format("unknown function '{}'", function_name));
  std::string body;
  std::vector<std::string> arguments;
  std::uint32_t offset = 0;
  for (const Parameter& parameter : function->parameters) {
    if (parameter.type == "int" || parameter.type == "bool") {
      throw Error(fmt::format("{}: kernels load only real parameters", function_name));
    }
    const std::uint32_t count = component_count(parameter.type);
    std::vector<std::string> loads;
    for (std::uint32_t component = 0; component < count; ++component) loads.push_back(fmt::format("SAAGEN_LOAD({})", offset++));
    // Constructors convert explicitly (half-precision GLSL has no implicit narrowing).
    const std::string value = fmt::format("{}({})", parameter.type, fmt::join(loads, ", "));
    body += fmt::format("    {} saagen_arg_{} = {};\n", parameter.type, parameter.name, value);
    arguments.push_back("saagen_arg_" + parameter.name);
  }
  body += fmt::format("    {} saagen_result = {}({});\n", function->return_type, function->name, fmt::join(arguments, ", "));
  const std::uint32_t results = component_count(function->return_type);
  for (std::uint32_t component = 0; component < results; ++component) {
    body += fmt::format("    SAAGEN_STORE({}, saagen_result{});\n", component,
                        results == 1 ? std::string() : fmt::format(".{}", swizzle[component]));
  }
  request.input_stride = offset;
  request.output_stride = results;
  return body;
}

std::vector<SourcePiece> kernel_sources(const Catalogue& catalogue, const std::string& file_name,
                                        const std::string& content, const KernelRequest& request) {
  const auto marker = find_marker(content);
  if (!marker) throw Error(fmt::format("{}: no saagen marker line", file_name));
  const TargetSyntax target =
      builtin_target(marker->target).with_precision(marker->precision).with_prefix(marker->prefix, macro_prefix(marker->prefix));
  const auto skeleton = target.kernel_skeletons.find(kind_name(request.kind));
  if (skeleton == target.kernel_skeletons.end()) {
    throw Error(fmt::format("target {} has no '{}' kernel skeleton", target.name, kind_name(request.kind)));
  }
  if (request.kind != KernelKind::compute && (request.width == 0 || request.width % 2 != 0)) {
    throw Error("quad and fragment kernels need an even, non-zero width");
  }

  NameMap names;
  for (const Function& function : catalogue.functions()) names[function.name] = prefixed_name(marker->prefix, function.name);
  const std::string body = translate(target, request.body, names);

  // The plain derivative macros expand to the target's coarse or fine spelling: the built-ins of
  // the base table, which the half-precision derivative helpers call on fp32 values (the
  // precision's table maps ddx to those helpers).
  const bool fine = request.plain_derivative == PlainDerivative::fine;
  const TargetSyntax base = builtin_target(marker->target);
  const std::string plain_ddx = intrinsic_name(base, fine ? "ddx_fine" : "ddx_coarse");
  const std::string plain_ddy = intrinsic_name(base, fine ? "ddy_fine" : "ddy_coarse");
  const auto fill = [&](std::string text) {
    text = substitute(std::move(text), "{core_only_macro}", macro_prefix(marker->prefix) + "CORE_ONLY");
    text = substitute(std::move(text), "{workgroup_size}", std::to_string(request.workgroup_size));
    text = substitute(std::move(text), "{input_stride}", std::to_string(request.input_stride));
    text = substitute(std::move(text), "{output_stride}", std::to_string(request.output_stride));
    text = substitute(std::move(text), "{width}", std::to_string(request.width));
    text = substitute(std::move(text), "{plain_ddx}", plain_ddx);
    text = substitute(std::move(text), "{plain_ddy}", plain_ddy);
    return text;
  };
  std::vector<SourcePiece> pieces;
  const std::string prologue = fill(skeleton->second.prologue);
  if (!prologue.empty()) pieces.push_back({"saagen-kernel-prologue", prologue});
  // Resources (the glint dictionary) that the file's functions sample, declared before it.
  std::vector<std::string> roots = marker->functions;
  if (roots.empty()) {
    for (const std::string& id : marker->variants) {
      if (const Variant* variant = catalogue.find_variant(id)) roots.insert(roots.end(), variant->functions.begin(), variant->functions.end());
    }
  }
  const std::string resources = resource_declarations(target, catalogue, roots);
  if (!resources.empty()) pieces.push_back({"saagen-kernel-resources", resources});
  pieces.push_back({file_name, content});
  pieces.push_back({"saagen-kernel-main", substitute(fill(skeleton->second.epilogue), "{body}", body)});
  return pieces;
}

CompileRequest kernel_compile_request(const Catalogue& catalogue, const std::string& file_name,
                                      const std::string& content, const KernelRequest& request) {
  const auto marker = find_marker(content);
  if (!marker) throw Error(fmt::format("{}: no saagen marker line", file_name));
  const TargetSyntax target = builtin_target(marker->target).with_precision(marker->precision);
  CompileRequest compile;
  compile.language = target.language;
  compile.stage = request.kind == KernelKind::fragment ? ShaderStage::fragment : ShaderStage::compute;
  compile.hlsl_native_16bit = target.native_16bit;
  compile.sources = kernel_sources(catalogue, file_name, content, request);
  return compile;
}

}  // namespace saagen

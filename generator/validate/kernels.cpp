#include "saagen/validate/kernels.hpp"

#include "saagen/error.hpp"
#include "saagen/target/resources.hpp"
#include "saagen/target/target.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <regex>

namespace saagen {
namespace {

std::string_view kind_name(KernelKind kind) {
  switch (kind) {
    case KernelKind::compute:
      return "compute";
    case KernelKind::quad_compute:
      return "quad_compute";
    case KernelKind::fragment:
      return "fragment";
  }
  return "compute";
}

const char* const swizzle = "xyzw";

// The target's name for a dialect intrinsic: "ddx_fine" -> "dFdxFine" in GLSL.
std::string intrinsic_name(const TargetSyntax& target, const std::string& dialect_name) {
  const auto found = target.intrinsics.find(dialect_name);
  if (found == target.intrinsics.end()) return dialect_name;
  return found->second.substr(0, found->second.find('('));
}

// The file with its plain derivative calls (the table's ddx and ddy) spelt as the fine or the
// coarse ones: what a driver that picks that form for the plain ones runs.
std::string redirect_plain_derivatives(const TargetSyntax& target, const std::string& content, bool fine) {
  std::string out = content;
  for (const char* axis : {"x", "y"}) {
    const std::string plain = intrinsic_name(target, fmt::format("dd{}", axis));
    const std::string chosen = intrinsic_name(target, fmt::format("dd{}_{}", axis, fine ? "fine" : "coarse"));
    out = std::regex_replace(out, std::regex("\\b" + plain + "\\("), chosen + "(");
  }
  return out;
}

}  // namespace

const GlueSymbols& kernel_glue_symbols() {
  static const GlueSymbols symbols{{{"saagen_index", "int"}, {"saagen_frag_coord", "real2"}},
                                   {{"SAAGEN_LOAD", "real", {"int"}}, {"SAAGEN_STORE", "", {"int", "real"}}}};
  return symbols;
}

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

std::vector<SourcePiece> kernel_sources(const Catalogue& catalogue, const std::string& file_name, const std::string& content,
                                        const KernelRequest& request) {
  const auto marker = find_marker(content);
  if (!marker) throw Error(fmt::format("{}: no saagen marker line", file_name));
  const TargetSyntax target =
      builtin_target(marker->target.table).with_precision(marker->precision).with_prefix(marker->prefix, macro_prefix(marker->prefix));
  const auto skeleton = target.kernel_skeletons.find(kind_name(request.kind));
  if (skeleton == target.kernel_skeletons.end()) {
    throw Error(fmt::format("target {} has no '{}' kernel skeleton", target.name, kind_name(request.kind)));
  }
  if (request.kind != KernelKind::compute && (request.width == 0 || request.width % 2 != 0)) {
    throw Error("quad and fragment kernels need an even, non-zero width");
  }

  NameMap names;
  for (const Function& function : catalogue.functions()) names[function.name] = prefixed_name(marker->prefix, function.name);
  const std::string body = print_glue(target, catalogue, request.body, names, kernel_glue_symbols());

  // The plain derivative macros expand to the target's coarse or fine spelling: the built-ins of
  // the base table, which the half-precision derivative helpers call on fp32 values (the
  // precision's table maps ddx to those helpers).
  const bool fine = request.plain_derivative == PlainDerivative::fine;
  const TargetSyntax base = builtin_target(marker->target.table);
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
    return substitute_type_placeholders(std::move(text), target);
  };
  std::vector<SourcePiece> pieces;
  const std::string prologue = fill(skeleton->second.prologue);
  if (!prologue.empty()) pieces.push_back({"saagen-kernel-prologue", prologue});
  // Resources (the glint dictionary) that the file's functions sample, declared before it.
  std::vector<std::string> roots = marker->functions;
  if (roots.empty()) {
    for (const std::string& id : marker->variants) {
      if (const Variant* variant = catalogue.find_variant(id))
        roots.insert(roots.end(), variant->functions.begin(), variant->functions.end());
    }
  }
  const std::string resources = resource_declarations(target, catalogue, roots);
  // An include needs its resources declared before it; a module starts with its enable
  // directives, and WGSL's module-scope declarations may come in any order.
  if (!resources.empty() && !target.resources_after_file) pieces.push_back({"saagen-kernel-resources", resources});
  pieces.push_back({file_name, request.redirect_plain_derivatives ? redirect_plain_derivatives(base, content, fine) : content});
  if (!resources.empty() && target.resources_after_file) pieces.push_back({"saagen-kernel-resources", resources});
  pieces.push_back({"saagen-kernel-main", substitute(fill(skeleton->second.epilogue), "{body}", body)});
  return pieces;
}

CompileRequest kernel_compile_request(const Catalogue& catalogue, const std::string& file_name, const std::string& content,
                                      const KernelRequest& request) {
  const auto marker = find_marker(content);
  if (!marker) throw Error(fmt::format("{}: no saagen marker line", file_name));
  const TargetSyntax target = builtin_target(marker->target.table).with_precision(marker->precision);
  CompileRequest compile;
  compile.language = target.language;
  compile.stage = request.kind == KernelKind::fragment ? ShaderStage::fragment : ShaderStage::compute;
  compile.hlsl_native_16bit = target.native_16bit;
  compile.sources = kernel_sources(catalogue, file_name, content, request);
  return compile;
}

}  // namespace saagen

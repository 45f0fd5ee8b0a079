#include "saagen/validate/validation.hpp"

#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/front/dialect.hpp"
#include "saagen/target/language.hpp"
#include "saagen/target/resources.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <utility>

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

// The validation skeletons' variables: the input vector and the accumulator.
const GlueSymbols& validation_glue_symbols() {
  static const GlueSymbols symbols{{{"saagen_seed", "real4"}, {"acc", "real"}}, {}};
  return symbols;
}

// The import-path line of the target's file form (naga_oil's `#define_import_path`, which its
// composer strips before WGSL sees the module) turned into a comment on the same line (the
// module's line numbers stay).
std::string without_import_path(const TargetSyntax& target, std::string content) {
  if (!target.takes_import_path()) return content;
  const std::string& line = target.file_form.import_path;
  const std::string directive = line.substr(0, line.find("{path}"));
  const auto found = content.find(directive);
  if (found != std::string::npos) {
    const auto start = directive.find_first_not_of('\n');
    content.insert(found + (start == std::string::npos ? 0 : start), "// ");
  }
  return content;
}

std::string client_name(ClientApi client) {
  return client == ClientApi::vulkan ? "vulkan" : client == ClientApi::opengl ? "opengl" : "opengl_es";
}
std::string stage_name(ShaderStage stage) {
  return stage == ShaderStage::compute ? "compute" : stage == ShaderStage::fragment ? "fragment" : "vertex";
}

}  // namespace

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

std::vector<SourcePiece> validation_sources(const Catalogue& catalogue, const EmissionMarker& marker, const std::string& file_name,
                                            const std::string& content, ShaderStage stage) {
  const TargetSyntax target =
      builtin_target(marker.target.table).with_precision(marker.precision).with_prefix(marker.prefix, macro_prefix(marker.prefix));
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
  const std::string calls = print_glue(target, catalogue, calls_in_dialect(catalogue, functions, stage), names, validation_glue_symbols());

  const std::string core_only = macro_prefix(marker.prefix) + "CORE_ONLY";
  const auto fill = [&](std::string text) {
    return substitute_type_placeholders(substitute(std::move(text), "{core_only_macro}", core_only), target);
  };
  std::vector<SourcePiece> pieces;
  const std::string prologue = fill(skeleton.prologue);
  if (!prologue.empty()) pieces.push_back({"saagen-validation-prologue", prologue});
  // An include needs its resources declared before it; a module opens with its enable directives.
  const std::string resources = resource_declarations(target, catalogue, functions);
  if (!resources.empty() && !target.resources_after_file) pieces.push_back({"saagen-validation-resources", resources});
  pieces.push_back({file_name, without_import_path(target, content)});
  if (!resources.empty() && target.resources_after_file) pieces.push_back({"saagen-validation-resources", resources});
  pieces.push_back({"saagen-validation-main", substitute(fill(skeleton.epilogue), "{calls}", calls)});
  return pieces;
}

FileValidation validate_file(const Catalogue& catalogue, const std::string& file_name, const std::string& content) {
  const auto marker = find_marker(content);
  if (!marker) throw Error(fmt::format("{}: no saagen marker line; this file was not written by `saagen emit`", file_name));
  const TargetSyntax target = builtin_target(marker->target.table).with_precision(marker->precision);
  if (!target.language->compiled_in_process()) return validate_wgsl_files(catalogue, {{file_name, content}}).front();

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

namespace saagen {
namespace {

// The runner that the program installed (install_webgpu_runner), or none.
WebGpuRunner& installed_webgpu_runner() {
  static WebGpuRunner runner;
  return runner;
}

nlohmann::json run_webgpu_jobs(const nlohmann::json& jobs) {
  const WebGpuRunner& runner = installed_webgpu_runner();
  if (!runner) {
    throw Error(
        "WGSL validation needs a WebGPU runner, and this program installed none: the saagen command line installs the harness's "
        "(saagen::harness::install_webgpu_runner)");
  }
  return runner(jobs);
}

// The number of lines before the emitted file in a validation module, to report its own lines.
int lines_before(const std::vector<SourcePiece>& pieces, const std::string& file_name) {
  int lines = 0;
  for (const SourcePiece& piece : pieces) {
    if (piece.name == file_name) break;
    lines += static_cast<int>(std::count(piece.text.begin(), piece.text.end(), '\n'));
  }
  return lines;
}

// One Tint message as "file:line:column: type: message", lines of the emitted file counted in it.
std::string describe_message(const nlohmann::json& message, const std::string& file_name, int offset, int file_lines) {
  const int line = message.value("line", 0);
  const int column = message.value("column", 0);
  const std::string place = line > offset && line <= offset + file_lines
                                ? fmt::format("{}:{}:{}", file_name, line - offset, column)
                                : fmt::format("{} (validation module line {}:{})", file_name, line, column);
  return fmt::format("{}: {}: {}\n", place, message.value("type", "error"), message.value("message", ""));
}

}  // namespace

void install_webgpu_runner(WebGpuRunner runner) { installed_webgpu_runner() = std::move(runner); }

std::vector<FileValidation> validate_wgsl_files(const Catalogue& catalogue, const std::vector<std::pair<std::string, std::string>>& files) {
  struct Module {
    std::size_t file;
    std::string check;
    int offset;
    int file_lines;
  };
  std::vector<Module> modules;
  nlohmann::json jobs = nlohmann::json::array();
  for (std::size_t index = 0; index < files.size(); ++index) {
    const auto& [file_name, content] = files[index];
    const auto marker = find_marker(content);
    if (!marker) throw Error(fmt::format("{}: no saagen marker line; this file was not written by `saagen emit`", file_name));
    const int file_lines = static_cast<int>(std::count(content.begin(), content.end(), '\n'));
    for (const ShaderStage stage : {ShaderStage::fragment, ShaderStage::compute}) {
      const auto pieces = validation_sources(domain_catalogue(catalogue, marker->domain), *marker, file_name, content, stage);
      const std::string entry = stage == ShaderStage::fragment ? "saagen_validate_fragment" : "saagen_validate_compute";
      const std::string stage_word = stage == ShaderStage::fragment ? "fragment" : "compute";
      jobs.push_back({{"id", fmt::format("m{}", modules.size())},
                      {"kind", "compile"},
                      {"code", joined_source(pieces)},
                      {"entry_points", nlohmann::json::array({{{"stage", stage_word}, {"name", entry}}})}});
      modules.push_back({index, "tint " + stage_word, lines_before(pieces, file_name), file_lines});
    }
  }
  const nlohmann::json results = run_webgpu_jobs(jobs);
  std::vector<FileValidation> validations;
  for (const auto& [file_name, content] : files) validations.push_back({file_name, {}});
  const auto& list = results.at("results");
  const auto features = results.value("features", nlohmann::json::array());
  const bool has_f16 = std::find(features.begin(), features.end(), "shader-f16") != features.end();
  for (std::size_t index = 0; index < modules.size(); ++index) {
    const Module& module = modules[index];
    // An f16 module compiles only on a device with shader-f16: without it, it is not judged.
    if (!has_f16 && is_half(find_marker(files[module.file].second)->precision)) {
      validations[module.file].checks.push_back({module.check + " skipped: the WebGPU adapter offers no shader-f16", true, "", 0});
      continue;
    }
    const nlohmann::json& result = list.at(index);
    const std::string& file_name = files[module.file].first;
    std::string log;
    for (const auto& message : result.value("messages", nlohmann::json::array())) {
      if (message.value("type", "") != "info") log += describe_message(message, file_name, module.offset, module.file_lines);
    }
    for (const auto& error : result.value("pipeline_errors", nlohmann::json::array()))
      log += fmt::format("{}: {}\n", file_name, error.get<std::string>());
    if (result.contains("error") && log.empty()) log = fmt::format("{}: {}\n", file_name, result.at("error").get<std::string>());
    validations[module.file].checks.push_back({module.check, log.empty(), log, 0});
  }
  return validations;
}

}  // namespace saagen

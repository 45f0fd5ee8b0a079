#include "saagen/products/spirv_library.hpp"

#include "saagen/emit/engines.hpp"
#include "saagen/emit/listing.hpp"
#include "saagen/error.hpp"
#include "saagen/target/target.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

namespace saagen {
namespace {

constexpr std::uint32_t spirv_magic = 0x07230203u;

// The universal environment of the module's SPIR-V version (the assembler writes that version).
spv_target_env universal_env(const std::vector<std::uint32_t>& words) {
  const std::uint32_t version = words.size() > 1 ? words[1] : 0;
  switch (version) {
    case 0x00010000u:
      return SPV_ENV_UNIVERSAL_1_0;
    case 0x00010100u:
      return SPV_ENV_UNIVERSAL_1_1;
    case 0x00010200u:
      return SPV_ENV_UNIVERSAL_1_2;
    case 0x00010300u:
      return SPV_ENV_UNIVERSAL_1_3;
    case 0x00010400u:
      return SPV_ENV_UNIVERSAL_1_4;
    case 0x00010500u:
      return SPV_ENV_UNIVERSAL_1_5;
    case 0x00010600u:
      return SPV_ENV_UNIVERSAL_1_6;
    default:
      return SPV_ENV_UNIVERSAL_1_3;
  }
}

std::string env_name(spv_target_env env) {
  switch (env) {
    case SPV_ENV_UNIVERSAL_1_0:
      return "1.0";
    case SPV_ENV_UNIVERSAL_1_1:
      return "1.1";
    case SPV_ENV_UNIVERSAL_1_2:
      return "1.2";
    case SPV_ENV_UNIVERSAL_1_3:
      return "1.3";
    case SPV_ENV_UNIVERSAL_1_4:
      return "1.4";
    case SPV_ENV_UNIVERSAL_1_5:
      return "1.5";
    case SPV_ENV_UNIVERSAL_1_6:
      return "1.6";
    default:
      return "?";
  }
}

// Collects SPIRV-Tools diagnostics into one string.
class Messages {
 public:
  void attach(spvtools::SpirvTools& tools) { tools.SetMessageConsumer(consumer()); }
  void attach(spvtools::Optimizer& optimizer) { optimizer.SetMessageConsumer(consumer()); }
  const std::string& text() const { return text_; }

 private:
  spvtools::MessageConsumer consumer() {
    return [this](spv_message_level_t, const char*, const spv_position_t& position, const char* message) {
      text_ += fmt::format("{}{}: {}", text_.empty() ? "" : "; ",
                           position.index ? fmt::format("word {}", position.index) : fmt::format("line {}", position.line), message);
    };
  }
  std::string text_;
};

// One instruction of the disassembly (numeric ids, no header): "%5 = OpLabel", "OpCapability Shader".
struct Instruction {
  std::string text;
  std::string result;                 // "%5", or empty
  std::string opcode;                 // "OpLabel"
  std::vector<std::string> operands;  // the tokens after the opcode; strings keep their quotes
};

// Splits text into whitespace-separated tokens; a quoted string (with \" and \\ escapes, and
// any other character, newlines included) is one token.
std::vector<std::string> tokens_of(std::string_view text) {
  std::vector<std::string> tokens;
  std::string current;
  bool quoted = false;
  for (std::size_t index = 0; index < text.size(); ++index) {
    const char c = text[index];
    if (quoted) {
      current += c;
      if (c == '\\' && index + 1 < text.size())
        current += text[++index];
      else if (c == '"')
        quoted = false;
      continue;
    }
    if (c == '"') {
      quoted = true;
      current += c;
    } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      if (!current.empty()) tokens.push_back(std::move(current));
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) tokens.push_back(std::move(current));
  return tokens;
}

Instruction parse_instruction(std::string text) {
  Instruction instruction;
  auto tokens = tokens_of(text);
  std::size_t first = 0;
  if (tokens.size() >= 3 && tokens[1] == "=") {
    instruction.result = tokens[0];
    first = 2;
  }
  if (first < tokens.size()) instruction.opcode = tokens[first];
  instruction.operands.assign(tokens.begin() + static_cast<std::ptrdiff_t>(std::min(first + 1, tokens.size())), tokens.end());
  instruction.text = std::move(text);
  return instruction;
}

// One instruction per line, except that a newline inside a quoted string belongs to it.
std::vector<Instruction> parse_module_text(const std::string& text) {
  std::vector<Instruction> instructions;
  std::string current;
  bool quoted = false;
  for (std::size_t index = 0; index < text.size(); ++index) {
    const char c = text[index];
    if (quoted && c == '\\' && index + 1 < text.size()) {
      current += c;
      current += text[++index];
      continue;
    }
    if (c == '"') quoted = !quoted;
    if (c == '\n' && !quoted) {
      if (current.find_first_not_of(" \t\r") != std::string::npos) instructions.push_back(parse_instruction(std::move(current)));
      current.clear();
      continue;
    }
    current += c;
  }
  if (current.find_first_not_of(" \t\r") != std::string::npos) instructions.push_back(parse_instruction(std::move(current)));
  return instructions;
}

std::string module_text(const std::vector<Instruction>& instructions) {
  std::string text;
  for (const Instruction& instruction : instructions) text += instruction.text + "\n";
  return text;
}

// The string literal for SPIR-V assembly.
std::string assembly_string(std::string_view value) {
  std::string out = "\"";
  for (const char c : value) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// The unquoted value of a string token.
std::string string_value(const std::string& token) {
  if (token.size() < 2 || token.front() != '"') return token;
  std::string out;
  for (std::size_t index = 1; index + 1 < token.size(); ++index) {
    if (token[index] == '\\' && index + 2 < token.size()) ++index;
    out += token[index];
  }
  return out;
}

bool is_module_prefix(const std::string& opcode) {
  static const std::set<std::string> prefix = {
      "OpCapability", "OpExtension",       "OpExtInstImport", "OpMemoryModel",     "OpEntryPoint", "OpExecutionMode", "OpExecutionModeId",
      "OpString",     "OpSourceExtension", "OpSource",        "OpSourceContinued", "OpName",       "OpMemberName",    "OpModuleProcessed"};
  return prefix.count(opcode) != 0;
}

// Index just after the debug section (the place of the first annotation).
std::size_t annotations_start(const std::vector<Instruction>& instructions) {
  std::size_t position = 0;
  for (std::size_t index = 0; index < instructions.size(); ++index) {
    if (is_module_prefix(instructions[index].opcode))
      position = index + 1;
    else
      break;
  }
  return position;
}

std::size_t after_last_capability(const std::vector<Instruction>& instructions) {
  std::size_t position = 0;
  for (std::size_t index = 0; index < instructions.size(); ++index) {
    if (instructions[index].opcode == "OpCapability") position = index + 1;
  }
  return position;
}

bool has_capability(const std::vector<Instruction>& instructions, std::string_view capability) {
  return std::any_of(instructions.begin(), instructions.end(), [&](const Instruction& instruction) {
    return instruction.opcode == "OpCapability" && !instruction.operands.empty() && instruction.operands[0] == capability;
  });
}

// Instructions that name or decorate an id (the first operand is the target).
bool targets_id(const Instruction& instruction, const std::set<std::string>& ids) {
  static const std::set<std::string> naming = {
      "OpName", "OpMemberName", "OpDecorate", "OpMemberDecorate", "OpDecorateId", "OpDecorateString", "OpMemberDecorateString"};
  return naming.count(instruction.opcode) && !instruction.operands.empty() && ids.count(instruction.operands[0]);
}

// The result ids of the OpFunction whose OpName is "<name>(...", glslang's mangled name.
std::vector<std::string> functions_named(const std::vector<Instruction>& instructions, const std::string& name) {
  std::set<std::string> function_ids;
  for (const Instruction& instruction : instructions) {
    if (instruction.opcode == "OpFunction") function_ids.insert(instruction.result);
  }
  std::vector<std::string> ids;
  for (const Instruction& instruction : instructions) {
    if (instruction.opcode != "OpName" || instruction.operands.size() < 2) continue;
    const std::string value = string_value(instruction.operands[1]);
    if (value.rfind(name + "(", 0) == 0 && function_ids.count(instruction.operands[0])) ids.push_back(instruction.operands[0]);
  }
  return ids;
}

// A readable description of every type id: f32, vec3<f32>, ptr<Function, vec3<f32>>, ...
std::map<std::string, std::string> type_descriptions(const std::vector<Instruction>& instructions) {
  std::map<std::string, std::string> types;
  const auto describe = [&types](const std::string& id) {
    const auto found = types.find(id);
    return found == types.end() ? id : found->second;
  };
  for (const Instruction& instruction : instructions) {
    const auto& op = instruction.operands;
    if (instruction.opcode == "OpTypeVoid")
      types[instruction.result] = "void";
    else if (instruction.opcode == "OpTypeBool")
      types[instruction.result] = "bool";
    else if (instruction.opcode == "OpTypeInt" && op.size() >= 2)
      types[instruction.result] = (op[1] == "1" ? "i" : "u") + op[0];
    else if (instruction.opcode == "OpTypeFloat" && !op.empty())
      types[instruction.result] = "f" + op[0];
    else if (instruction.opcode == "OpTypeVector" && op.size() >= 2)
      types[instruction.result] = fmt::format("vec{}<{}>", op[1], describe(op[0]));
    else if (instruction.opcode == "OpTypePointer" && op.size() >= 2)
      types[instruction.result] = fmt::format("ptr<{}, {}>", op[0], describe(op[1]));
    else if (instruction.opcode == "OpTypeFunction" && !op.empty()) {
      std::vector<std::string> parameters;
      for (std::size_t index = 1; index < op.size(); ++index) parameters.push_back(describe(op[index]));
      types[instruction.result] = fmt::format("{}({})", describe(op[0]), fmt::join(parameters, ", "));
    }
  }
  return types;
}

std::vector<std::uint32_t> run_dead_code_passes(const std::vector<std::uint32_t>& words) {
  spvtools::Optimizer optimizer(universal_env(words));
  Messages messages;
  messages.attach(optimizer);
  // Exported functions are roots of both passes; nothing else is reachable once main is gone.
  optimizer.RegisterPass(spvtools::CreateEliminateDeadFunctionsPass());
  optimizer.RegisterPass(spvtools::CreateAggressiveDCEPass());
  optimizer.RegisterPass(spvtools::CreateEliminateDeadConstantPass());
  std::vector<std::uint32_t> optimized;
  if (!optimizer.Run(words.data(), words.size(), &optimized)) {
    throw Error(fmt::format("spirv-opt (dead-code passes) failed: {}", messages.text()));
  }
  return optimized;
}

std::string upper_identifier(std::string_view text) {
  std::string result;
  for (const char c : text)
    result += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : '_';
  return result;
}

// The exports of a module: LinkageAttributes "name" Export decorations.
std::vector<std::pair<std::string, std::string>> export_decorations(const std::vector<Instruction>& instructions) {
  std::vector<std::pair<std::string, std::string>> exports;  // id, name
  for (const Instruction& instruction : instructions) {
    const auto& op = instruction.operands;
    if (instruction.opcode == "OpDecorate" && op.size() >= 4 && op[1] == "LinkageAttributes" && op[3] == "Export") {
      exports.emplace_back(op[0], string_value(op[2]));
    }
  }
  return exports;
}

std::uint32_t numeric_id(const std::string& id) { return static_cast<std::uint32_t>(std::stoul(id.substr(1))); }

// The functions of `variant` a library exports: those without derivatives.
std::vector<std::string> exportable_functions(const Catalogue& catalogue, const Variant& variant) {
  std::vector<std::string> exported;
  for (const std::string& name : variant.functions) {
    if (!catalogue.find_function(name)->fragment_only) exported.push_back(name);
  }
  if (exported.empty()) throw Error(fmt::format("variant {} has no function without derivatives to export", variant.id));
  return exported;
}

// The module without its entry points, everything defined inside them, their execution modes and
// the workgroup size that belongs to the removed compute entry point (a consumer declares its own).
std::vector<Instruction> without_entry_points(std::vector<Instruction> instructions) {
  std::set<std::string> dead;
  for (const Instruction& instruction : instructions) {
    if (instruction.opcode == "OpEntryPoint" && instruction.operands.size() >= 2) dead.insert(instruction.operands[1]);
  }
  std::vector<Instruction> kept;
  bool inside_entry = false;
  for (Instruction& instruction : instructions) {
    if (instruction.opcode == "OpFunction" && dead.count(instruction.result)) inside_entry = true;
    if (inside_entry) {
      if (!instruction.result.empty()) dead.insert(instruction.result);
      if (instruction.opcode == "OpFunctionEnd") inside_entry = false;
      continue;
    }
    if (instruction.opcode == "OpEntryPoint" || instruction.opcode == "OpExecutionMode" || instruction.opcode == "OpExecutionModeId")
      continue;
    kept.push_back(std::move(instruction));
  }
  std::erase_if(kept, [&dead](const Instruction& instruction) {
    return targets_id(instruction, dead) || (instruction.opcode == "OpDecorate" && instruction.operands.size() >= 3 &&
                                             instruction.operands[1] == "BuiltIn" && instruction.operands[2] == "WorkgroupSize");
  });
  return kept;
}

// Marks each exported function with an Export linkage attribute, records the marker line as an
// OpModuleProcessed and declares the Linkage capability.
void decorate_exports(std::vector<Instruction>& kept, const std::vector<std::string>& exported, const SpirvLibrary& library) {
  std::vector<Instruction> decorations;
  for (const std::string& name : exported) {
    const std::string emitted = prefixed_name(library.marker.prefix, name);
    const auto ids = functions_named(kept, emitted);
    if (ids.size() != 1) {
      throw Error(fmt::format("{}: glslang's module has {} definitions of {} (expected one); cannot export it", library.file_name,
                              ids.size(), emitted));
    }
    decorations.push_back(parse_instruction(fmt::format("OpDecorate {} LinkageAttributes {} Export", ids[0], assembly_string(emitted))));
  }
  const std::size_t annotations = annotations_start(kept);
  decorations.insert(decorations.begin(), parse_instruction("OpModuleProcessed " + assembly_string(marker_line(library.marker) + "\n")));
  kept.insert(kept.begin() + static_cast<std::ptrdiff_t>(annotations), decorations.begin(), decorations.end());
  if (!has_capability(kept, "Linkage")) {
    kept.insert(kept.begin() + static_cast<std::ptrdiff_t>(after_last_capability(kept)), parse_instruction("OpCapability Linkage"));
  }
}

// The exports and their SPIR-V function types, read back from the final module.
std::vector<SpirvExport> read_exports(const std::vector<Instruction>& final_instructions, const std::vector<std::string>& exported,
                                      const std::string& prefix) {
  const auto types = type_descriptions(final_instructions);
  std::map<std::string, std::string> function_types;  // id -> description
  for (const Instruction& instruction : final_instructions) {
    if (instruction.opcode == "OpFunction" && instruction.operands.size() >= 3) {
      const auto found = types.find(instruction.operands[2]);
      function_types[instruction.result] = found == types.end() ? instruction.operands[2] : found->second;
    }
  }
  const auto decorated = export_decorations(final_instructions);
  std::vector<SpirvExport> exports;
  for (const std::string& name : exported) {
    const std::string emitted = prefixed_name(prefix, name);
    const auto found = std::find_if(decorated.begin(), decorated.end(), [&](const auto& entry) { return entry.second == emitted; });
    exports.push_back({emitted, name, numeric_id(found->first), function_types[found->first]});
  }
  return exports;
}

// Reflection: the `saagen list --json` entries of the exported functions plus their SPIR-V types.
nlohmann::json library_reflection(const Catalogue& base_catalogue, const EmitOptions& options, const Variant& variant,
                                  const SpirvLibrary& library, const std::vector<Instruction>& final_instructions) {
  const nlohmann::json catalogue_entry = catalogue_json(base_catalogue, library.marker.prefix, options.domain);
  nlohmann::json functions = nlohmann::json::array();
  for (const SpirvExport& entry : library.exports) {
    for (const auto& json_variant : catalogue_entry.at("variants")) {
      if (json_variant.at("id") != variant.id) continue;
      for (const auto& function : json_variant.at("functions")) {
        if (function.at("name") != entry.template_name) continue;
        nlohmann::json exported_function = function;
        exported_function["linkage_name"] = entry.name;
        exported_function["spirv_type"] = entry.spirv_type;
        functions.push_back(std::move(exported_function));
      }
    }
  }
  nlohmann::json capabilities = nlohmann::json::array();
  for (const Instruction& instruction : final_instructions) {
    if (instruction.opcode == "OpCapability" && !instruction.operands.empty()) capabilities.push_back(instruction.operands[0]);
  }
  nlohmann::json option_values = nlohmann::json::object();
  for (const auto& [option, value] : library.marker.option_values) option_values[option] = value;
  return {{"saagen_version", std::string(version())},
          {"module", library.file_name},
          {"variant", variant.id},
          {"prefix", library.marker.prefix},
          {"precision", to_string(library.marker.precision)},
          {"guards", library.marker.guards},
          {"options", option_values},
          {"spirv_version", env_name(universal_env(library.words))},
          {"capabilities", capabilities},
          {"calling_convention",
           "glslang's: every parameter is an OpTypePointer Function to its value type; the result is returned by "
           "value. Imports must declare exactly spirv_type."},
          {"exports", functions}};
}

// `base_catalogue`'s variant, compiled from its GLSL emission in options.domain: the exports are
// the functions as emitted in that domain (the domain wrappers where roughness goes in and out).
SpirvLibrary build_library(const Catalogue& base_catalogue, const EmitOptions& options, const Variant& base_variant) {
  EmitOptions glsl = options;  // the emission of the library's source target (spirv_library_target)
  glsl.target = spirv_library_target().name;
  glsl.variants = {base_variant.id};
  const EmittedFile file = emit_variants(base_catalogue, glsl).front();
  const Catalogue& catalogue = domain_catalogue(base_catalogue, options.domain);
  const Variant& variant = catalogue.variant(base_variant.id);

  CompileRequest request;
  request.language = spirv_library_target().language;
  request.stage = ShaderStage::compute;
  request.client = ClientApi::vulkan;
  // The validation skeleton: the file under <PREFIX>CORE_ONLY and a main that calls every
  // function without derivatives once, with arguments loaded from a buffer, so that glslang
  // emits every function (it does not inline without the optimizer).
  request.sources = validation_sources(catalogue, file.marker, file.file_name, file.content, ShaderStage::compute);
  const CompileResult compiled = compile_to_spirv(request);
  if (!compiled.ok) throw Error(fmt::format("{}: the SPIR-V library does not compile: {}", file.file_name, compiled.log));
  const std::vector<std::string> exported = exportable_functions(catalogue, variant);

  SpirvLibrary library;
  library.marker = file.marker;
  library.marker.target = OutputTarget::product(OutputKind::spirv_library);
  const std::string stem = file.file_name.substr(0, file.file_name.rfind('.'));
  library.file_name = stem + ".spv";
  library.header_name = stem + ".spv.h";

  std::vector<Instruction> kept = without_entry_points(parse_module_text(disassemble_spirv(compiled.spirv)));
  decorate_exports(kept, exported, library);
  library.words = run_dead_code_passes(assemble_spirv(module_text(kept)));
  std::vector<std::string> exported_names;
  for (const std::string& name : exported) exported_names.push_back(prefixed_name(library.marker.prefix, name));
  if (const std::string problems = validate_spirv_library(library.words, exported_names); !problems.empty()) {
    throw Error(fmt::format("{}: the library module is invalid: {}", library.file_name, problems));
  }

  const auto final_instructions = parse_module_text(disassemble_spirv(library.words));
  library.exports = read_exports(final_instructions, exported, library.marker.prefix);
  library.reflection = library_reflection(base_catalogue, options, variant, library, final_instructions);
  return library;
}

}  // namespace

std::string disassemble_spirv(const std::vector<std::uint32_t>& words) {
  spvtools::SpirvTools tools(universal_env(words));
  Messages messages;
  messages.attach(tools);
  std::string text;
  if (!tools.Disassemble(words, &text, SPV_BINARY_TO_TEXT_OPTION_NO_HEADER)) {
    throw Error(fmt::format("spirv-dis failed: {}", messages.text()));
  }
  return text;
}

std::vector<std::uint32_t> assemble_spirv(const std::string& text) {
  // The version of the text's module is not in the text; every module saagen edits is SPIR-V
  // 1.3 (Vulkan 1.1), which the universal 1.3 environment writes.
  spvtools::SpirvTools tools(SPV_ENV_UNIVERSAL_1_3);
  Messages messages;
  messages.attach(tools);
  std::vector<std::uint32_t> words;
  if (!tools.Assemble(text, &words, SPV_TEXT_TO_BINARY_OPTION_PRESERVE_NUMERIC_IDS)) {
    throw Error(fmt::format("spirv-as failed: {}", messages.text()));
  }
  return words;
}

std::vector<SpirvLibrary> emit_spirv_libraries(const Catalogue& catalogue, const EmitOptions& options) {
  validate_prefix(options.prefix);
  const bool converted = options.domain != Domain::alpha2;
  if (!spirv_library_target().precisions.count(options.precision)) {
    throw Error(fmt::format("the spirv target compiles the GLSL emission, which has no precision '{}'; choose one of: {}",
                            to_string(options.precision), fmt::join(precision_names(spirv_library_target().precision_kinds()), ", ")));
  }
  // The variants a module can hold (spirv_library_variants); unnamed, in another domain, those with
  // a roughness in and out (as `emit` does).
  std::vector<const Variant*> variants;
  for (const std::string& id : spirv_library_variants(catalogue, options.variants)) {
    const Variant* variant = catalogue.find_variant(id);
    if (!variant) {
      std::vector<std::string> ids;
      for (const Variant& known : catalogue.variants()) ids.push_back(known.id);
      throw Error(fmt::format("unknown variant '{}'; choose one of: {}", id, fmt::join(ids, ", ")));
    }
    if (options.variants.empty() && converted && !variant_has_roughness_io(catalogue, *variant)) continue;
    variants.push_back(variant);
  }
  std::vector<SpirvLibrary> libraries;
  for (const Variant* variant : variants) libraries.push_back(build_library(catalogue, options, *variant));
  return libraries;
}

std::string spirv_library_header(const Catalogue& base_catalogue, const SpirvLibrary& library) {
  const Catalogue& catalogue = domain_catalogue(base_catalogue, library.marker.domain);
  const Variant& variant = *catalogue.find_variant(library.marker.variants.front());
  const std::string stem = library.file_name.substr(0, library.file_name.rfind('.'));
  const std::string guard = upper_identifier(library.header_name);
  const std::string qualifier_macro = macro_prefix(library.marker.prefix) + "SPV_CONST";
  const std::size_t instructions = count_spirv_instructions(library.words);

  std::ostringstream out;
  out << fmt::format("// Generated by saagen {} -- do not edit; regenerate with `saagen emit --target spirv`.\n", version());
  out << marker_line(library.marker) << "\n//\n";
  out << fmt::format("// {}: the SPIR-V library module of variant {} -- {}\n", library.file_name, variant.id, variant.summary);
  out << fmt::format("//   {} -- {}; domain: {}\n", variant.paper, variant.equation, variant.domain);
  out << fmt::format("// SPIR-V {}, Logical addressing, GLSL450 memory model, capabilities {}; no entry point.\n",
                     library.reflection.at("spirv_version").get<std::string>(),
                     fmt::join(library.reflection.at("capabilities").get<std::vector<std::string>>(), ", "));
  out << fmt::format("// {} words ({} bytes), {} instructions. Exported functions (LinkageAttributes ... Export):\n", library.words.size(),
                     library.words.size() * 4, instructions);
  for (const SpirvExport& entry : library.exports) {
    const Function& function = *catalogue.find_function(entry.template_name);
    std::vector<std::string> parameters;
    for (const Parameter& parameter : function.parameters) parameters.push_back(parameter.type + " " + parameter.name);
    out << fmt::format("//   {} {}({})\n//     SPIR-V type {}\n", function.return_type, entry.name, fmt::join(parameters, ", "),
                       entry.spirv_type);
  }
  out << "// Link it with a module that declares these functions with LinkageAttributes \"<name>\" Import\n"
         "// (spvtools::Link or spirv-link); each parameter is a pointer to a Function-storage variable,\n"
         "// as glslang passes arguments. The reflection JSON below lists names, parameters and types.\n";
  out << fmt::format("\n#ifndef {0}\n#define {0}\n\n#include <stddef.h>\n#include <stdint.h>\n\n", guard);
  out << fmt::format("#ifndef {0}\n#ifdef __cplusplus\n#define {0} inline constexpr\n#else\n#define {0} static const\n#endif\n#endif\n\n",
                     qualifier_macro);
  out << fmt::format("{} uint32_t {}_spv[{}] = {{\n{}}};\n", qualifier_macro, stem, library.words.size(),
                     spirv_c_initializer(library.words));
  out << fmt::format("{} size_t {}_spv_word_count = {};\n", qualifier_macro, stem, library.words.size());
  out << fmt::format("{} size_t {}_spv_size_bytes = {};\n\n", qualifier_macro, stem, library.words.size() * 4);
  out << fmt::format("// The reflection of the exported functions (JSON).\n{} char {}_spv_reflection_json[] =\n{};\n", qualifier_macro,
                     stem, c_string_literal_lines(library.reflection.dump(2) + "\n"));
  out << fmt::format("\n#endif  // {}\n", guard);
  return out.str();
}

std::string validate_spirv_library(const std::vector<std::uint32_t>& words, const std::vector<std::string>& exports) {
  if (words.size() < 5 || words[0] != spirv_magic) return "not a SPIR-V module";
  spvtools::SpirvTools tools(universal_env(words));
  Messages messages;
  messages.attach(tools);
  if (!tools.Validate(words)) return "spirv-val: " + messages.text();
  std::vector<std::string> problems;
  const auto instructions = parse_module_text(disassemble_spirv(words));
  if (!has_capability(instructions, "Linkage")) problems.push_back("no Linkage capability");
  if (std::any_of(instructions.begin(), instructions.end(), [](const Instruction& i) { return i.opcode == "OpEntryPoint"; })) {
    problems.push_back("a library module has no entry point, this one has");
  }
  const auto decorated = export_decorations(instructions);
  for (const std::string& name : exports) {
    if (std::none_of(decorated.begin(), decorated.end(), [&](const auto& entry) { return entry.second == name; })) {
      problems.push_back(fmt::format("{} is not exported", name));
    }
  }
  return fmt::format("{}", fmt::join(problems, "; "));
}

std::vector<std::uint32_t> import_stub_functions(const std::vector<std::uint32_t>& words, const std::vector<std::string>& names) {
  auto instructions = parse_module_text(disassemble_spirv(words));
  std::map<std::string, std::string> imports;  // id -> name
  for (const std::string& name : names) {
    const auto ids = functions_named(instructions, name);
    if (ids.size() != 1) throw Error(fmt::format("the module has {} definitions of {} (expected one stub)", ids.size(), name));
    imports[ids[0]] = name;
  }
  std::vector<Instruction> prefix, declarations, definitions;
  std::set<std::string> dead;
  std::vector<Instruction>* function = nullptr;
  bool stub = false;
  for (Instruction& instruction : instructions) {
    if (instruction.opcode == "OpFunction") {
      stub = imports.count(instruction.result) != 0;
      function = stub ? &declarations : &definitions;
      function->push_back(std::move(instruction));
      continue;
    }
    if (!function) {
      prefix.push_back(std::move(instruction));
      continue;
    }
    const bool end = instruction.opcode == "OpFunctionEnd";
    if (!stub || end || instruction.opcode == "OpFunctionParameter")
      function->push_back(std::move(instruction));
    else if (!instruction.result.empty())
      dead.insert(instruction.result);
    if (end) function = nullptr;
  }
  std::erase_if(prefix, [&dead](const Instruction& instruction) { return targets_id(instruction, dead); });
  std::vector<Instruction> decorations;
  for (const auto& [id, name] : imports) {
    decorations.push_back(parse_instruction(fmt::format("OpDecorate {} LinkageAttributes {} Import", id, assembly_string(name))));
  }
  prefix.insert(prefix.begin() + static_cast<std::ptrdiff_t>(annotations_start(prefix)), decorations.begin(), decorations.end());
  if (!has_capability(prefix, "Linkage")) {
    prefix.insert(prefix.begin() + static_cast<std::ptrdiff_t>(after_last_capability(prefix)), parse_instruction("OpCapability Linkage"));
  }
  // Declarations precede every definition (SPIR-V's logical layout).
  prefix.insert(prefix.end(), std::make_move_iterator(declarations.begin()), std::make_move_iterator(declarations.end()));
  prefix.insert(prefix.end(), std::make_move_iterator(definitions.begin()), std::make_move_iterator(definitions.end()));
  return assemble_spirv(module_text(prefix));
}

std::string glsl_import_stubs(const Catalogue& catalogue, const std::vector<std::string>& functions, std::string_view prefix,
                              Precision precision) {
  const TargetSyntax target = spirv_library_target().with_precision(precision);
  std::string stubs;
  for (const std::string& name : functions) {
    const Function* function = catalogue.find_function(name);
    if (!function) throw Error(fmt::format("unknown function '{}'", name));
    std::vector<std::string> parameters;
    for (const Parameter& parameter : function->parameters) parameters.push_back(target.types.at(parameter.type) + " " + parameter.name);
    const std::string& result = target.types.at(function->return_type);
    stubs += fmt::format("{} {}({}) {{ return {}(0); }}\n", result, prefixed_name(prefix, name), fmt::join(parameters, ", "), result);
  }
  return stubs;
}

std::vector<std::uint32_t> add_module_processed(const std::vector<std::uint32_t>& words, std::string_view text) {
  auto instructions = parse_module_text(disassemble_spirv(words));
  instructions.insert(instructions.begin() + static_cast<std::ptrdiff_t>(annotations_start(instructions)),
                      parse_instruction("OpModuleProcessed " + assembly_string(text)));
  return assemble_spirv(module_text(instructions));
}

std::vector<std::uint32_t> add_source_extension(const std::vector<std::uint32_t>& words, std::string_view text) {
  // Spliced into the binary (the header, version included, stays as it is) before the first
  // instruction after the mode-setting section: capabilities, extensions, imports, memory
  // model, entry points and execution modes.
  static const std::set<std::uint32_t> mode_setting = {17, 10, 11, 14, 15, 16, 331};
  constexpr std::uint32_t op_source_extension = 4;
  std::size_t position = 5;
  while (position < words.size() && mode_setting.count(words[position] & 0xffffu) && (words[position] >> 16) != 0) {
    position += words[position] >> 16;
  }
  if (words.size() < 5 || position > words.size()) throw Error("not a SPIR-V module: truncated instruction stream");
  std::vector<std::uint32_t> literal((text.size() + 4) / 4, 0u);  // NUL-terminated, padded to a word
  for (std::size_t index = 0; index < text.size(); ++index) {
    literal[index / 4] |= std::uint32_t(static_cast<unsigned char>(text[index])) << (8 * (index % 4));
  }
  std::vector<std::uint32_t> result(words.begin(), words.begin() + static_cast<std::ptrdiff_t>(position));
  result.push_back(static_cast<std::uint32_t>((literal.size() + 1) << 16) | op_source_extension);
  result.insert(result.end(), literal.begin(), literal.end());
  result.insert(result.end(), words.begin() + static_cast<std::ptrdiff_t>(position), words.end());
  return result;
}

std::string spirv_file_bytes(const std::vector<std::uint32_t>& words) {
  std::string bytes;
  bytes.reserve(words.size() * 4);
  for (const std::uint32_t word : words) {
    for (int shift = 0; shift < 32; shift += 8) bytes += static_cast<char>((word >> shift) & 0xffu);
  }
  return bytes;
}

std::vector<std::uint32_t> spirv_words_from_bytes(std::string_view bytes) {
  if (bytes.size() % 4 != 0 || bytes.size() < 20) throw Error("not a SPIR-V module: its size is not a multiple of 4 bytes, or too small");
  std::vector<std::uint32_t> words(bytes.size() / 4);
  for (std::size_t index = 0; index < words.size(); ++index) {
    std::uint32_t word = 0;
    for (int byte = 0; byte < 4; ++byte) word |= std::uint32_t(static_cast<unsigned char>(bytes[index * 4 + byte])) << (8 * byte);
    words[index] = word;
  }
  if (words[0] != spirv_magic) throw Error("not a little-endian SPIR-V module (bad magic number)");
  return words;
}

std::string spirv_c_initializer(const std::vector<std::uint32_t>& words) {
  std::string out;
  for (std::size_t index = 0; index < words.size(); ++index) {
    if (index % 6 == 0) out += "  ";
    out += fmt::format("0x{:08x}u,", words[index]);
    out += (index % 6 == 5 || index + 1 == words.size()) ? "\n" : " ";
  }
  return out;
}

std::string c_string_literal_lines(std::string_view text) {
  std::string out;
  std::string line = "  \"";
  for (const char c : text) {
    if (c == '"' || c == '\\')
      line += fmt::format("\\{}", c);
    else if (c == '\n') {
      out += line + "\\n\"\n";
      line = "  \"";
      continue;
    } else if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f)
      line += fmt::format("\\{:03o}", static_cast<unsigned char>(c));
    else
      line += c;
  }
  if (line != "  \"") out += line + "\"\n";
  if (out.empty()) out = "  \"\"\n";
  if (out.back() == '\n') out.pop_back();
  return out;
}

// The variants a SPIR-V library module can hold: a module cannot leave a resource (the glint
// dictionary) for its consumer to declare, so those variants are left out of "all variants" and
// rejected when named.
std::vector<std::string> spirv_library_variants(const Catalogue& catalogue, const std::vector<std::string>& named) {
  const auto reads_resource = [&](const Variant& variant) { return !resources_read(catalogue, variant.functions).empty(); };
  std::vector<std::string> ids;
  for (const Variant& variant : catalogue.variants()) {
    const bool asked = named.empty() || std::find(named.begin(), named.end(), variant.id) != named.end();
    if (!asked) continue;
    if (!reads_resource(variant)) {
      ids.push_back(variant.id);
    } else if (!named.empty()) {
      throw Error(
          fmt::format("--variant {}: a SPIR-V library module cannot leave the {} binding to the including shader; "
                      "emit it with --target glsl or hlsl",
                      variant.id, fmt::join(resources_read(catalogue, variant.functions), ", ")));
    }
  }
  for (const std::string& id : named) {
    if (!catalogue.find_variant(id)) ids.push_back(id);  // unknown ids keep the emitter's own message
  }
  return ids;
}

}  // namespace saagen

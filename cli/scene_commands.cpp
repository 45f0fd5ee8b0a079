#include "scene_commands.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/integrate/include_handler.hpp"
#include "saagen/io/input.hpp"
#include "saagen/io/output.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/products/spirv_library.hpp"
#include "saagen/scene/manifest.hpp"
#include "saagen/scene/planner.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/compiler.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

namespace saagen::cli {
namespace {

namespace fs = std::filesystem;

std::string read_source(const fs::path& path) { return read_input_file(path, source_size_limit, "a GLSL or HLSL source file"); }

// `#include "name"` on a line of its own: the name, else nullopt. `#include <name>` is an error.
std::optional<std::string> include_target(std::string_view line, const std::string& where) {
  std::size_t index = line.find_first_not_of(" \t");
  if (index == std::string_view::npos || line[index] != '#') return std::nullopt;
  index = line.find_first_not_of(" \t", index + 1);
  if (index == std::string_view::npos || line.substr(index, 7) != "include") return std::nullopt;
  index = line.find_first_not_of(" \t", index + 7);
  if (index == std::string_view::npos) throw Error(fmt::format("{}: #include names no file", where));
  const char open = line[index];
  // <saagen/...> names a snippet generated in memory (saagen/integrate/include_handler.hpp); "..." a file.
  if (open == '<' && line.substr(index + 1, 7) == "saagen/") {
    const auto close = line.find('>', index + 1);
    if (close == std::string_view::npos) throw Error(fmt::format("{}: unterminated #include", where));
    return std::string(line.substr(index + 1, close - index - 1));
  }
  if (open != '"') {
    throw Error(fmt::format(
        "{}: only #include \"FILE\" (searched next to the file, then in -I directories) and #include <saagen/...> are supported", where));
  }
  const auto close = line.find('"', index + 1);
  if (close == std::string_view::npos) throw Error(fmt::format("{}: unterminated #include", where));
  return std::string(line.substr(index + 1, close - index - 1));
}

// Expands #include "..." into named source pieces, so that compiler messages name the file
// and line they come from (a `#line` directive restarts the count after each include).
class IncludeExpander {
 public:
  explicit IncludeExpander(std::vector<std::string> directories) : directories_(std::move(directories)) {}

  void expand(const fs::path& file, int depth) {
    if (depth > 32) throw Error(fmt::format("{}: #include nested deeper than 32 (a cycle?)", file.string()));
    const std::string text = read_source(file);
    files_.push_back(file);
    if (const auto marker = find_marker(text)) {
      try {
        native_16bit_ = native_16bit_ || builtin_target(marker->target).with_precision(marker->precision).native_16bit;
      } catch (const Error&) {
        // Not a file this saagen can read the precision of; compile it as it is.
      }
    }
    std::string chunk;
    std::istringstream lines(text);
    int number = 0;
    for (std::string line; std::getline(lines, line);) {
      ++number;
      const auto included = include_target(line, fmt::format("{}:{}", file.string(), number));
      if (!included) {
        chunk += line + "\n";
        continue;
      }
      if (!chunk.empty()) pieces_.push_back({file.string(), chunk});
      if (is_saagen_include(*included))
        add_generated(*included, fmt::format("{}:{}", file.string(), number));
      else
        expand(resolve(*included, file, number), depth + 1);
      chunk = fmt::format("#line {}\n", number + 1);
    }
    if (!chunk.empty()) pieces_.push_back({file.string(), chunk});
  }

  std::vector<SourcePiece>& pieces() { return pieces_; }
  // Every file read: the input and what it includes.
  const std::vector<fs::path>& files() const { return files_; }
  bool native_16bit() const { return native_16bit_; }

 private:
  // A saagen/ name: the snippet generated in memory, as the include handlers resolve it.
  void add_generated(const std::string& name, const std::string& where) {
    EmittedFile file;
    try {
      file = resolve_include(name, {});
    } catch (const Error& error) {
      throw Error(fmt::format("{}: {}", where, error.what()));
    }
    native_16bit_ = native_16bit_ || builtin_target(file.marker.target).with_precision(file.marker.precision).native_16bit;
    pieces_.push_back({name, file.content});
  }

  fs::path resolve(const std::string& name, const fs::path& from, int line) const {
    std::vector<fs::path> candidates = {from.parent_path() / name};
    for (const std::string& directory : directories_) candidates.push_back(fs::path(directory) / name);
    for (const fs::path& candidate : candidates) {
      std::error_code error;
      if (fs::is_regular_file(candidate, error)) return candidate;
    }
    throw Error(fmt::format("{}:{}: #include \"{}\" not found next to the file or in the -I directories", from.string(), line, name));
  }

  std::vector<std::string> directories_;
  std::vector<SourcePiece> pieces_;
  std::vector<fs::path> files_;
  bool native_16bit_ = false;
};

// `compile -o` never names one of its inputs, not even with --force.
void check_not_an_input(const fs::path& output, const std::vector<fs::path>& inputs) {
  std::error_code error;
  for (const fs::path& input : inputs) {
    if (fs::equivalent(output, input, error)) {
      throw Error(fmt::format("{}: is an input of this compilation ({}); choose another output path", output.string(), input.string()));
    }
  }
}

// -I directories must exist: a typo would otherwise surface as a missing #include.
void check_include_directories(const std::vector<std::string>& directories) {
  for (const std::string& directory : directories) {
    std::error_code error;
    if (!fs::is_directory(directory, error)) {
      throw Error(fmt::format("-I {}: not a directory; pass an existing directory to search for #include files", directory));
    }
  }
}

// glslang's log as one line: its first error (which names the file and line), and how many
// more there are.
std::string first_compiler_message(const std::string& log) {
  std::vector<std::string> errors;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("ERROR: ", 0) == 0 && line.find("compilation errors.") == std::string::npos)
      errors.push_back(line.substr(7));
    else if (line.rfind("spirv-val: ", 0) == 0)
      errors.push_back(line);
  }
  if (errors.empty()) {
    const auto end = log.find('\n');
    return fmt::format("compilation to SPIR-V failed: {}", log.substr(0, end));
  }
  std::string first = errors.front();
  while (!first.empty() && first.back() == ' ') first.pop_back();
  return errors.size() == 1 ? first : fmt::format("{} (and {} more errors)", first, errors.size() - 1);
}

// The message as is when it starts with FILE:LINE:, else prefixed with the input's name.
std::string located(const fs::path& input, const std::string& message) {
  const auto colon = message.find(':');
  const bool has_location = colon != std::string::npos && colon + 1 < message.size() &&
                            std::isdigit(static_cast<unsigned char>(message[colon + 1])) && message.find(' ') > colon;
  return has_location ? message : fmt::format("{}: {}", input.string(), message);
}

// Whether the module has an OpEntryPoint (glslang's HLSL front end accepts a missing entry
// function and emits none).
bool has_entry_point(const std::vector<std::uint32_t>& words) {
  constexpr std::uint32_t op_entry_point = 15;
  for (std::size_t word = 5; word < words.size();) {
    const std::uint32_t length = words[word] >> 16;
    if ((words[word] & 0xffffu) == op_entry_point) return true;
    if (length == 0) break;
    word += length;
  }
  return false;
}

std::string_view stage_name(ShaderStage stage) {
  return stage == ShaderStage::vertex ? "vertex" : stage == ShaderStage::compute ? "compute" : "fragment";
}

}  // namespace

SceneCommands::SceneCommands(CLI::App& app, CLI::App* emit, const std::vector<CLI::Option*>& emit_exclusive) {
  plan_ = app.add_subcommand("plan", "Print, per material of a scene manifest, the variant chosen, why, what to call, and its cost");
  plan_->add_option("MANIFEST", plan_manifest_, "Scene manifest (TOML; see examples/scene.saagen.toml)");
  plan_->add_option("--trade-table", plan_trade_table_, "Measured trade table (JSON, as bench_shading --json writes); rules otherwise");
  plan_->add_flag("--no-cost", plan_no_cost_, "Skip compiling the cost kernels (optimized SPIR-V instruction counts)");
  plan_->add_flag("--rules", plan_rules_, "Print the planner's rules table");

  CLI::Option* manifest =
      emit->add_option("--manifest,-m", emit_manifest_, "Scene manifest: one bundle per target with only the functions its materials need");
  for (CLI::Option* option : emit_exclusive) manifest->excludes(option);
  emit->add_option("--trade-table", emit_trade_table_, "With --manifest: the measured trade table the planner reads")->needs(manifest);
  emit->add_flag("--list-outputs", emit_list_outputs_, "With --manifest: print the files it would write, one per line, and write nothing")
      ->needs(manifest);

  compile_ = app.add_subcommand(
      "compile",
      "Compile a shader (GLSL or HLSL; #include \"...\" resolved, #include <saagen/...> generated) to SPIR-V in-process, with spirv-val");
  compile_->add_option("FILE", compile_input_, "Shader source")->required();
  compile_->add_option("--output,-o", compile_output_, "SPIR-V output file")->required();
  compile_->add_option("--stage,-S", compile_stage_, "vert, frag or comp (default: from the extension .vert/.frag/.comp)")
      ->check(CLI::IsMember({"vert", "frag", "comp"}));
  compile_->add_option("--language", compile_language_, "glsl or hlsl (default: hlsl for .hlsl, else glsl)")
      ->check(CLI::IsMember({"glsl", "hlsl"}));
  compile_->add_option("--client", compile_client_, "vulkan or opengl")->check(CLI::IsMember({"vulkan", "opengl"}))->capture_default_str();
  compile_->add_option("--entry", compile_entry_, "Entry point (HLSL; GLSL's is always main)")->capture_default_str();
  compile_->add_option("-I,--include-dir", compile_include_dirs_, "Directory searched for #include \"...\" (repeatable)");
  compile_->add_flag("--optimize,-O", compile_optimize_, "Run spirv-opt -O on the result");
  compile_->add_flag("--force", compile_force_, "Overwrite an output file that saagen did not write");
}

int SceneCommands::run_plan(const Catalogue& catalogue) const {
  if (plan_rules_) std::cout << rules_text();
  if (plan_manifest_.empty()) {
    if (plan_rules_) return 0;
    throw Error("plan needs a MANIFEST (see examples/scene.saagen.toml), or --rules");
  }
  if (plan_rules_) std::cout << "\n";
  const Manifest manifest = load_manifest(plan_manifest_, catalogue);
  const Catalogue& planned = scene_catalogue(manifest, catalogue);
  std::optional<MeasuredTradeTable> table;
  if (!plan_trade_table_.empty()) table = load_trade_table(plan_trade_table_);
  ScenePlan plan = plan_scene(planned, manifest, table ? &*table : nullptr);
  if (!plan_no_cost_) measure_costs(planned, manifest, plan);
  std::cout << format_plan(planned, manifest, plan);
  return 0;
}

int SceneCommands::run_emit(const Catalogue& catalogue, const std::string& output_directory, bool force) const {
  const Manifest manifest = load_manifest(emit_manifest_, catalogue);
  const Catalogue& planned = scene_catalogue(manifest, catalogue);
  std::optional<MeasuredTradeTable> table;
  if (!emit_trade_table_.empty()) table = load_trade_table(emit_trade_table_);
  const ScenePlan plan = plan_scene(planned, manifest, table ? &*table : nullptr);
  std::vector<OutputFile> outputs;
  for (EmittedFile& file : emit_scene(planned, manifest, plan)) {
    outputs.push_back({fs::path(output_directory) / file.file_name, std::move(file.content)});
  }
  if (plans_glints(manifest)) {
    // The dictionary the glint variants sample, generated with the manifest's glint options.
    const std::vector<std::uint8_t> bytes = glints::dictionary_ktx2_for(manifest.option_values);
    outputs.push_back({fs::path(output_directory) / glint_dictionary_file_name(manifest), std::string(bytes.begin(), bytes.end())});
  }
  if (emit_list_outputs_) {
    for (const OutputFile& output : outputs) std::cout << output.path.string() << "\n";
    return 0;
  }
  // The manifest and the trade table are never written over, not even with --force.
  const WriteReport report = write_outputs(outputs, force, {emit_manifest_, emit_trade_table_});
  for (const fs::path& path : report.written) std::cout << "wrote     " << path.string() << "\n";
  for (const fs::path& path : report.unchanged) std::cout << "unchanged " << path.string() << "\n";
  return 0;
}

int SceneCommands::run_compile() const {
  const fs::path input(compile_input_), output(compile_output_);
  const CompileRequest settings = compile_settings(input);
  check_include_directories(compile_include_dirs_);

  IncludeExpander expander(compile_include_dirs_);
  expander.expand(input, 0);
  check_not_an_input(output, expander.files());
  check_output_paths({output}, compile_force_);

  CompileRequest request = settings;
  request.hlsl_native_16bit = expander.native_16bit();
  request.sources = std::move(expander.pieces());
  const CompileResult result = compile_to_spirv(request);
  if (!result.ok) throw Error(located(input, first_compiler_message(result.log)));
  if (!has_entry_point(result.spirv)) {
    throw Error(fmt::format("{}: no entry point '{}' for the {} stage; pass --entry with the name of the shader's entry function",
                            input.string(), request.entry_point, stage_name(request.stage)));
  }
  std::vector<std::uint32_t> spirv = result.spirv;
  if (compile_optimize_) {
    spirv = optimize_spirv(spirv, request.client);
    if (spirv.empty()) throw Error(fmt::format("{}: spirv-opt failed", input.string()));
  }
  spirv = add_source_extension(spirv, fmt::format("{} compiled from {}", output_tag, input.filename().string()));
  const WriteReport report = write_outputs({{output, spirv_file_bytes(spirv)}}, compile_force_);
  std::cout << fmt::format("{} {} ({} SPIR-V words)\n", report.written.empty() ? "unchanged" : "wrote    ", compile_output_, spirv.size());
  return 0;
}

CompileRequest SceneCommands::compile_settings(const fs::path& input) const {
  const std::string extension = input.extension().string();
  std::string stage = compile_stage_;
  if (stage.empty()) {
    if (extension == ".vert" || extension == ".frag" || extension == ".comp")
      stage = extension.substr(1);
    else
      throw Error(fmt::format("{}: cannot tell the stage from the extension; pass --stage vert, frag or comp", input.string()));
  }
  const SourceLanguage language =
      !compile_language_.empty() ? *source_language(compile_language_) : source_language_of_extension(extension);
  if (language == SourceLanguage::glsl && compile_entry_ != "main") {
    throw Error(fmt::format("--entry {}: GLSL's entry point is always main; --entry applies to HLSL only", compile_entry_));
  }
  if (compile_entry_.empty()) throw Error("--entry: empty; pass the name of the HLSL entry function");
  CompileRequest request;
  request.language = language;
  request.stage = stage == "vert" ? ShaderStage::vertex : stage == "comp" ? ShaderStage::compute : ShaderStage::fragment;
  request.client = compile_client_ == "opengl" ? ClientApi::opengl : ClientApi::vulkan;
  request.entry_point = compile_entry_;
  return request;
}

}  // namespace saagen::cli

// saagen: the command-line front end. Every failure prints one line on stderr and exits non-zero;
// nothing is written unless everything that would be written has been produced first.
#include "arguments.hpp"
#include "glint_commands.hpp"
#include "glint_options.hpp"
#include "pass_commands.hpp"
#include "report_commands.hpp"
#include "scene_commands.hpp"
#include "score_command.hpp"
#include "texture_commands.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/emit/engines.hpp"
#include "saagen/emit/listing.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/io/input.hpp"
#include "saagen/io/output.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/products/output_validation.hpp"
#include "saagen/products/spirv_library.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/validation.hpp"
#ifdef SAAGEN_HAVE_HARNESS
#include "saagen/harness/webgpu.hpp"
#endif

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <regex>

namespace {

namespace fs = std::filesystem;
using saagen::Catalogue;

constexpr int exit_usage = 2;
constexpr int exit_failure = 1;

struct EmitArguments {
  std::string target = "glsl";
  std::vector<std::string> variants;
  std::string prefix = "saa_";
  std::optional<double> sigma2;
  std::optional<double> kappa;
  std::string output_directory;
  bool force = false;
  std::string precision = "fp32";
  bool unguarded = false;
  std::optional<std::string> preset;   // an engine's variant, sigma^2, kappa and domain
  std::optional<std::string> domain;   // roughness domain of the functions' roughness in and out
  std::string import_path;             // module targets: naga_oil's #define_import_path
  std::string module_name = "module";  // module targets: the stem of the one module of several variants
  saagen::cli::GlintOptions glint;     // the glint variants' options (--glint-count, ...)
};

int run_list(const Catalogue& base_catalogue, bool json, const std::string& prefix, saagen::Domain domain) {
  saagen::validate_prefix(prefix);
  if (json) {
    std::cout << saagen::catalogue_json(base_catalogue, prefix, domain).dump(2) << "\n";
    return 0;
  }
  const Catalogue& catalogue = saagen::domain_catalogue(base_catalogue, domain);
  for (const saagen::Variant& variant : catalogue.variants()) {
    if (domain != saagen::Domain::alpha2 && !saagen::variant_has_roughness_io(base_catalogue, *base_catalogue.find_variant(variant.id)))
      continue;
    std::cout << fmt::format("{:<26} {:<8} tangents:{:<3} {}\n", variant.id, to_string(variant.path), variant.needs_tangents ? "yes" : "no",
                             variant.summary);
    std::cout << fmt::format("{:<26} {} -- {}\n", "", variant.paper, variant.equation);
    const auto resources = saagen::resources_read(catalogue, variant.functions);
    if (!resources.empty()) {
      std::cout << fmt::format("{:<26} resources: {} (declared by the including shader; `saagen list --json` shows how)\n", "",
                               fmt::join(resources, ", "));
    }
    for (const std::string& name : variant.functions) {
      const saagen::Function& function = *catalogue.find_function(name);
      std::vector<std::string> parameters;
      for (const saagen::Parameter& parameter : function.parameters) parameters.push_back(parameter.type + " " + parameter.name);
      std::cout << fmt::format("{:<26}   {} {}{}({})  [{}]\n", "", function.return_type, prefix, function.name, fmt::join(parameters, ", "),
                               to_string(function.role));
    }
  }
  return 0;
}

// The glint templates join an emission only where a glint variant is named, or where every
// variant is emitted to a target other than SPIR-V libraries (built from the SAA templates alone).
const Catalogue& emission_catalogue(const Catalogue& every_variant, const saagen::EmitOptions& options) {
  const Catalogue& builtin = Catalogue::builtin();
  if (options.variants.empty()) return options.target.kind != saagen::OutputKind::spirv_library ? every_variant : builtin;
  const bool names_a_glint = std::any_of(options.variants.begin(), options.variants.end(),
                                         [&](const std::string& id) { return builtin.find_variant(id) == nullptr; });
  return names_a_glint ? every_variant : builtin;
}

int emit_files(const Catalogue& every_variant, const EmitArguments& arguments);

// The library names the glint options by their constants (--glint_count): the messages use the
// command line's spelling (--glint-count).
int run_emit(const Catalogue& every_variant, const EmitArguments& arguments) {
  try {
    return emit_files(every_variant, arguments);
  } catch (const saagen::Error& error) {
    throw saagen::Error(saagen::cli::GlintOptions::spelled(error.what(), "glint-"));
  }
}

int emit_files(const Catalogue& every_variant, const EmitArguments& arguments) {
  saagen::cli::check_output_named("--output", arguments.output_directory);
  saagen::cli::check_named_once("--variant", arguments.variants);
  saagen::EmitOptions options;
  options.target = arguments.target;
  options.prefix = arguments.prefix;
  // A preset names the engine's variant, sigma^2, kappa and roughness domain; explicit options win.
  const saagen::EmitSettings settings{arguments.preset, arguments.variants, arguments.sigma2, arguments.kappa, arguments.domain};
  saagen::apply_settings(every_variant, settings, options);
  options.precision = saagen::parse_precision(arguments.precision);
  options.guards = !arguments.unguarded;
  options.import_path = arguments.import_path;
  arguments.glint.apply(options);
  const Catalogue& catalogue = emission_catalogue(every_variant, options);
  if (arguments.glint.any() && !catalogue.find_variant("glints")) {
    throw saagen::Error(
        "--glint-* options set the glint variants' constants, and none is emitted; add --variant glints or glints-ggaa "
        "(or name no variant)");
  }

  std::vector<saagen::OutputFile> outputs;
  if (options.target.kind == saagen::OutputKind::spirv_library) {
    // Per variant a linkable SPIR-V library module and a C/C++ header embedding it.
    for (const saagen::SpirvLibrary& library : saagen::emit_spirv_libraries(catalogue, options)) {
      outputs.push_back({fs::path(arguments.output_directory) / library.file_name, saagen::spirv_file_bytes(library.words)});
      outputs.push_back({fs::path(arguments.output_directory) / library.header_name, saagen::spirv_library_header(catalogue, library)});
    }
  } else if (!saagen::builtin_target(options.target.name()).has_includes() && options.variants.size() > 1) {
    // A language without includes (WGSL) cannot take two files that both define the shared
    // helpers: several variants make one module holding their dependency closure once.
    if (!std::regex_match(arguments.module_name, std::regex("[A-Za-z][A-Za-z0-9_]{0,63}"))) {
      throw saagen::Error(fmt::format("--module '{}': not a name; use a letter, then letters, digits or '_' (at most 64 characters)",
                                      arguments.module_name));
    }
    const saagen::BundleRequest request{arguments.module_name, saagen::public_functions(catalogue, options.variants), options.variants, {}};
    saagen::EmittedFile file = saagen::emit_bundle(catalogue, options, request);
    outputs.push_back({fs::path(arguments.output_directory) / file.file_name, std::move(file.content)});
  } else {
    std::vector<saagen::EmittedFile> files = saagen::emit_variants(catalogue, options);
    if (!options.import_path.empty() && files.size() > 1) {
      throw saagen::Error(
          fmt::format("--import-path {}: names one module, but {} files would be written; name the variants with --variant "
                      "(several make one module)",
                      options.import_path, files.size()));
    }
    for (saagen::EmittedFile& file : files)
      outputs.push_back({fs::path(arguments.output_directory) / file.file_name, std::move(file.content)});
  }
  const saagen::WriteReport report = saagen::write_outputs(outputs, arguments.force);
  for (const fs::path& path : report.written) std::cout << "wrote     " << path.string() << "\n";
  for (const fs::path& path : report.unchanged) std::cout << "unchanged " << path.string() << "\n";
  return 0;
}

std::string read_file(const fs::path& path) {
  return saagen::read_input_file(path, saagen::source_size_limit, "a file written by `saagen emit`");
}

// Files `saagen emit` wrote in a directory: known target extensions holding a marker line.
std::vector<std::pair<std::string, std::string>> emitted_files_in(const fs::path& directory) {
  std::error_code error;
  if (!fs::is_directory(directory, error)) {
    throw saagen::Error(fmt::format("{}: not a directory; pass the directory `saagen emit -o` wrote", directory.string()));
  }
  std::vector<std::string> extensions;
  for (const std::string& target : saagen::builtin_target_names())
    extensions.push_back("." + saagen::builtin_target(target).file_extension);
  extensions.insert(extensions.end(), {".spv", ".comp"});  // SPIR-V libraries and deferred passes
  std::vector<std::pair<std::string, std::string>> files;
  for (const fs::path& path : saagen::cli::regular_files_in(directory)) {
    if (std::find(extensions.begin(), extensions.end(), path.extension().string()) == extensions.end()) continue;
    std::string content = read_file(path);
    if (saagen::find_marker(content)) files.emplace_back(path.string(), std::move(content));
  }
  if (files.empty())
    throw saagen::Error(
        fmt::format("{}: holds no file written by saagen; run `saagen emit -o {}` first", directory.string(), directory.string()));
  return files;
}

// Without a directory: every variant for every built-in target, emitted in memory.
std::vector<std::pair<std::string, std::string>> all_emitted_files(const Catalogue& catalogue) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const std::string& target : saagen::builtin_target_names()) {
    saagen::EmitOptions options;
    options.target = target;
    for (saagen::EmittedFile& file : saagen::emit_variants(catalogue, options)) files.emplace_back(file.file_name, std::move(file.content));
  }
  return files;
}

int run_validate(const Catalogue& catalogue, const std::string& directory) {
  const auto files = directory.empty() ? all_emitted_files(catalogue) : emitted_files_in(directory);
  int failures = 0;
  saagen::validate_outputs(catalogue, files, [&](const saagen::FileValidation& validation) {
    std::cout << validation.summary() << "\n";
    if (!validation.ok()) {
      ++failures;
      for (const saagen::ValidationCheck& check : validation.checks) {
        if (!check.ok) std::cerr << check.name << ":\n" << check.log;
      }
    }
  });
  std::cout << fmt::format("{} file(s) validated, {} failed\n", files.size(), failures);
  return failures == 0 ? 0 : exit_failure;
}

// What the command printed must have reached standard output: a full disk or a closed file there
// (`saagen list --json > /dev/full`) is a failure, in one line, not exit 0.
int finish_standard_output(int code) {
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) || std::cout.fail();
  if (!failed) return code;
  const int error = errno;
  std::cerr << "saagen: error: standard output: write failed (" << (error ? std::strerror(error) : "I/O error")
            << "); check the file or pipe it goes to\n";
  return exit_failure;
}

// CLI11 prints multi-line messages; saagen prints one line and the command's --help hint.
int report_parse_error(const CLI::App& app, const CLI::ParseError& error) {
  if (error.get_exit_code() == 0) return finish_standard_output(app.exit(error));  // --help, --version
  // CLI11's own line breaks become spaces; anything else quoted from the arguments is escaped.
  std::string message = error.what();
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::cerr << "saagen: error: " << saagen::one_line(message) << " (run `saagen --help`)\n";
  return exit_usage;
}

// `saagen list`: the catalogue, as text or JSON.
class ListCommand {
 public:
  explicit ListCommand(CLI::App& app)
      : command_(app.add_subcommand("list", "List every variant: id, paper and equation, render path, tangents, functions")) {
    command_->add_flag("--json", json_, "Machine-readable catalogue (the contract for engines and tests)");
    command_->add_option("--prefix", prefix_, "Prefix shown in emitted names")->capture_default_str();
    command_->add_option("--domain", domain_, "Roughness domain of the listed functions: alpha2, alpha, perceptual or smoothness")
        ->capture_default_str();
  }
  bool requested() const { return static_cast<bool>(*command_); }
  int run(const Catalogue& catalogue) const { return run_list(catalogue, json_, prefix_, saagen::find_domain(domain_).kind); }

 private:
  CLI::App* command_;
  bool json_ = false;
  std::string prefix_ = "saa_";
  std::string domain_ = "alpha2";
};

// `saagen emit` of variants (without --manifest: SceneCommands takes that).
class EmitCommand {
 public:
  explicit EmitCommand(CLI::App& app) : command_(app.add_subcommand("emit", "Write one include file per variant for a target")) {
    command_
        ->add_option(
            "--target,-t", arguments_.target,
            "Target language: glsl, gles (GLSL ES 3.00: WebGL2, OpenGL ES 3), hlsl, wgsl (WebGPU modules), or spirv (linkable SPIR-V library modules + C/C++ headers)")
        ->capture_default_str();
    command_->add_option("--variant,-v", arguments_.variants, "Variant id (repeatable); all variants when none is named");
    preset_option_ = command_->add_option(
        "--preset", preset_,
        "An engine's shipped form: hdrp, filament, filament-taa, o3de, bevy or vsgl (variant, sigma^2, kappa and domain; explicit options win)");
    domain_option_ = command_->add_option(
        "--domain", domain_,
        "Roughness in and out of the emitted functions: alpha2 (default), alpha, perceptual (alpha = r^2) or smoothness (1 - r)");
    command_->add_option("--prefix", arguments_.prefix, "Prefix of every global name in the output")->capture_default_str();
    sigma2_option_ = command_->add_option("--sigma2", sigma2_, "Variance of the pixel filter in pixels^2, in (0, 4] (default 0.25)");
    kappa_option_ =
        command_->add_option("--kappa", kappa_, "Clamp of the kernel roughness in the alpha^2 domain, in [0, 1] (default 0.18)");
    command_->add_option("--output,-o", arguments_.output_directory, "Output directory")->required();
    command_->add_flag("--force", arguments_.force, "Overwrite files that saagen did not write");
    command_
        ->add_option("--precision", arguments_.precision,
                     "fp32, fp16 (GLSL float16_t, GLSL ES mediump, WGSL f16) or min16 (HLSL min16float)")
        ->capture_default_str();
    command_->add_flag("--unguarded", arguments_.unguarded, "Emit the papers' unguarded formulas (for comparison; see docs/STABILITY.md)");
    command_->add_option("--import-path", arguments_.import_path,
                         "WGSL: write `#define_import_path PATH` (naga_oil, Bevy's shader imports) into the one module written");
    command_
        ->add_option("--module", arguments_.module_name,
                     "WGSL: the name of the one module that several --variant make (file PREFIX+NAME.wgsl)")
        ->capture_default_str();
    arguments_.glint.add_to(command_, "glint-");
  }
  CLI::App* command() const { return command_; }
  bool requested() const { return static_cast<bool>(*command_); }
  const std::string& output_directory() const { return arguments_.output_directory; }
  bool force() const { return arguments_.force; }
  // The options that shape a variant's emission, which `emit --manifest` refuses (the manifest sets them).
  std::vector<CLI::Option*> per_variant_options() const {
    std::vector<CLI::Option*> options;
    for (const char* name : {"--target", "--variant", "--prefix", "--sigma2", "--kappa", "--precision", "--unguarded", "--preset",
                             "--domain", "--import-path", "--module"}) {
      if (CLI::Option* option = command_->get_option_no_throw(name)) options.push_back(option);
    }
    return options;
  }
  int run(const Catalogue& catalogue) {
    if (*sigma2_option_) arguments_.sigma2 = saagen::cli::parse_number("--sigma2", sigma2_);
    if (*kappa_option_) arguments_.kappa = saagen::cli::parse_number("--kappa", kappa_);
    if (*preset_option_) arguments_.preset = preset_;
    if (*domain_option_) arguments_.domain = domain_;
    return run_emit(catalogue, arguments_);
  }

 private:
  CLI::App* command_;
  EmitArguments arguments_;
  std::string sigma2_, kappa_, preset_, domain_;
  CLI::Option* preset_option_ = nullptr;
  CLI::Option* domain_option_ = nullptr;
  CLI::Option* sigma2_option_ = nullptr;
  CLI::Option* kappa_option_ = nullptr;
};

// `saagen validate [DIR]`.
class ValidateCommand {
 public:
  explicit ValidateCommand(CLI::App& app)
      : command_(app.add_subcommand(
            "validate",
            "Compile and spirv-validate emitted files in-process, WGSL with Tint (Dawn for Node) (all variants and targets when no DIR)")) {
    command_->add_option("DIR", directory_, "Directory written by `saagen emit`");
  }
  bool requested() const { return static_cast<bool>(*command_); }
  int run(const Catalogue& catalogue) const { return run_validate(catalogue, directory_); }

 private:
  CLI::App* command_;
  std::string directory_;
};

// A first argument that names no command: one line naming the commands.
bool names_unknown_command(CLI::App& app, int argc, char** argv) {
  if (argc <= 1 || argv[1][0] == '-') return false;
  if (!app.get_subcommands([&](const CLI::App* command) { return command->get_name() == argv[1]; }).empty()) return false;
  std::cerr
      << "saagen: error: unknown command '" << saagen::one_line(argv[1])
      << "'; use list, emit or validate, plan or compile for scene manifests, bench or report for the trade-offs, score for clips rendered elsewhere (run `saagen --help`)\n";
  return true;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef SAAGEN_HAVE_HARNESS
  saagen::harness::install_webgpu_runner();  // `validate` checks WGSL with Tint through it
#endif
  CLI::App app{"saagen: emits geometric specular anti-aliasing shader snippets (GLSL, HLSL) and validates them in-process"};
  app.set_version_flag("--version", std::string(saagen::version()));
  app.require_subcommand(1);

  const ListCommand list(app);
  EmitCommand emit(app);
  const ValidateCommand validate(app);
  // Scene manifests: `plan`, `emit --manifest`, `compile`; see scene_commands.cpp.
  const saagen::cli::SceneCommands scene(app, emit.command(), emit.per_variant_options());
  const saagen::cli::GlintCommands glints(app);  // `saagen glints ...`
  // The speed/accuracy trade: `bench`, `report`; see report_commands.cpp.
  const saagen::cli::ReportCommands trade(app);
  // Clips rendered elsewhere, scored with the trade's metrics: `score`; see score_command.cpp.
  const saagen::cli::ScoreCommand score(app);
  // The deferred roughness-limiter pass: `pass`; see pass_commands.cpp.
  const saagen::cli::PassCommand deferred_pass(app);
  // Normal-map prefiltering: `texture prefilter`; see texture_commands.cpp.
  const saagen::cli::TextureCommands texture(app);

  if (names_unknown_command(app, argc, argv)) return exit_usage;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return report_parse_error(app, error);
  }

  const auto dispatch = [&]() -> int {
    const Catalogue& catalogue = Catalogue::builtin();
    // `list` and `emit` show and write every variant, the glinty BRDFs included; the planner and
    // the other commands keep the screen-space SAA catalogue.
    const Catalogue& every_variant = saagen::glints::catalogue();
    if (list.requested()) return list.run(every_variant);
    if (emit.requested() && scene.emit_from_manifest()) {
      saagen::cli::check_output_named("--output", emit.output_directory());
      return scene.run_emit(catalogue, emit.output_directory(), emit.force());
    }
    if (scene.plan_requested()) return scene.run_plan(catalogue);
    if (scene.compile_requested()) return scene.run_compile();
    if (trade.bench_requested()) return trade.run_bench();
    if (trade.report_requested()) return trade.run_report();
    if (score.requested()) return score.run();
    if (emit.requested()) return emit.run(every_variant);
    if (validate.requested()) return validate.run(every_variant);
    if (glints.requested()) return glints.run();
    if (deferred_pass.requested()) return deferred_pass.run(catalogue);
    if (texture.requested()) return texture.run();
    return exit_failure;
  };
  try {
    return finish_standard_output(dispatch());
  } catch (const saagen::Error& error) {
    std::cerr << "saagen: error: " << error.what() << "\n";
    return exit_failure;
  } catch (const std::exception& error) {
    std::cerr << "saagen: internal error: " << saagen::one_line(error.what()) << "\n";
    return exit_failure;
  }
}

#include "glint_commands.hpp"

#include "arguments.hpp"

#include "saagen/error.hpp"
#include "saagen/io/input.hpp"
#include "saagen/io/output.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/products/prefilter.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/validation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <iostream>

namespace saagen::cli {
namespace {

namespace fs = std::filesystem;

std::vector<std::uint8_t> read_image(const fs::path& path, std::string_view what) {
  const std::string bytes = read_input_file(path, image_size_limit, what);
  return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
}

std::string as_string(const std::vector<std::uint8_t>& bytes) { return std::string(bytes.begin(), bytes.end()); }

// Level 0 of the dictionary before rounding, as little-endian float32.
std::string raw_level_bytes(const glints::Dictionary& dictionary) {
  const auto level = glints::dictionary_levels(dictionary, false).front();
  std::string bytes;
  bytes.reserve(level.size() * 4);
  for (double v : level) {
    const float f = static_cast<float>(v);
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, 4);
    for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<char>(bits >> (8 * k)));
  }
  return bytes;
}

void print_report(const WriteReport& report) {
  for (const fs::path& path : report.written) std::cout << "wrote     " << path.string() << "\n";
  for (const fs::path& path : report.unchanged) std::cout << "unchanged " << path.string() << "\n";
}

}  // namespace

GlintCommands::GlintCommands(CLI::App& app) {
  glints_ = app.add_subcommand("glints", "Glints (Chermain et al. 2020/2021, docs/GLINTS.md): snippets, dictionary texture, LEAN moments");
  glints_->require_subcommand(1);

  emit_ = glints_->add_subcommand("emit", "Write the glint snippets (glints: textureLod baseline; glints-ggaa: GGAA)");
  emit_->add_option("--target,-t", target_, "Target language: glsl, gles (GLSL ES 3.00: WebGL2), hlsl or wgsl")->capture_default_str();
  emit_->add_option("--variant,-v", variants_, "glints or glints-ggaa (repeatable); both when none is named");
  emit_->add_option("--prefix", prefix_, "Prefix of every global name")->capture_default_str();
  emit_->add_option("--precision", precision_, "fp32 only: the glint BRDF has no derived or proven half-precision bound")
      ->capture_default_str();
  emit_->add_flag("--unguarded", unguarded_, "Emit the papers' unguarded formulas (for comparison)");
  glint_options_.add_to(emit_, "");
  emit_->add_option("--output,-o", output_directory_, "Output directory")->required();
  emit_->add_flag("--force", force_, "Overwrite files that saagen did not write");

  validate_ = glints_->add_subcommand("validate", "Compile and spirv-validate glint snippets (all forms when no DIR)");
  validate_->add_option("DIR", validate_directory_, "Directory written by `saagen glints emit`");

  dictionary_ = glints_->add_subcommand("dictionary", "Generate the dictionary texture (KTX2: RGBA16F 1D array with MIPs)");
  dictionary_->add_option("--count", glint_options_.count, "Distributions N (multiple of 4; default 192)");
  dictionary_->add_option("--lods", glint_options_.lods, "LODs L (default 16)");
  dictionary_->add_option("--resolution", resolution_, "Texels per distribution (power of two)")->capture_default_str();
  dictionary_->add_option("--alpha", glint_options_.alpha, "Beckmann roughness alpha_dict of the last LOD (default 0.5)");
  dictionary_->add_option("--lobe-sigma", lobe_sigma_, "Standard deviation of a lobe")->capture_default_str();
  dictionary_->add_option("--seed", seed_, "Random seed, a whole number in [0, 2^64 - 1]")->capture_default_str();
  dictionary_->add_flag("--no-mips", no_mips_, "Level 0 only (the textureLod baseline needs no MIPs)");
  dictionary_->add_option("--raw", raw_file_,
                          "Also write the unrounded level-0 densities as little-endian float32 (.f32), layer-major, 4 per texel");
  dictionary_->add_option("--output,-o", output_file_, "Output .ktx2 file")->required();
  dictionary_->add_flag("--force", force_, "Overwrite a file that saagen did not write");

  lean_ = glints_->add_subcommand("lean", "Pre-compute the LEAN moment MIP chain of a normal map (PNG, KTX2 or binary PPM) as KTX2");
  lean_
      ->add_option("NORMAL_MAP", normal_map_,
                   "Tangent-space normal map: PNG or KTX2 (read as `texture prefilter` reads them), or binary PPM (P6, 8 bits)")
      ->required();
  lean_->add_option("--output,-o", output_file_, "Output .ktx2 file")->required();
  lean_->add_flag("--force", force_, "Overwrite a file that saagen did not write");
}

int GlintCommands::run() const {
  if (emit_->parsed()) return run_emit();
  if (validate_->parsed()) return run_validate();
  if (dictionary_->parsed()) return run_dictionary();
  return run_lean();
}

int GlintCommands::run_emit() const {
  check_output_named("--output", output_directory_);
  check_named_once("--variant", variants_);
  EmitOptions options;
  options.target = target_;
  options.variants = variants_;
  options.prefix = prefix_;
  options.precision = parse_precision(precision_);
  options.guards = !unguarded_;
  glint_options_.apply(options);
  std::vector<OutputFile> outputs;
  std::vector<EmittedFile> files;
  try {
    files = glints::emit(options);
  } catch (const Error& error) {
    throw Error(GlintOptions::spelled(error.what(), ""));
  }
  for (EmittedFile& file : files) outputs.push_back({fs::path(output_directory_) / file.file_name, std::move(file.content)});
  print_report(write_outputs(outputs, force_));
  return 0;
}

int GlintCommands::run_validate() const {
  std::vector<std::pair<std::string, std::string>> files;
  if (validate_directory_.empty()) {
    for (const TargetSyntax* target : vulkan_targets()) {
      EmitOptions options;
      options.target = target->name;
      for (EmittedFile& file : glints::emit(options)) files.emplace_back(file.file_name, std::move(file.content));
    }
  } else {
    std::error_code error;
    if (!fs::is_directory(validate_directory_, error)) throw Error(fmt::format("{}: not a directory", validate_directory_));
    for (const fs::path& path : regular_files_in(validate_directory_)) {
      const std::string extension = path.extension().string();
      const auto targets = vulkan_targets();
      if (std::none_of(targets.begin(), targets.end(),
                       [&](const TargetSyntax* target) { return "." + target->file_extension == extension; }))
        continue;
      std::string content = read_input_file(path, source_size_limit, "a file written by `saagen glints emit`");
      if (find_marker(content)) files.emplace_back(path.string(), std::move(content));
    }
    if (files.empty()) throw Error(fmt::format("{}: holds no file written by saagen", validate_directory_));
  }
  int failures = 0;
  for (const auto& [name, content] : files) {
    const FileValidation validation = validate_file(glints::catalogue(), name, content);
    std::cout << validation.summary() << "\n";
    if (!validation.ok()) {
      ++failures;
      for (const ValidationCheck& check : validation.checks) {
        if (!check.ok) std::cerr << check.name << ":\n" << check.log;
      }
    }
  }
  std::cout << fmt::format("{} file(s) validated, {} failed\n", files.size(), failures);
  return failures == 0 ? 0 : 1;
}

int GlintCommands::run_dictionary() const {
  check_output_named("--output", output_file_);
  glints::DictionaryParams params;
  if (glint_options_.count) params.count = *glint_options_.count;
  if (glint_options_.lods) params.lods = *glint_options_.lods;
  if (glint_options_.alpha) params.alpha = *glint_options_.alpha;
  params.resolution = resolution_;
  params.lobe_sigma = lobe_sigma_;
  params.seed = parse_unsigned("--seed", seed_);
  params.validate();
  // Every output path is checked before the generation starts, and written together.
  std::vector<fs::path> paths = {output_file_};
  if (!raw_file_.empty()) paths.insert(paths.end(), {raw_file_, fs::path(raw_file_ + ".saagen")});
  check_output_paths(paths, force_);

  const glints::Dictionary dictionary = glints::generate_dictionary(params);
  const glints::DictionaryTexture texture = glints::dictionary_texture(dictionary, !no_mips_);
  std::vector<OutputFile> outputs = {{output_file_, as_string(write_ktx2(glints::dictionary_ktx2(texture, params)))}};
  if (!raw_file_.empty()) {
    std::string raw = raw_level_bytes(dictionary);
    outputs.push_back(ownership_sidecar(raw_file_, raw,
                                        fmt::format("level 0 of {} before rounding: little-endian float32, layer-major, 4 per texel",
                                                    fs::path(output_file_).filename().string())));
    outputs.push_back({raw_file_, std::move(raw)});
  }
  print_report(write_outputs(outputs, force_));
  std::cout << fmt::format("dictionary {} x {} layers, {} levels, {:.0f} KiB of texels\n", texture.width, texture.layers,
                           texture.levels.size(), glints::texture_bytes(texture) / 1024.0);
  return 0;
}

int GlintCommands::run_lean() const {
  check_output_named("--output", output_file_);
  check_output_paths({output_file_}, force_, {normal_map_});
  const std::vector<std::uint8_t> bytes = read_image(normal_map_, "a PNG, KTX2 or binary PPM (P6) normal map");
  const glints::SlopeMap map = prefilter::read_lean_slopes(bytes, normal_map_);
  const auto levels = glints::lean_moments(map);
  print_report(write_outputs({{output_file_, as_string(write_ktx2(glints::lean_ktx2(levels)))}}, force_, {normal_map_}));
  std::cout << fmt::format("LEAN moments {} x {}, {} levels\n", map.width, map.height, levels.size());
  return 0;
}

}  // namespace saagen::cli

#include "glint_commands.hpp"

#include "saagen/error.hpp"
#include "saagen/glints.hpp"
#include "saagen/output.hpp"
#include "saagen/validation.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <algorithm>
#include <cstring>
#include <sstream>

namespace saagen::cli {
namespace {

namespace fs = std::filesystem;

std::vector<std::uint8_t> read_bytes(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw Error(fmt::format("{}: cannot be read", path.string()));
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>());
}

// Writes a binary file through a temporary and a rename; an existing file is replaced only when
// it is a KTX2 file (or a raw file this command wrote before) or `force` is set.
void write_binary(const fs::path& path, const std::vector<std::uint8_t>& bytes, bool force, bool ktx2) {
  std::error_code error;
  if (fs::exists(path, error) && !force) {
    const auto existing = read_bytes(path);
    const bool ours = ktx2 ? existing.size() >= 12 && existing[1] == 'K' && existing[2] == 'T' && existing[3] == 'X' && existing[5] == '2'
                           : path.extension() == ".f32";
    if (!ours) throw Error(fmt::format("{}: exists and was not written by saagen; pass --force to overwrite it", path.string()));
  }
  if (!path.parent_path().empty()) fs::create_directories(path.parent_path(), error);
  const fs::path temporary = path.string() + ".saagen-tmp";
  {
    std::ofstream stream(temporary, std::ios::binary);
    if (!stream) throw Error(fmt::format("{}: cannot be written", path.string()));
    stream.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!stream) throw Error(fmt::format("{}: cannot be written", path.string()));
  }
  fs::rename(temporary, path, error);
  if (error) throw Error(fmt::format("{}: cannot be written: {}", path.string(), error.message()));
}

}  // namespace

GlintCommands::GlintCommands(CLI::App& app) {
  glints_ = app.add_subcommand("glints", "Glints (Chermain et al. 2020/2021, docs/GLINTS.md): snippets, dictionary texture, LEAN moments");
  glints_->require_subcommand(1);

  emit_ = glints_->add_subcommand("emit", "Write the glint snippets (glints: textureLod baseline; glints-ggaa: GGAA)");
  emit_->add_option("--target,-t", target_, "glsl or hlsl")->capture_default_str();
  emit_->add_option("--variant,-v", variants_, "glints or glints-ggaa (repeatable); both when none is named");
  emit_->add_option("--prefix", prefix_, "Prefix of every global name")->capture_default_str();
  emit_->add_option("--precision", precision_, "fp32, fp16 (GLSL) or min16 (HLSL)")->capture_default_str();
  emit_->add_flag("--unguarded", unguarded_, "Emit the papers' unguarded formulas (for comparison)");
  emit_->add_option("--count", count_, "Distributions N in the dictionary (multiple of 4; default 192)");
  emit_->add_option("--lods", lods_, "LODs L of the dictionary (default 16)");
  emit_->add_option("--alpha", alpha_, "Beckmann roughness of the dictionary (default 0.5)");
  emit_->add_option("--kernel-scale", kernel_scale_, "s_K of GGAA (default 0.5)");
  emit_->add_option("--output,-o", output_directory_, "Output directory")->required();
  emit_->add_flag("--force", force_, "Overwrite files that saagen did not write");

  validate_ = glints_->add_subcommand("validate", "Compile and spirv-validate glint snippets (all forms when no DIR)");
  validate_->add_option("DIR", validate_directory_, "Directory written by `saagen glints emit`");

  dictionary_ = glints_->add_subcommand("dictionary", "Generate the dictionary texture (KTX2: RGBA16F 1D array with MIPs)");
  dictionary_->add_option("--count", count_, "Distributions N (multiple of 4; default 192)");
  dictionary_->add_option("--lods", lods_, "LODs L (default 16)");
  dictionary_->add_option("--resolution", resolution_, "Texels per distribution (power of two)")->capture_default_str();
  dictionary_->add_option("--alpha", alpha_, "Beckmann roughness alpha_dict of the last LOD (default 0.5)");
  dictionary_->add_option("--lobe-sigma", lobe_sigma_, "Standard deviation of a lobe")->capture_default_str();
  dictionary_->add_option("--seed", seed_, "Random seed")->capture_default_str();
  dictionary_->add_flag("--no-mips", no_mips_, "Level 0 only (the textureLod baseline needs no MIPs)");
  dictionary_->add_option("--raw", raw_file_, "Also write the unrounded level-0 densities as little-endian float32 (.f32), layer-major, 4 per texel");
  dictionary_->add_option("--output,-o", output_file_, "Output .ktx2 file")->required();
  dictionary_->add_flag("--force", force_, "Overwrite a file that saagen did not write");

  lean_ = glints_->add_subcommand("lean", "Pre-compute the LEAN moment MIP chain of a normal map (binary PPM) as KTX2");
  lean_->add_option("NORMAL_MAP", normal_map_, "Tangent-space normal map, binary PPM (P6, 8 bits)")->required();
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
  EmitOptions options;
  options.target = target_;
  options.variants = variants_;
  options.prefix = prefix_;
  options.precision = precision_;
  options.guards = !unguarded_;
  if (count_) options.option_values["glint_count"] = *count_;
  if (lods_) options.option_values["glint_lods"] = *lods_;
  if (alpha_) options.option_values["glint_alpha"] = *alpha_;
  if (kernel_scale_) options.option_values["glint_kernel_scale"] = *kernel_scale_;
  std::vector<OutputFile> outputs;
  for (EmittedFile& file : glints::emit(options)) outputs.push_back({fs::path(output_directory_) / file.file_name, std::move(file.content)});
  const WriteReport report = write_outputs(outputs, force_);
  for (const fs::path& path : report.written) std::cout << "wrote     " << path.string() << "\n";
  for (const fs::path& path : report.unchanged) std::cout << "unchanged " << path.string() << "\n";
  return 0;
}

int GlintCommands::run_validate() const {
  std::vector<std::pair<std::string, std::string>> files;
  if (validate_directory_.empty()) {
    for (const std::string target : {"glsl", "hlsl"}) {
      EmitOptions options;
      options.target = target;
      for (EmittedFile& file : glints::emit(options)) files.emplace_back(file.file_name, std::move(file.content));
    }
  } else {
    std::error_code error;
    if (!fs::is_directory(validate_directory_, error)) throw Error(fmt::format("{}: not a directory", validate_directory_));
    for (const auto& entry : fs::directory_iterator(validate_directory_)) {
      const std::string extension = entry.path().extension().string();
      if (!entry.is_regular_file() || (extension != ".glsl" && extension != ".hlsl")) continue;
      const auto bytes = read_bytes(entry.path());
      std::string content(bytes.begin(), bytes.end());
      if (find_marker(content)) files.emplace_back(entry.path().string(), std::move(content));
    }
    std::sort(files.begin(), files.end());
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
  glints::DictionaryParams params;
  if (count_) params.count = *count_;
  if (lods_) params.lods = *lods_;
  if (alpha_) params.alpha = *alpha_;
  params.resolution = resolution_;
  params.lobe_sigma = lobe_sigma_;
  params.seed = seed_;
  const glints::Dictionary dictionary = glints::generate_dictionary(params);
  const glints::DictionaryTexture texture = glints::dictionary_texture(dictionary, !no_mips_);
  write_binary(output_file_, glints::write_ktx2(glints::dictionary_ktx2(texture, params)), force_, true);
  std::cout << fmt::format("wrote     {} ({} x {} layers, {} levels, {:.0f} KiB of texels)\n", output_file_, texture.width, texture.layers,
                           texture.levels.size(), glints::texture_bytes(texture) / 1024.0);
  if (!raw_file_.empty()) {
    const auto level = glints::dictionary_levels(dictionary, false).front();
    std::vector<std::uint8_t> bytes;
    for (double v : level) {
      const float f = static_cast<float>(v);
      std::uint32_t bits = 0;
      std::memcpy(&bits, &f, 4);
      for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<std::uint8_t>(bits >> (8 * k)));
    }
    write_binary(raw_file_, bytes, force_, false);
    std::cout << fmt::format("wrote     {} ({} float32 values)\n", raw_file_, level.size());
  }
  return 0;
}

int GlintCommands::run_lean() const {
  const auto map = glints::slopes_from_ppm(read_bytes(normal_map_));
  const auto levels = glints::lean_moments(map);
  write_binary(output_file_, glints::write_ktx2(glints::lean_ktx2(levels)), force_, true);
  std::cout << fmt::format("wrote     {} ({} x {}, {} levels)\n", output_file_, map.width, map.height, levels.size());
  return 0;
}

}  // namespace saagen::cli

#include "scene_commands.hpp"

#include "report_commands.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/integrate/include_handler.hpp"
#include "saagen/io/include_expansion.hpp"
#include "saagen/io/input.hpp"
#include "saagen/io/output.hpp"
#include "saagen/measure/gltf.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/products/spirv_library.hpp"
#include "saagen/scene/manifest.hpp"
#include "saagen/scene/planner.hpp"
#include "saagen/target/language.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/compiler.hpp"

#include <fmt/format.h>

#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include <sys/stat.h>

namespace saagen::cli {
namespace {

namespace fs = std::filesystem;

std::string read_source(const fs::path& path) { return read_input_file(path, source_size_limit, "a GLSL or HLSL source file"); }

// The files `compile` reads for #include: "..." next to the including file, then in the -I
// directories; <saagen/...> generated in memory (saagen/integrate/include_handler.hpp). Records
// every file read and whether a saagen snippet among them needs native 16-bit types.
class IncludeReader {
 public:
  explicit IncludeReader(std::vector<std::string> directories) : directories_(std::move(directories)) {}

  std::shared_ptr<const IncludeFile> read(const fs::path& path) {
    auto& file = cache_[path.string()];
    if (file) return file;
    file = std::make_shared<const IncludeFile>(IncludeFile{path.string(), identity(path), read_source(path)});
    files_.push_back(path);
    note_marker(file->text);
    return file;
  }

  IncludeSources sources() {
    return {[this](const std::string& name, const IncludeFile& from) { return find(name, from); },
            [this](const std::string& name) {
              const EmittedFile file = resolve_include(name, {});
              native_16bit_ = native_16bit_ || builtin_target(file.marker.target.table).with_precision(file.marker.precision).native_16bit;
              return file.content;
            }};
  }

  // Every file read: the input and what it includes.
  const std::vector<fs::path>& files() const { return files_; }
  bool native_16bit() const { return native_16bit_; }

 private:
  // The first candidate that exists and is not a directory (a FIFO or device is then refused by
  // the reader, not reported as missing).
  std::shared_ptr<const IncludeFile> find(const std::string& name, const IncludeFile& from) {
    std::vector<fs::path> candidates = {fs::path(from.name).parent_path() / name};
    for (const std::string& directory : directories_) candidates.push_back(fs::path(directory) / name);
    for (const fs::path& candidate : candidates) {
      std::error_code error;
      const fs::file_status status = fs::status(candidate, error);
      if (!error && fs::exists(status) && !fs::is_directory(status)) return read(candidate);
    }
    return nullptr;
  }

  static std::string identity(const fs::path& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) return path.string();
    return fmt::format("{}:{}", status.st_dev, status.st_ino);
  }

  void note_marker(const std::string& text) {
    if (const auto marker = find_marker(text)) {
      try {
        native_16bit_ = native_16bit_ || builtin_target(marker->target.table).with_precision(marker->precision).native_16bit;
      } catch (const Error&) {
        // Not a file this saagen can read the precision of; compile it as it is.
      }
    }
  }

  std::vector<std::string> directories_;
  std::map<std::string, std::shared_ptr<const IncludeFile>> cache_;
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

// The languages `compile` takes: those whose tables have glslang validate them (glsl, hlsl).
std::vector<std::string> glslang_languages() {
  std::vector<std::string> names;
  for (const std::string& name : language_names())
    if (SourceLanguage::named(name)->compiled_in_process()) names.push_back(name);
  return names;
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

// An identifier from a glTF name (manifest.hpp's rule: a letter, then letters, digits, '_' or,
// where allowed, '-'; at most 64 characters).
std::string identifier_from(std::string_view text, bool allow_dash, std::string_view fallback) {
  std::string out;
  for (char c : text) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || (allow_dash && c == '-');
    if (out.size() < 56) out += keep ? c : '_';
  }
  if (out.empty() || !std::isalpha(static_cast<unsigned char>(out.front()))) out = std::string(fallback) + "_" + out;
  return out.substr(0, 56);
}

// The next code point of valid UTF-8 at text[at] (advancing at); nullopt for an invalid sequence.
std::optional<char32_t> next_code_point(std::string_view text, std::size_t& at) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(at);
  const int length = lead < 0x80 ? 1 : (lead >> 5) == 0x6 ? 2 : (lead >> 4) == 0xe ? 3 : (lead >> 3) == 0x1e ? 4 : 0;
  if (length == 0 || at + static_cast<std::size_t>(length) > text.size()) return std::nullopt;
  char32_t code = length == 1 ? lead : lead & (0x7f >> length);
  for (int i = 1; i < length; ++i) {
    const unsigned char next = byte(at + static_cast<std::size_t>(i));
    if ((next & 0xc0) != 0x80) return std::nullopt;
    code = (code << 6) | (next & 0x3f);
  }
  static constexpr char32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < smallest[length] || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) return std::nullopt;
  at += static_cast<std::size_t>(length);
  return code;
}

// TOML's short escape letter of a control character (\b \t \n \f \r); 0 for the others.
char short_escape(char32_t code) {
  switch (code) {
    case '\b':
      return 'b';
    case '\t':
      return 't';
    case '\n':
      return 'n';
    case '\f':
      return 'f';
    case '\r':
      return 'r';
    default:
      return 0;
  }
}

// Text as a TOML basic string, quotes included, in printable ASCII: control characters, DEL and
// every non-ASCII character escaped (\uXXXX, \UXXXXXXXX), so that no name can end the string or the
// line; nullopt when the text is not valid UTF-8 (TOML strings are Unicode).
std::optional<std::string> toml_string(std::string_view text) {
  std::string out = "\"";
  for (std::size_t at = 0; at < text.size();) {
    const auto code = next_code_point(text, at);
    if (!code) return std::nullopt;
    if (*code == '"' || *code == '\\') {
      out += '\\';
      out += static_cast<char>(*code);
    } else if (const char letter = short_escape(*code)) {
      out += '\\';
      out += letter;
    } else if (*code >= 0x20 && *code < 0x7f) {
      out += static_cast<char>(*code);
    } else if (*code <= 0xffff) {
      out += fmt::format("\\u{:04X}", static_cast<std::uint32_t>(*code));
    } else {
      out += fmt::format("\\U{:08X}", static_cast<std::uint32_t>(*code));
    }
  }
  return out + "\"";
}

// Where a manifest material comes from (written as a TOML string); a name that cannot be written is
// reported against the asset.
std::string material_source(const measure::GltfAsset& asset, std::size_t index) {
  const measure::GltfMaterial& material = asset.materials[index];
  if (!toml_string(material.name)) {
    throw Error(fmt::format("--gltf {}: material {}'s name is not valid UTF-8, which a manifest cannot hold; rename the material",
                            asset.path, index));
  }
  return fmt::format("glTF material {} '{}'", index, material.name);
}

// The scene manifest of a glTF asset (docs/GLTF_SCENES.md, "The manifest of an asset"): one
// material per glTF material its primitives use, in the asset's order, and after each
// KHR_materials_clearcoat material its coat as a second filtered lobe. Every glTF mesh has
// tangents (its own, or generated by the loader), so tangents = true; normal_maps where the
// lobe's normal texture exists (the coat's own: a coat without one is shaded with the geometric
// normal, KHR_materials_clearcoat); anisotropic where KHR_materials_anisotropy has a non-zero
// strength or a texture (its lobe is the extension's (alpha_t, alpha_b) in the frame turned to its
// direction, which the matrix form filters: saagen/measure/anisotropy.hpp); content =
// "clearcoat" on a coat lobe (saagen's advice for clearcoat, saagen/advice.hpp), while the base
// lobe under it is classified as any material's (normal-mapped with a normal texture, else
// curved), as the trade's by_content rows classify the scenes NAME-coat and NAME; each lobe's
// roughness (GltfMaterial::roughness_range: the factor, or the factor times its texture's G
// range); domain = "perceptual", glTF's roughness (roughnessFactor x G).
std::string gltf_manifest_text(const measure::GltfAsset& asset, std::string_view path, const std::vector<std::string>& targets) {
  std::ostringstream s;
  // A path that is not UTF-8 is written with its odd bytes as U+FFFD: the key is a note.
  std::string path_text;
  for (std::size_t at = 0; at < asset.path.size();) {
    const std::size_t from = at;
    if (next_code_point(asset.path, at)) {
      path_text.append(asset.path, from, at - from);
    } else {
      path_text += "\xEF\xBF\xBD";
      at = from + 1;
    }
  }
  s << "# Scene manifest of the glTF asset named by `source`, written by `saagen plan --gltf` from its materials.\n"
    << "# Edit it freely; `saagen plan` and `saagen emit --manifest` read it as any manifest.\n\n";
  s << "source = " << *toml_string(path_text) << "\n";
  s << "name = \"" << identifier_from(asset.name, false, "asset") << "\"\n";
  s << "targets = [";
  for (std::size_t i = 0; i < targets.size(); ++i) s << (i ? ", " : "") << "\"" << targets[i] << "\"";
  s << "]\n";
  s << "domain = \"perceptual\"  # glTF's roughness: roughnessFactor x G of metallicRoughnessTexture\n";
  std::vector<bool> used(asset.materials.size(), false);
  for (int m : asset.object_material) used[static_cast<std::size_t>(m)] = true;
  std::set<std::string> names;
  auto unique = [&](std::string name, std::size_t index) {
    if (names.count(name)) name += "_" + std::to_string(index);
    names.insert(name);
    return name;
  };
  auto lobe = [&](const std::string& name, const std::string& source, bool normal_maps, bool anisotropic, bool coat_layer,
                  std::pair<double, double> roughness, const std::string& comment) {
    s << "\n# " << comment << "\n";
    if (anisotropic)
      s << "# KHR_materials_anisotropy: alpha2 = (alpha_t^2, alpha_b^2), alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha, in the\n"
           "# tangent frame turned to the anisotropy direction (half_ts in that frame); the matrix form adds its kernel to\n"
           "# diag(alpha2) and keeps the kernel's own orientation\n";
    s << "[[material]]\nsource = " << *toml_string(source) << "\nname = \"" << name << "\"\npath = \"" << path << "\"\ntangents = true\n";
    if (normal_maps) s << "normal_maps = true\n";
    if (anisotropic) s << "anisotropic = true\n";
    if (coat_layer) s << "content = \"clearcoat\"\n";
    if (roughness.first == roughness.second)
      s << fmt::format("roughness = {:.6g}\n", roughness.first);
    else
      s << fmt::format("roughness = [{:.6g}, {:.6g}]  # the factor times its texture's smallest and largest G\n", roughness.first,
                       roughness.second);
  };
  for (std::size_t m = 0; m < asset.materials.size(); ++m) {
    if (!used[m]) continue;
    const measure::GltfMaterial& material = asset.materials[m];
    const std::string name = unique(identifier_from(material.name, true, "material"), m);
    const bool anisotropic = material.anisotropy && (material.anisotropy_strength != 0.0 || material.anisotropy_texture);
    const bool coated = material.clearcoat && material.clearcoat_factor > 0.0;
    const std::string source = material_source(asset, m);
    lobe(name, source, material.normal_map != nullptr, anisotropic, false, material.roughness_range(),
         "glTF material " + std::to_string(m) + ": " + material.describe_factors());
    if (coated)
      lobe(unique(name.substr(0, 50) + "_coat", m), source + ", its clearcoat", material.clearcoat_normal_map != nullptr, false, true,
           material.clearcoat_roughness_range(),
           "its KHR_materials_clearcoat layer, a second filtered lobe: roughness " +
               fmt::format("{}", material.clearcoat_roughness_factor) +
               (material.clearcoat_normal_map ? ", the coat's own normal texture" : ", the geometric normal (no coat normal texture)"));
  }
  return s.str();
}

}  // namespace

std::string SceneCommands::write_gltf_manifest(const Catalogue& catalogue) const {
  if (plan_output_.empty()) throw Error("--gltf " + plan_gltf_ + ": name the manifest to write with --output FILE");
  const OutputFile sidecar_name = ownership_sidecar(plan_output_, "", "");
  std::vector<fs::path> inputs = {plan_gltf_};
  if (!plan_trade_table_.empty()) inputs.emplace_back(plan_trade_table_);
  check_output_paths({plan_output_, sidecar_name.path}, plan_force_, inputs);
  measure::GltfAsset asset;
  try {
    asset = measure::load_gltf(plan_gltf_);
  } catch (const measure::GltfError& error) {
    throw Error(fmt::format("--gltf {}", error.what()));
  }
  // Every file the asset was read from (its buffers and images too) is an input.
  inputs.insert(inputs.end(), asset.files.begin(), asset.files.end());
  const std::string text = gltf_manifest_text(asset, plan_path_, plan_targets_);
  parse_manifest(text, plan_output_, catalogue);  // what is written must plan: checked before writing
  const WriteReport report =
      write_outputs({{plan_output_, text}, ownership_sidecar(plan_output_, text, "scene manifest of " + plan_gltf_)}, plan_force_, inputs);
  for (const fs::path& path : report.written)
    if (path == fs::path(plan_output_)) std::cout << "wrote     " << path.string() << "\n";
  for (const fs::path& path : report.unchanged)
    if (path == fs::path(plan_output_)) std::cout << "unchanged " << path.string() << "\n";
  std::cout << "\n";
  return plan_output_;
}

SceneCommands::SceneCommands(CLI::App& app, CLI::App* emit, const std::vector<CLI::Option*>& emit_exclusive) {
  plan_ = app.add_subcommand("plan", "Print, per material of a scene manifest, the variant chosen, why, what to call, and its cost");
  plan_->add_option("MANIFEST", plan_manifest_, "Scene manifest (TOML; see examples/scene.saagen.toml)");
  plan_->add_option(
      "--trade-table", plan_trade_table_,
      "Measured trade table (JSON): saagen bench --json's (the plan decides on its rows), or bench_shading --json's (a device's timings cost the configurations at the light count it timed); saagen's own measurement otherwise");
  plan_->add_flag("--no-cost", plan_no_cost_, "Skip compiling the cost kernels (optimized SPIR-V instruction counts)");
  plan_->add_flag("--rules", plan_rules_, "Print the planner's rules table");
  plan_->add_flag("--advice", plan_advice_,
                  "Print saagen's table-free advice per content, render path and preference (Markdown), with its comparison with "
                  "no SAA on saagen's scenes and on held-out scenes");
  plan_->add_flag("--json", plan_json_, "Print the plan as JSON (per material: variant, wrapper, BRDF, feed, prefilter, why)");
  plan_->add_flag("--taa", plan_taa_, "Plan for a scene under TAA, as `taa = true` in the manifest (sigma2 0.0625 unless set)");
  CLI::Option* gltf = plan_->add_option("--gltf", plan_gltf_,
                                        "Write the scene manifest of a glTF 2.0 asset (.gltf or .glb) to --output, one material per glTF "
                                        "material its meshes use and one per clearcoat layer, then plan it");
  gltf->excludes(plan_->get_option("MANIFEST"));
  plan_->add_option("--output,-o", plan_output_, "With --gltf: the manifest to write (TOML)")->needs(gltf);
  plan_->add_option("--path", plan_path_, "With --gltf: the render path of every material")
      ->check(CLI::IsMember({"forward", "deferred"}))
      ->capture_default_str()
      ->needs(gltf);
  plan_->add_option("--target", plan_targets_, "With --gltf: the manifest's targets (repeatable)")->capture_default_str()->needs(gltf);
  plan_->add_flag("--force", plan_force_, "With --gltf: overwrite a manifest that saagen did not write")->needs(gltf);
  CLI::Option* measure = plan_->add_flag("--measure", plan_measure_,
                                         "With --gltf: first measure the asset as `saagen bench --preset medium --scene ASSET` does "
                                         "(minutes), then plan with that trade table instead of saagen's own scenes'");
  measure->needs(gltf)->excludes(plan_->get_option("--trade-table"));
  plan_->add_option("--cache", plan_cache_, "With --measure: directory caching ground-truth images between runs")->needs(measure);

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
  compile_
      ->add_option("--language", compile_language_,
                   "The source's language, one whose table has glslang compile it (default: hlsl for .hlsl, else glsl)")
      ->check(CLI::IsMember(glslang_languages()));
  compile_->add_option("--client", compile_client_, "vulkan or opengl")->check(CLI::IsMember({"vulkan", "opengl"}))->capture_default_str();
  compile_->add_option("--entry", compile_entry_, "Entry point (HLSL; GLSL's is always main)")->capture_default_str();
  compile_->add_option("-I,--include-dir", compile_include_dirs_, "Directory searched for #include \"...\" (repeatable)");
  compile_->add_flag("--optimize,-O", compile_optimize_, "Run spirv-opt -O on the result");
  compile_->add_flag("--force", compile_force_, "Overwrite an output file that saagen did not write");
}

int SceneCommands::run_plan(const Catalogue& catalogue) const {
  if (plan_advice_) {
    std::cout << advice_markdown(catalogue);
    if (plan_manifest_.empty() && plan_gltf_.empty() && !plan_rules_) return 0;
    std::cout << "\n";
  }
  if (plan_rules_) std::cout << rules_text();
  if (plan_manifest_.empty() && plan_gltf_.empty()) {
    if (plan_rules_) return 0;
    throw Error("plan needs a MANIFEST (see examples/scene.saagen.toml), --gltf ASSET -o MANIFEST, or --rules");
  }
  if (plan_rules_) std::cout << "\n";
  // Every input is read before anything is written: a bad table leaves no manifest behind.
  std::optional<MeasuredTradeTable> table;
  if (!plan_trade_table_.empty()) table = load_trade_table(plan_trade_table_);
  if (plan_measure_) table = parse_trade_table(measure_asset_table(plan_gltf_, plan_cache_), "the measurement of " + plan_gltf_);
  const std::string manifest_path = plan_gltf_.empty() ? plan_manifest_ : write_gltf_manifest(catalogue);
  Manifest manifest = load_manifest(manifest_path, catalogue);
  if (plan_taa_) manifest.taa = true;
  const Catalogue& planned = scene_catalogue(manifest, catalogue);
  ScenePlan plan = plan_scene(planned, manifest, table ? &*table : nullptr);
  if (!plan_gltf_.empty()) {  // the asset to measure is the one planned
    for (MaterialPlan& material : plan.materials) {
      for (const auto& [placeholder, value] :
           {std::pair<std::string, std::string>{"`saagen bench --scene ASSET.glb", "`saagen bench --scene " + plan_gltf_},
            {"`saagen plan MANIFEST", "`saagen plan " + manifest_path}})
        if (const auto at = material.measure_advice.find(placeholder); at != std::string::npos)
          material.measure_advice.replace(at, placeholder.size(), value);
    }
  }
  if (plan_json_) {
    std::cout << plan_json(manifest, plan);
    return 0;
  }
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
  if (outputs.empty()) {  // every material is advised no filter (saagen/advice.hpp)
    std::cout << "nothing to write: every material of " << emit_manifest_ << " is planned with no filter (`saagen plan` says why)\n";
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

  IncludeReader reader(compile_include_dirs_);
  const IncludeExpansion expansion = expand_includes(*reader.read(input), reader.sources());
  check_not_an_input(output, reader.files());
  check_output_paths({output}, compile_force_);

  CompileRequest request = settings;
  request.hlsl_native_16bit = reader.native_16bit();
  for (const ExpandedPiece& piece : expansion.pieces) request.sources.push_back({piece.name, piece.text});
  const CompileResult result = compile_to_spirv(request);
  if (!result.ok) {
    const std::string message = first_compiler_message(result.log);
    throw Error(deferred_include_error(expansion, message).value_or(located(input, message)));
  }
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
  if (!language->front_end().named_entry_points && compile_entry_ != "main") {
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

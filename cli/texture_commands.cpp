#include "texture_commands.hpp"

#include "arguments.hpp"

#include "saagen/advice.hpp"
#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/io/input.hpp"
#include "saagen/io/output.hpp"
#include "saagen/products/prefilter.hpp"

#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <iterator>

namespace saagen::cli {
namespace {

// A regular file of at most 256 MiB (a device, FIFO or directory is refused at once).
std::vector<std::uint8_t> read_input(const std::string& path) {
  const std::string bytes = read_input_file(path, image_size_limit, "a PNG or KTX2 normal map");
  return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
}

}  // namespace

TextureCommands::TextureCommands(CLI::App& app) {
  texture_ = app.add_subcommand("texture", "Texture tools: normal-map prefiltering (docs/GUIDE.md, \"Normal-map prefiltering\")");
  texture_->require_subcommand(1);
  prefilter_ = texture_->add_subcommand(
      "prefilter", fmt::format("Normal map (PNG or KTX2) to a KTX2 MIP chain of roughness (Toksvig or an engine's bake) or LEAN "
                               "slope moments (docs/PREFILTER.md); {}",
                               advice::kPrefilterSamplingText));
  prefilter_
      ->add_option("IN", input_,
                   "Tangent-space normal map: PNG (8/16-bit RGB/RGBA) or KTX2 (RGBA8 UNORM, RGBA16F, RGBA32F), power-of-two size, "
                   "at most 8192 texels a side and 4096 x 4096 in all, a file of at most 256 MiB")
      ->required();
  prefilter_->add_option("--output,-o", output_, "Output .ktx2 file")->required();
  prefilter_
      ->add_option("--method", method_,
                   "toksvig, unreal (composite texture), filament-vmf (roughness-prefilter), hdrp (normal-map filtering): one roughness "
                   "channel; lean: slope moments")
      ->capture_default_str();
  prefilter_
      ->add_option("--domain", domain_,
                   "Domain of --roughness and of the toksvig output: alpha2, alpha, perceptual (alpha = r^2) or smoothness (1 - r)")
      ->capture_default_str();
  prefilter_->add_option("--roughness", roughness_, "Constant base roughness in that domain, in [0, 1]")
      ->check(value_given())
      ->capture_default_str();
  prefilter_->add_flag("--float32", float32_, "Roughness methods: R32_SFLOAT instead of R16_SFLOAT");
  CLI::Option* gltf =
      prefilter_->add_flag("--gltf", gltf_,
                           "Roughness methods: glTF metallicRoughnessTexture layout, R8G8B8A8_UNORM with G = perceptual roughness, B = "
                           "--metallic, R = A = 1");
  prefilter_->add_option("--metallic", metallic_, "--gltf: metallic value of the B channel, in [0, 1]")
      ->check(value_given())
      ->needs(gltf)
      ->capture_default_str();
  prefilter_
      ->add_option("--scale", scale_,
                   "Roughness methods: the bake's addition to alpha^2 times this, in [0, 4] (1: as published; the best strength "
                   "depends on the map: measure it with saagen bench --prefilter-scale, docs/PREFILTER.md)")
      ->check(value_given())
      ->capture_default_str();
  prefilter_->add_flag("--force", force_, "Overwrite a file that saagen did not write");
}

int TextureCommands::run() const {
  prefilter::Options options;
  options.method = prefilter::parse_method(method_);
  options.domain = find_domain(domain_).kind;
  options.roughness = roughness_;
  options.float32 = float32_;
  options.gltf = gltf_;
  options.metallic = metallic_;
  options.scale = scale_;
  options.validate();
  const std::vector<std::uint8_t> input = read_input(input_);
  check_output_paths({output_}, force_, {input_});  // before decoding; never over the input, not even with --force
  const auto levels = prefilter::build_levels(prefilter::read_normal_map(input, input_));
  const auto bytes = write_ktx2(prefilter::prefilter_ktx2(levels, options));
  const WriteReport report = write_outputs({{output_, std::string(bytes.begin(), bytes.end())}}, force_, {input_});
  const char* verb = report.written.empty() ? "unchanged" : "wrote    ";
  std::cout << fmt::format("{} {} ({} x {}, {} levels, {}{})\n", verb, output_, levels.front().width, levels.front().height, levels.size(),
                           prefilter::to_string(options.method), options.gltf ? ", glTF metallicRoughness: G = perceptual roughness" : "");
  std::cout << fmt::format("sample    {}\n", advice::kPrefilterSamplingText);
  return 0;
}

}  // namespace saagen::cli

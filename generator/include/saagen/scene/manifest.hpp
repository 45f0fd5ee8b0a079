// Scene manifests: a TOML file naming the targets, the emission options and, per
// material, what the planner needs to pick a variant. The format is documented with an example
// in examples/scene.saagen.toml and examples/INTEGRATION.md.
//
// Every problem is reported as one line: "FILE:LINE:COLUMN: key 'KEY' ...: what is wrong;
// allowed: ...". toml++ gives every key and value its source position.
#pragma once

#include "saagen/advice.hpp"
#include "saagen/domain.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/io/marker.hpp"
#include "saagen/precision.hpp"
#include "saagen/scene/cost_tables.hpp"

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

struct SourcePosition {
  int line = 0;
  int column = 0;
};

enum class Preference { accuracy, speed };
enum class Ndf { ggx, beckmann };
std::string_view to_string(Preference preference);
std::string_view to_string(Ndf ndf);

// A material's perceptual roughness, as engines and glTF's roughnessFactor give it (GGX alpha is
// its square): one value (low = high), or the range a roughness texture spans.
struct RoughnessRange {
  double low = 0.0, high = 0.0;
};

struct Material {
  std::string name;
  RenderPath path = RenderPath::forward;  // forward or deferred (never any)
  bool anisotropic = false;
  bool tangents = false;
  Ndf ndf = Ndf::ggx;
  bool normal_maps = false;
  // `content`: what the surface looks like at pixel scale, which decides saagen's advice
  // (saagen/advice.hpp); nullopt: normal-mapped with normal_maps = true, else curved.
  std::optional<advice::Content> content;
  bool glints = false;                    // the glinty BRDF (forward, tangents): the planner picks a glint variant
  Precision precision = Precision::fp32;  // fp32 or fp16 (per target: see target_precision)
  Preference prefer = Preference::accuracy;
  // `budget`: at most this shading cost over no SAA (the ISA ratio on the manifest's gpu_family,
  // generator/data/isa_cost.json); the plan then takes the most accurate configuration within it
  // that beats no SAA, whatever `prefer` says, else no filter.
  std::optional<double> budget;
  // `lights`: the lights that shade a pixel of the material, 1 to kMaxLights (the manifest's
  // scene-wide `lights` when the material sets none; default 1). A forward filter and every lobe
  // are paid per light, a deferred filter's roughness once per pixel, so the shading cost over no
  // SAA that `prefer = "speed"` and `budget` read depends on it (IsaTable::cost_light_count).
  int lights = 1;
  // `map_lod`: the finest MIP level the material's normal maps are sampled at in its views (the
  // implicit LOD where it is seen closest; 0: close-ups at the map's full resolution). saagen's
  // normal-mapped advice then pools only its scenes with maps that far away
  // (AdviceTable::find), where it has measured them; 0 (the default): every distance.
  int map_lod = 0;
  // `roughness`: the material's perceptual roughness, one value or [lowest, highest]. saagen's
  // decision then also refuses a configuration that loses to no SAA on any measured cell (one
  // scene at one alpha) at the measured alphas that bracket the material's
  // (cost_tables.hpp: bracketing_alphas); nullopt: decided over every measured roughness pooled.
  std::optional<RoughnessRange> roughness;
  std::optional<std::string> variant;  // explicit choice, overriding the planner's rules
  SourcePosition position;             // of the [[material]] header
  // Position of each key given in the file (values), for diagnostics found after parsing.
  std::map<std::string, SourcePosition, std::less<>> positions;
};

struct Manifest {
  std::string source_name;            // the file name used in diagnostics
  std::string name = "scene";         // the bundle's name: files are <prefix><name>[_<precision>].<ext>
  std::vector<OutputTarget> targets;  // snippets of built-in target tables, parsed from `targets`
  std::string prefix = "saa_";
  std::map<std::string, double> option_values;  // only the options the file sets (sigma2, kappa)
  // The GPU family whose ISA cost ranks `prefer = "speed"` (a family of the committed ISA table,
  // planner.hpp); empty: kDefaultGpuFamily (vega10).
  std::string gpu_family;
  // `lights`: the scene-wide light count, the default of every material's `lights` (default 1).
  int lights = 1;
  // `preset`: an engine's form (saagen/emit/engines.hpp): its sigma2 and kappa where the file sets
  // none, its variant for deferred materials that name none, and its roughness domain.
  std::optional<std::string> preset;
  Domain domain = Domain::alpha2;  // `domain`: roughness in and out of the emitted functions
  // `import_path`: the naga_oil module path of the module-language (WGSL) bundles; the fp16
  // bundle's is PATH_fp16. Empty: none.
  std::string import_path;
  // `taa`: the scene runs under temporal anti-aliasing (docs/TAA.md); the planner then defaults
  // sigma2 to the kernel measured under TAA (planner.hpp, kTaaSigma2).
  bool taa = false;
  std::vector<Material> materials;

  // "FILE:LINE:COLUMN: " for a position in this manifest.
  std::string where(SourcePosition position) const;
};

// The GGX alpha range of a material's `roughness` (each end squared); nullopt without one.
std::optional<AlphaRange> alpha_range(const Material& material);

// The material's content type: `content`, else normal-mapped with normal maps, else curved.
advice::Content content_of(const Material& material);

// The target's precision for a manifest precision: the same name when the target has it, and
// for "fp16" a target without an fp16 form falls back to "min16" (HLSL min16float); nullopt
// when the target has neither.
std::optional<Precision> target_precision(const OutputTarget& target, Precision precision);

// Keys a manifest may have, for documentation and for the unknown-key message.
const std::vector<std::string>& manifest_keys();
const std::vector<std::string>& material_keys();

// Parses and checks a manifest's text. Throws saagen::Error (one line, as above) on the first
// problem: TOML syntax, unknown keys, wrong types, unknown values or variants, out-of-range
// options, an unsafe prefix or name, duplicate material names, unavailable features.
Manifest parse_manifest(std::string_view text, std::string_view source_name, const Catalogue& catalogue);
// Reads the file and parses it; the path (as given) names it in diagnostics.
Manifest load_manifest(const std::filesystem::path& path, const Catalogue& catalogue);

// The glint dictionary written next to the bundles when a material has glints = true:
// <prefix><name>_glint_dictionary.ktx2 (glints::dictionary_ktx2_for the manifest's options: the
// dictionary its glint_count, glint_lods, glint_resolution and glint_alpha describe).
std::string glint_dictionary_file_name(const Manifest& manifest);
bool plans_glints(const Manifest& manifest);

}  // namespace saagen

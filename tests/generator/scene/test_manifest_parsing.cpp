// Scene manifests (test_manifest, with test_manifest_planner.cpp, test_manifest_trade_table.cpp and
// test_manifest_bundle.cpp): parsing and its one-line errors (file:line:column, key, what is
// allowed), and the `preset` and `domain` keys.
#include "manifest_support.hpp"

#include "saagen/validate/validation.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using saagen::Catalogue;
using namespace saagen::test::manifest;

// ---------------------------------------------------------------------------------------------
// Parsing

TEST(Manifest, ParsesTheExample) {
  const saagen::Manifest manifest = saagen::load_manifest(example_manifest, Catalogue::builtin());
  EXPECT_EQ(manifest.name, "scene");
  EXPECT_EQ(manifest.targets,
            (std::vector<saagen::OutputTarget>{saagen::OutputTarget::snippet("glsl"), saagen::OutputTarget::snippet("hlsl")}));
  EXPECT_EQ(manifest.prefix, "saa_");
  EXPECT_EQ(manifest.option_values.at("sigma2"), 0.25);
  EXPECT_EQ(manifest.option_values.at("kappa"), 0.18);
  ASSERT_EQ(manifest.materials.size(), 4u);
  const saagen::Material& car = manifest.materials[0];
  EXPECT_EQ(car.name, "car_paint");
  EXPECT_EQ(car.path, saagen::RenderPath::forward);
  EXPECT_TRUE(car.anisotropic);
  EXPECT_TRUE(car.tangents);
  EXPECT_EQ(car.ndf, saagen::Ndf::ggx);
  EXPECT_TRUE(car.normal_maps);
  EXPECT_EQ(car.prefer, saagen::Preference::accuracy);
  EXPECT_EQ(manifest.materials[1].ndf, saagen::Ndf::beckmann);
  EXPECT_EQ(manifest.materials[1].prefer, saagen::Preference::speed);
  EXPECT_EQ(manifest.materials[2].path, saagen::RenderPath::deferred);
  EXPECT_FALSE(manifest.materials[2].tangents);
  EXPECT_EQ(manifest.materials[3].precision, saagen::Precision::fp16);
  EXPECT_EQ(manifest.gpu_family, "vega10");
  EXPECT_EQ(car.position.line, 32);
}

TEST(Manifest, DefaultsAndIntegerNumbers) {
  const saagen::Manifest manifest = parse(header + "kappa = 0\n" + forward_material);
  EXPECT_EQ(manifest.name, "scene");
  EXPECT_EQ(manifest.prefix, "saa_");
  EXPECT_EQ(manifest.option_values.at("kappa"), 0.0);
  EXPECT_FALSE(manifest.option_values.count("sigma2"));
  const saagen::Material& material = manifest.materials.at(0);
  EXPECT_FALSE(material.anisotropic);
  EXPECT_FALSE(material.tangents);
  EXPECT_EQ(material.ndf, saagen::Ndf::ggx);
  EXPECT_EQ(material.precision, saagen::Precision::fp32);
  EXPECT_EQ(material.prefer, saagen::Preference::accuracy);
  EXPECT_EQ(material.lights, 1);
  EXPECT_EQ(manifest.lights, 1);
  EXPECT_FALSE(material.variant);
}

// `lights`: scene-wide, the default of every material, which may set its own.
TEST(Manifest, LightsAreSceneWideAndPerMaterial) {
  const saagen::Manifest manifest =
      parse(header + "lights = 4\n" + forward_material + "[[material]]\nname = \"n\"\npath = \"deferred\"\nlights = 16\n");
  EXPECT_EQ(manifest.lights, 4);
  EXPECT_EQ(manifest.materials.at(0).lights, 4);
  EXPECT_EQ(manifest.materials.at(1).lights, 16);
  EXPECT_EQ(parse(header + forward_material + "lights = 64\n").materials.at(0).lights, 64);
}

// `map_lod`: how far away a material's normal maps are seen, 0 (close-ups) by default.
TEST(Manifest, MapLodIsAMaterialsNormalMapDistance) {
  EXPECT_EQ(parse(header + forward_material + "normal_maps = true\n").materials.at(0).map_lod, 0);
  EXPECT_EQ(parse(header + forward_material + "normal_maps = true\nmap_lod = 4\n").materials.at(0).map_lod, 4);
  EXPECT_EQ(parse(header + forward_material + "normal_maps = true\nmap_lod = 16\n").materials.at(0).map_lod, 16);
}

// `roughness`: one perceptual roughness or the range a texture spans; GGX alpha is its square.
TEST(Manifest, RoughnessIsOneValueOrARange) {
  EXPECT_FALSE(parse(header + forward_material).materials.at(0).roughness);
  const saagen::Material one = parse(header + forward_material + "roughness = 0.1\n").materials.at(0);
  ASSERT_TRUE(one.roughness);
  EXPECT_EQ(one.roughness->low, 0.1);
  EXPECT_EQ(one.roughness->high, 0.1);
  const saagen::Material range = parse(header + forward_material + "roughness = [0, 1]\n").materials.at(0);
  ASSERT_TRUE(range.roughness);
  EXPECT_EQ(range.roughness->low, 0.0);
  EXPECT_EQ(range.roughness->high, 1.0);
  const auto alphas = saagen::alpha_range(parse(header + forward_material + "roughness = [0.1, 0.5]\n").materials.at(0));
  ASSERT_TRUE(alphas);
  EXPECT_DOUBLE_EQ(alphas->low, 0.01);
  EXPECT_DOUBLE_EQ(alphas->high, 0.25);
}

// The measured alphas a material's alpha range is judged at: those inside it and the nearest on
// either side (an alpha between two measured ones is judged by both).
TEST(Manifest, AMaterialsAlphasAreBracketedByTheMeasuredOnes) {
  const std::vector<double> measured = {0.0025, 0.01, 0.05, 0.3};
  using V = std::vector<double>;
  EXPECT_EQ(saagen::bracketing_alphas(measured, {0.01, 0.01}), (V{0.01}));
  EXPECT_EQ(saagen::bracketing_alphas(measured, {0.02, 0.02}), (V{0.01, 0.05}));
  EXPECT_EQ(saagen::bracketing_alphas(measured, {0.0, 0.0}), (V{0.0025}));
  EXPECT_EQ(saagen::bracketing_alphas(measured, {0.5, 1.0}), (V{0.3}));
  EXPECT_EQ(saagen::bracketing_alphas(measured, {0.005, 0.06}), (V{0.0025, 0.01, 0.05, 0.3}));
  EXPECT_EQ(saagen::bracketing_alphas(measured, {0.01, 0.05}), (V{0.01, 0.05}));
  EXPECT_EQ(saagen::bracketing_alphas({}, {0.01, 0.05}), V{});
  // A roughness written to three digits names the measured alpha it rounds: 0.316^2 = 0.0999.
  EXPECT_EQ(saagen::bracketing_alphas(measured, {0.316 * 0.316, 0.316 * 0.316}), (V{0.05, 0.3}));
  EXPECT_EQ(saagen::bracketing_alphas({0.05, 0.1, 0.3}, {0.316 * 0.316, 0.316 * 0.316}), (V{0.1}));
  EXPECT_EQ(saagen::bracketing_alphas({0.05, 0.1, 0.3}, {0.097, 0.097}), (V{0.05, 0.1}));
}

struct BadCase {
  const char* what;
  std::string text;
  std::string message;
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.what; }

class BadManifest : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadManifest, IsRejectedWithPositionKeyAndWhatIsAllowed) { EXPECT_EQ(error_of(GetParam().text), GetParam().message); }

const std::string material_keys =
    "name, path, anisotropic, tangents, ndf, normal_maps, content, glints, precision, prefer, budget, lights, map_lod, roughness, variant, source";
const std::string filters =
    "\"forward-aniso-slope\", \"forward-aniso-projected\", \"forward-axis-slope\", \"forward-axis-projected\", "
    "\"deferred-previous\", \"deferred-max\", \"deferred-sum\", \"deferred-avg\", \"deferred-projected-space\", \"deferred-aniso\"";

const std::string roughness_rule =
    "a number in [0, 1], the perceptual roughness (as glTF's roughnessFactor; GGX alpha is its square), or [lowest, highest] where a "
    "texture varies it";

const std::string lights_rule =
    "an integer from 1 to 64: the lights that shade a pixel, at which the shading cost over no SAA is read (the nearest measured "
    "count not above it: 1, 4 or 16); default ";

INSTANTIATE_TEST_SUITE_P(
    Errors, BadManifest,
    ::testing::Values(
        BadCase{"lights_zero", header + forward_material + "lights = 0\n",
                "scene.toml:5:10: key 'lights' of material 'm': 0 is outside [1, 64]; allowed: " + lights_rule +
                    "the scene's `lights`, else 1"},
        BadCase{"lights_too_many", header + "lights = 65\n" + forward_material,
                "scene.toml:2:10: key 'lights': 65 is outside [1, 64]; allowed: " + lights_rule + "1"},
        BadCase{"lights_fraction", header + forward_material + "lights = 4.5\n",
                "scene.toml:5:10: key 'lights' of material 'm': must be an integer, got a floating-point number; allowed: " + lights_rule +
                    "the scene's `lights`, else 1"},
        BadCase{"lights_string", header + "lights = \"4\"\n" + forward_material,
                "scene.toml:2:10: key 'lights': must be an integer, got a string; allowed: " + lights_rule + "1"},
        BadCase{"map_lod_without_normal_maps", header + forward_material + "map_lod = 4\n",
                "scene.toml:5:11: key 'map_lod' of material 'm': a normal map's distance needs normal_maps = true; allowed: normal_maps = "
                "true"},
        BadCase{"map_lod_too_far", header + forward_material + "normal_maps = true\nmap_lod = 17\n",
                "scene.toml:6:11: key 'map_lod' of material 'm': 17 is outside [0, 16]; allowed: an integer from 0 to 16: the finest MIP "
                "level the material's normal maps are sampled at where it is seen closest (default 0: close-ups)"},
        BadCase{"toml_syntax", header + "prefix = = 1\n",
                "scene.toml:2:10: not valid TOML: Error while parsing value: could not determine value type; allowed: TOML 1.0 "
                "(see examples/scene.saagen.toml)"},
        BadCase{
            "unknown_top_key", header + "colour = 1\n" + forward_material,
            "scene.toml:2:1: unknown key 'colour'; allowed keys: name, targets, prefix, gpu_family, lights, sigma2, kappa, glint_count, glint_lods, "
            "glint_alpha, glint_resolution, glint_kernel_scale, glint_max_anisotropy, glint_relative_area, preset, domain, import_path, taa, source, material"},
        BadCase{"unknown_material_key", header + forward_material + "colour = 0.5\n",
                "scene.toml:5:1: unknown key 'colour' of material 'm'; allowed keys: " + material_keys},
        BadCase{"roughness_above_one", header + forward_material + "roughness = 1.5\n",
                "scene.toml:5:13: key 'roughness' of material 'm': 1.5 is outside [0, 1]; allowed: " + roughness_rule},
        BadCase{"roughness_three_values", header + forward_material + "roughness = [0.1, 0.2, 0.3]\n",
                "scene.toml:5:13: key 'roughness' of material 'm': an array of 3 numbers; allowed: " + roughness_rule},
        BadCase{"roughness_reversed", header + forward_material + "roughness = [0.3, 0.1]\n",
                "scene.toml:5:13: key 'roughness' of material 'm': the lowest, 0.3, is above the highest, 0.1; allowed: " + roughness_rule},
        BadCase{"roughness_string", header + forward_material + "roughness = [\"0.1\", 0.2]\n",
                "scene.toml:5:14: key 'roughness' of material 'm': must be a number, got a string; allowed: " + roughness_rule},
        BadCase{"wrong_type_number", header + "sigma2 = \"big\"\n" + forward_material,
                "scene.toml:2:10: key 'sigma2': must be a number, got a string; allowed: a number in (0, 4] (variance sigma^2 of the "
                "Gaussian pixel filter in pixels^2 (sigma = 0.5 px by default); default 0.25)"},
        BadCase{"wrong_type_boolean", header + forward_material + "tangents = \"yes\"\n",
                "scene.toml:5:12: key 'tangents' of material 'm': must be a boolean, got a string; allowed: true, false"},
        BadCase{
            "wrong_type_targets", "targets = \"glsl\"\n" + forward_material,
            "scene.toml:1:11: key 'targets': must be an array, got a string; allowed: an array of \"gles\", \"glsl\", \"hlsl\", \"wgsl\""},
        BadCase{"wrong_type_material", header + "material = 3\n",
                "scene.toml:2:12: key 'material': must be an array of tables, got an integer; allowed: an array of tables, one "
                "[[material]] per material"},
        BadCase{"unknown_value", header + forward_material + "ndf = \"phong\"\n",
                "scene.toml:5:7: key 'ndf' of material 'm': unknown value \"phong\"; allowed: \"ggx\", \"beckmann\""},
        BadCase{"unknown_path", header + "[[material]]\nname = \"m\"\npath = \"tiled\"\n",
                "scene.toml:4:8: key 'path' of material 'm': unknown value \"tiled\"; allowed: \"forward\", \"deferred\""},
        BadCase{"unknown_variant", header + forward_material + "variant = \"deferred-fancy\"\n",
                "scene.toml:5:11: key 'variant' of material 'm': unknown variant \"deferred-fancy\"; allowed: " + filters},
        BadCase{"brdf_is_not_a_filter", header + forward_material + "variant = \"brdf-ggx\"\n",
                "scene.toml:5:11: key 'variant' of material 'm': not a filter variant (the BRDF is planned from 'ndf'): "
                "\"brdf-ggx\"; allowed: " +
                    filters},
        BadCase{"unknown_target", "targets = [\"glsl\", \"metal\"]\n" + forward_material,
                "scene.toml:1:20: key 'targets': unknown target \"metal\"; allowed: \"gles\", \"glsl\", \"hlsl\", \"wgsl\""},
        BadCase{
            "duplicate_target", "targets = [\"glsl\", \"glsl\"]\n" + forward_material,
            "scene.toml:1:20: key 'targets': \"glsl\" is listed twice; allowed: each of \"gles\", \"glsl\", \"hlsl\", \"wgsl\" at most once"},
        BadCase{"empty_targets", "targets = []\n" + forward_material,
                "scene.toml:1:11: key 'targets': the array is empty; allowed: an array of \"gles\", \"glsl\", \"hlsl\", \"wgsl\""},
        BadCase{"missing_targets", forward_material,
                "scene.toml:1:1: missing key 'targets'; allowed: an array of \"gles\", \"glsl\", \"hlsl\", \"wgsl\""},
        BadCase{"sigma2_out_of_range", header + "sigma2 = 5\n" + forward_material,
                "scene.toml:2:10: key 'sigma2': 5 is out of range; allowed: a number in (0, 4] (variance sigma^2 of the Gaussian "
                "pixel filter in pixels^2 (sigma = 0.5 px by default); default 0.25)"},
        BadCase{"sigma2_zero", header + "sigma2 = 0.0\n" + forward_material,
                "scene.toml:2:10: key 'sigma2': 0 is out of range; allowed: a number in (0, 4] (variance sigma^2 of the Gaussian "
                "pixel filter in pixels^2 (sigma = 0.5 px by default); default 0.25)"},
        BadCase{"kappa_out_of_range", header + "kappa = -0.5\n" + forward_material,
                "scene.toml:2:9: key 'kappa': -0.5 is out of range; allowed: a number in [0, 1] (clamp kappa of the kernel "
                "roughness, in the alpha^2 domain; default 0.18)"},
        BadCase{"kappa_nan", header + "kappa = nan\n" + forward_material,
                "scene.toml:2:9: key 'kappa': nan is out of range; allowed: a number in [0, 1] (clamp kappa of the kernel "
                "roughness, in the alpha^2 domain; default 0.18)"},
        BadCase{"prefix_digit", header + "prefix = \"1x_\"\n" + forward_material,
                "scene.toml:2:10: key 'prefix': \"1x_\" is not a safe identifier prefix; allowed: letters, digits and '_', "
                "starting with a letter, at most 32 characters, no '__', not 'gl_'"},
        BadCase{"prefix_injection", header + "prefix = \"x;\\n#define\"\n" + forward_material,
                "scene.toml:2:10: key 'prefix': \"x;\\x0a#define\" is not a safe identifier prefix; allowed: letters, digits and "
                "'_', starting with a letter, at most 32 characters, no '__', not 'gl_'"},
        BadCase{"prefix_gl", header + "prefix = \"gl_\"\n" + forward_material,
                "scene.toml:2:10: key 'prefix': \"gl_\" is not a safe identifier prefix; allowed: letters, digits and '_', "
                "starting with a letter, at most 32 characters, no '__', not 'gl_'"},
        BadCase{"duplicate_material", header + forward_material + forward_material,
                "scene.toml:6:8: key 'name' of material #2: duplicate material name \"m\" (first defined at scene.toml:3:8); "
                "allowed: a name no other material has"},
        BadCase{"material_name_not_identifier", header + "[[material]]\nname = \"car paint\"\npath = \"forward\"\n",
                "scene.toml:3:8: key 'name' of material #1: \"car paint\" is not an identifier; allowed: an identifier: a letter, "
                "then letters, digits, '_' or '-' (at most 64 characters)"},
        BadCase{"missing_path", header + "[[material]]\nname = \"m\"\n",
                "scene.toml:2:1: missing key 'path' of material 'm'; allowed: \"forward\", \"deferred\""},
        BadCase{"no_material", header,
                "scene.toml:1:1: missing key 'material'; allowed: an array of tables, one [[material]] per material"},
        BadCase{"glints", header + forward_material + "glints = true\n",
                "scene.toml:5:10: key 'glints' of material 'm': the glinty BRDF is evaluated per light in the tangent frame: "
                "glints = true needs path = \"forward\" and tangents = true; allowed: false, or true with path = \"forward\" and "
                "tangents = true"},
        BadCase{"glints_in_half_precision", header + forward_material + "tangents = true\nglints = true\nprecision = \"fp16\"\n",
                "scene.toml:7:13: key 'precision' of material 'm': the glinty BRDF is numerically supported in fp32 only (no "
                "half-precision error bound is derived or proven); allowed: \"fp32\" with glints = true"},
        BadCase{"fp16_unknown_precision", header + forward_material + "precision = \"fp64\"\n",
                "scene.toml:5:13: key 'precision' of material 'm': unknown value \"fp64\"; allowed: \"fp32\", \"fp16\""},
        BadCase{"bundle_name_collides", header + "name = \"deferred_sum\"\n" + forward_material,
                "scene.toml:2:8: key 'name': \"deferred_sum\" would collide with the file `saagen emit` writes for deferred-sum; "
                "allowed: an identifier: a letter, then letters, digits or '_' (at most 64 characters); default \"scene\""},
        BadCase{"anisotropic_without_tangents", header + forward_material + "anisotropic = true\n",
                "scene.toml:5:15: key 'tangents' of material 'm': anisotropic = true needs tangents = true (an anisotropic BRDF is "
                "defined in a tangent frame); allowed: tangents = true, or anisotropic = false"},
        BadCase{"forward_variant_in_deferred",
                header + "[[material]]\nname = \"m\"\npath = \"deferred\"\ntangents = true\n"
                         "variant = \"forward-axis-projected\"\n",
                "scene.toml:6:11: key 'variant' of material 'm': forward-axis-projected filters the half vector of each light in a "
                "forward pass; this material's path is deferred; allowed: \"deferred-previous\", \"deferred-max\", \"deferred-sum\", "
                "\"deferred-avg\", \"deferred-projected-space\", \"deferred-aniso\""},
        BadCase{"variant_needs_tangents", header + forward_material + "variant = \"deferred-previous\"\n",
                "scene.toml:5:11: key 'variant' of material 'm': deferred-previous needs tangents = true (it filters in the tangent "
                "frame); allowed: \"deferred-max\", \"deferred-sum\", \"deferred-avg\", \"deferred-projected-space\", \"deferred-aniso\""}),
    [](const ::testing::TestParamInfo<BadCase>& info) { return std::string(info.param.what); });

TEST(Manifest, UnreadableFileNamesItself) {
  try {
    (void)saagen::load_manifest("/nonexistent/scene.toml", Catalogue::builtin());
    FAIL() << "no error";
  } catch (const saagen::Error& error) {
    EXPECT_EQ(std::string(error.what()).rfind("/nonexistent/scene.toml: cannot be read", 0), 0u) << error.what();
  }
}

// `preset` and `domain` (examples/INTEGRATION.md, "Engines"): the preset's sigma2, kappa, variant
// for deferred materials and roughness domain; keys the file sets win.
const std::string deferred_material = "[[material]]\nname = \"d\"\npath = \"deferred\"\n";

TEST(Bundle, PresetSetsConstantsVariantAndDomain) {
  const auto files = emit_text(header + "preset = \"hdrp\"\n" + deferred_material);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].file_name, "saa_scene_smoothness.glsl");
  const auto marker = saagen::find_marker(files[0].content);
  ASSERT_TRUE(marker);
  EXPECT_EQ(marker->variants, (std::vector<std::string>{"deferred-sum"}));
  EXPECT_EQ(marker->domain, saagen::Domain::smoothness);
  EXPECT_EQ(marker->option_values.at("sigma2"), 0.1);
  EXPECT_EQ(marker->option_values.at("kappa"), 0.04);
  EXPECT_EQ(marker->functions, (std::vector<std::string>{"deferred_sum_smoothness", "deferred_sum_fragment_smoothness"}));
  EXPECT_NE(files[0].content.find("d (deferred): deferred-sum -> saa_deferred_sum_fragment_smoothness"), std::string::npos);
  const saagen::FileValidation validation = saagen::validate_file(Catalogue::builtin(), files[0].file_name, files[0].content);
  EXPECT_TRUE(validation.ok()) << validation.summary();

  const auto overridden = emit_text(header + "preset = \"hdrp\"\ndomain = \"perceptual\"\nkappa = 0.1\n" + deferred_material);
  const auto marker2 = saagen::find_marker(overridden.at(0).content);
  EXPECT_EQ(marker2->domain, saagen::Domain::perceptual);
  EXPECT_EQ(marker2->option_values.at("kappa"), 0.1);
  EXPECT_EQ(marker2->option_values.at("sigma2"), 0.1);
}

// A domain reaches the plan's text, its costs and the bundle next to materials without one (a
// forward-aniso material keeps its alpha^2 matrix form).
TEST(Planner, PlansAndCostsInTheManifestsDomain) {
  const std::string text = header + "preset = \"filament\"\n" + deferred_material +
                           "[[material]]\nname = \"paint\"\npath = \"forward\"\nanisotropic = true\ntangents = true\n";
  const saagen::Manifest manifest = parse(text);
  saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest);
  saagen::measure_costs(Catalogue::builtin(), manifest, plan);
  const std::string printed = saagen::format_plan(Catalogue::builtin(), manifest, plan);
  EXPECT_NE(printed.find("call      saa_deferred_sum_fragment_perceptual(perceptual_roughness, normal_ws)"), std::string::npos) << printed;
  EXPECT_NE(printed.find("the variant of the manifest's preset \"filament\""), std::string::npos) << printed;
  EXPECT_NE(
      printed.find("call      saa_forward_aniso_projected_transported_fragment(alpha2, half_ws, normal_ws, tangent_ws, bitangent_ws)"),
      std::string::npos)
      << printed;
  EXPECT_GT(plan.materials.at(0).cost.at("glsl"), 0);
  const auto files = saagen::emit_scene(Catalogue::builtin(), manifest, plan);
  ASSERT_EQ(files.size(), 1u);
  const saagen::FileValidation validation = saagen::validate_file(Catalogue::builtin(), files[0].file_name, files[0].content);
  EXPECT_TRUE(validation.ok()) << validation.summary();
}

TEST(Manifest, BadPresetOrDomainIsOneLine) {
  EXPECT_EQ(
      error_of(header + "preset = \"unreal\"\n" + deferred_material),
      "scene.toml:2:10: key 'preset': unknown value \"unreal\"; allowed: \"hdrp\", \"filament\", \"filament-taa\", \"o3de\", \"bevy\", "
      "\"vsgl\"");
  EXPECT_EQ(error_of(header + "domain = \"linear\"\n" + deferred_material),
            "scene.toml:2:10: key 'domain': unknown value \"linear\"; allowed: \"alpha2\", \"alpha\", \"perceptual\", \"smoothness\"");
}

}  // namespace

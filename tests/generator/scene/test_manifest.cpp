// Scene manifests: parsing and its one-line errors (file:line:column, key, what is
// allowed), the planner's rules and trade table, minimal emission (exactly the dependency
// closure; removing a material removes its code), and the bundle's validation and CLI.
#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/scene/manifest.hpp"
#include "saagen/scene/planner.hpp"
#include "saagen/validate/validation.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using saagen::Catalogue;

const fs::path example_manifest = fs::path(SAAGEN_SOURCE_DIR) / "examples" / "scene.saagen.toml";

std::string read_text(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

saagen::Manifest parse(const std::string& text) { return saagen::parse_manifest(text, "scene.toml", Catalogue::builtin()); }

// The message parse (and plan) throws for `text`, or "" when it is accepted.
std::string error_of(const std::string& text) {
  try {
    const saagen::Manifest manifest = parse(text);
    (void)saagen::plan_scene(Catalogue::builtin(), manifest);
  } catch (const saagen::Error& error) {
    return error.what();
  }
  return "";
}

const std::string header = "targets = [\"glsl\"]\n";
const std::string forward_material = "[[material]]\nname = \"m\"\npath = \"forward\"\n";

// Names of the functions defined (not merely declared in a comment) in an emitted file.
std::set<std::string> defined_functions(const std::string& content, const std::string& prefix) {
  std::set<std::string> names;
  const std::regex definition("^[A-Za-z0-9_]+ " + prefix + "([A-Za-z0-9_]+)\\(");
  std::istringstream lines(content);
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    if (std::regex_search(line, match, definition)) names.insert(match[1]);
  }
  return names;
}

std::set<std::string> closure_names(const std::vector<std::string>& roots) {
  std::set<std::string> names;
  for (const saagen::Function* function : Catalogue::builtin().closure(roots)) names.insert(function->name);
  return names;
}

std::vector<saagen::EmittedFile> emit_text(const std::string& text) {
  const saagen::Manifest manifest = parse(text);
  return saagen::emit_scene(Catalogue::builtin(), manifest, saagen::plan_scene(Catalogue::builtin(), manifest));
}

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
  EXPECT_EQ(car.position.line, 28);
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

struct BadCase {
  const char* what;
  std::string text;
  std::string message;
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.what; }

class BadManifest : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadManifest, IsRejectedWithPositionKeyAndWhatIsAllowed) { EXPECT_EQ(error_of(GetParam().text), GetParam().message); }

const std::string material_keys =
    "name, path, anisotropic, tangents, ndf, normal_maps, content, glints, precision, prefer, budget, lights, variant, source";
const std::string filters =
    "\"forward-aniso-slope\", \"forward-aniso-projected\", \"forward-axis-slope\", \"forward-axis-projected\", "
    "\"deferred-previous\", \"deferred-max\", \"deferred-sum\", \"deferred-avg\", \"deferred-projected-space\", \"deferred-aniso\"";

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
        BadCase{"toml_syntax", header + "prefix = = 1\n",
                "scene.toml:2:10: not valid TOML: Error while parsing value: could not determine value type; allowed: TOML 1.0 "
                "(see examples/scene.saagen.toml)"},
        BadCase{
            "unknown_top_key", header + "colour = 1\n" + forward_material,
            "scene.toml:2:1: unknown key 'colour'; allowed keys: name, targets, prefix, gpu_family, lights, sigma2, kappa, glint_count, glint_lods, "
            "glint_alpha, glint_resolution, glint_kernel_scale, glint_max_anisotropy, glint_relative_area, preset, domain, import_path, taa, source, material"},
        BadCase{"unknown_material_key", header + forward_material + "roughness = 0.5\n",
                "scene.toml:5:1: unknown key 'roughness' of material 'm'; allowed keys: " + material_keys},
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

// ---------------------------------------------------------------------------------------------
// Planning

struct RuleCase {
  std::string material;  // the keys after name
  std::string rule;
  std::string variant;
  std::vector<std::string> functions;
};

void PrintTo(const RuleCase& c, std::ostream* os) { *os << c.rule; }

class Rules : public ::testing::TestWithParam<RuleCase> {};

TEST_P(Rules, PickTheDocumentedVariantAndFunctions) {
  const saagen::Manifest manifest = parse(header + "[[material]]\nname = \"m\"\n" + GetParam().material);
  const saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest);
  ASSERT_EQ(plan.materials.size(), 1u);
  EXPECT_EQ(plan.materials[0].rule, GetParam().rule);
  EXPECT_EQ(plan.materials[0].variant, GetParam().variant);
  EXPECT_EQ(plan.materials[0].functions, GetParam().functions);
  EXPECT_FALSE(plan.materials[0].reason.empty());
}

INSTANTIATE_TEST_SUITE_P(
    Planner, Rules,
    // GGX on curved content in a forward pass: rules F1-F3 choose, then saagen's decision on the
    // committed measurement: forward-aniso-projected/tail with tangents (the rule's own F3 form),
    // deferred-aniso/tail without, which did not lose on the held-out models
    // (TableFreeAdviceFollowsTheMeasuredContent); an anisotropic
    // material keeps F1's form, and speed takes no filter for it (its only other form loses);
    // an isotropic one takes forward-aniso-projected for speed too (the cheaper
    // forward-axis-projected/tail loses to no SAA on one of saagen's curved scenes, so it is set
    // aside); the Beckmann cases keep the rules' choice.
    ::testing::Values(RuleCase{"path = \"forward\"\nanisotropic = true\ntangents = true\n",
                               "F1",
                               "forward-aniso-projected",
                               {"forward_aniso_projected", "forward_aniso_projected_fragment", "ggx_brdf_filtered_matrix"}},
                      RuleCase{"path = \"forward\"\nanisotropic = true\ntangents = true\nndf = \"beckmann\"\n",
                               "F1",
                               "forward-aniso-projected",
                               {"forward_aniso_projected", "forward_aniso_projected_fragment", "beckmann_brdf_matrix", "ndf_clamp_tau"}},
                      RuleCase{"path = \"forward\"\nanisotropic = true\ntangents = true\nprefer = \"speed\"\nndf = \"beckmann\"\n",
                               "F2",
                               "forward-axis-projected",
                               {"forward_axis_projected", "forward_axis_projected_fragment"}},  // speed: the engine's own BRDF
                      RuleCase{"path = \"forward\"\nanisotropic = true\ntangents = true\nprefer = \"speed\"\n", "advice", "none", {}},
                      RuleCase{"path = \"forward\"\ntangents = true\n",
                               "F3",
                               "forward-aniso-projected",
                               {"forward_aniso_projected", "forward_aniso_projected_fragment", "ggx_brdf_filtered_matrix"}},
                      RuleCase{"path = \"forward\"\ntangents = true\nprefer = \"speed\"\n",
                               "advice",
                               "forward-aniso-projected",
                               {"forward_aniso_projected", "forward_aniso_projected_fragment", "ggx_brdf_filtered_matrix"}},
                      RuleCase{"path = \"forward\"\ntangents = true\nprefer = \"speed\"\nndf = \"beckmann\"\n",
                               "F4",
                               "deferred-avg",
                               {"deferred_avg", "deferred_avg_fragment"}},
                      RuleCase{"path = \"forward\"\n",
                               "advice",
                               "deferred-aniso",
                               {"deferred_aniso", "deferred_aniso_fragment", "deferred_aniso_roughness", "deferred_aniso_brdf"}},
                      RuleCase{"path = \"forward\"\nndf = \"beckmann\"\n", "F5", "deferred-avg", {"deferred_avg", "deferred_avg_fragment"}},
                      RuleCase{"path = \"forward\"\nprefer = \"speed\"\nndf = \"beckmann\"\n",
                               "F5",
                               "deferred-avg",
                               {"deferred_avg", "deferred_avg_fragment"}},
                      RuleCase{"path = \"deferred\"\n",
                               "D0",
                               "deferred-aniso",
                               {"deferred_aniso", "deferred_aniso_fragment", "deferred_aniso_roughness", "deferred_aniso_brdf"}},
                      // Normal-mapped content: deferred-avg/tail, the largest video gain of the forms that lose to
                      // no SAA on none of saagen's maps (the hdrp bake loses on pmndrs-0014).
                      RuleCase{"path = \"deferred\"\nnormal_maps = true\n",
                               "D1",
                               "deferred-avg",
                               {"deferred_avg", "deferred_avg_fragment", "ggx_brdf_filtered_axis"}},
                      RuleCase{"path = \"deferred\"\nnormal_maps = true\nndf = \"beckmann\"\n",
                               "D1",
                               "deferred-avg",
                               {"deferred_avg", "deferred_avg_fragment"}},
                      RuleCase{
                          "path = \"deferred\"\nndf = \"beckmann\"\n", "D1", "deferred-avg", {"deferred_avg", "deferred_avg_fragment"}},
                      // Curved content: no filter an anisotropic deferred material can use beats no SAA.
                      RuleCase{"path = \"deferred\"\nanisotropic = true\ntangents = true\n", "advice", "none", {}},
                      // With normal maps the same deferred-avg/tail, which an anisotropic material can use too.
                      RuleCase{"path = \"deferred\"\nanisotropic = true\ntangents = true\nnormal_maps = true\n",
                               "D1",
                               "deferred-avg",
                               {"deferred_avg", "deferred_avg_fragment", "ggx_brdf_filtered_axis"}},
                      // Curved content, deferred, speed: only deferred-aniso beats no SAA, the most expensive deferred
                      // form (1.69x); speed never takes it, and the cheaper deferred kernels lose: no filter.
                      RuleCase{"path = \"deferred\"\nprefer = \"speed\"\n", "advice", "none", {}},
                      RuleCase{"path = \"deferred\"\nprefer = \"speed\"\nndf = \"beckmann\"\n",
                               "D2",
                               "deferred-avg",
                               {"deferred_avg", "deferred_avg_fragment"}},
                      RuleCase{"path = \"deferred\"\nvariant = \"deferred-sum\"\n",
                               "manifest",
                               "deferred-sum",
                               {"deferred_sum", "deferred_sum_fragment", "ggx_brdf_filtered_axis"}},
                      RuleCase{"path = \"deferred\"\ntangents = true\nvariant = \"deferred-max\"\n",
                               "manifest",
                               "deferred-max",
                               {"deferred_max", "deferred_max_fragment", "ggx_brdf_filtered_axis"}},
                      RuleCase{"path = \"deferred\"\nvariant = \"deferred-max\"\n",
                               "manifest",
                               "deferred-max",
                               {"deferred_max_tangent_free", "deferred_max_tangent_free_fragment", "ggx_brdf_filtered_axis"}}),
    [](const ::testing::TestParamInfo<RuleCase>& info) { return "case" + std::to_string(info.index) + "_" + info.param.rule; });

// Without a trade table, GGX materials follow saagen's one decision on the committed measurement
// (generator/data/advice.json) per content type, path and TAA: a filter only where it beats no
// SAA beyond its interval on saagen's scenes and does not lose to it on the held-out scenes; no
// filter elsewhere, with the reason and how the advice held.
TEST(Planner, TableFreeAdviceFollowsTheMeasuredContent) {
  const auto plan_of = [](const std::string& top, const std::string& keys) {
    return saagen::plan_scene(Catalogue::builtin(), parse(header + top + "[[material]]\nname = \"m\"\npath = " + keys)).materials.at(0);
  };
  // Curved, forward: forward-aniso-projected/tail (the rule's own form, F3) beats no SAA on
  // saagen's scenes most in the video error and does not lose on the held-out models (it ties).
  const auto forward = plan_of("", "\"forward\"\ntangents = true\n");
  EXPECT_EQ(forward.variant, "forward-aniso-projected");
  EXPECT_EQ(forward.rule, "F3");
  EXPECT_NE(forward.measure_advice.find("this advice held on content it was not derived from"), std::string::npos)
      << forward.measure_advice;
  // Curved, deferred: the same.
  const auto deferred = plan_of("", "\"deferred\"\n");
  EXPECT_EQ(deferred.variant, "deferred-aniso");
  EXPECT_NE(deferred.reason.find("deferred-aniso/tail (image -"), std::string::npos) << deferred.reason;
  EXPECT_NE(deferred.measure_advice.find("this advice held on content it was not derived from (held-out scenes duck, WusonOBJ, teapots: "),
            std::string::npos)
      << deferred.measure_advice;
  // Speed never takes the most expensive form: on curved content in the deferred path only
  // deferred-aniso beats no SAA, so no filter.
  const auto speed = plan_of("", "\"deferred\"\nprefer = \"speed\"\n");
  EXPECT_EQ(speed.variant, "none");
  EXPECT_NE(speed.reason.find("most expensive form"), std::string::npos) << speed.reason;
  // Normal-mapped: the forms with the largest video gain on the content's mean (the hdrp bake on
  // the geometric normal, the map-fed deferred-sum/tail) lose to no SAA on one of its scenes
  // (pmndrs-0014), so they are set aside; deferred-avg/tail beats no SAA on every one, and on the
  // held-out maps.
  const auto mapped = plan_of("", "\"deferred\"\nnormal_maps = true\n");
  EXPECT_EQ(mapped.variant, "deferred-avg");
  EXPECT_EQ(mapped.feed, "shading");
  EXPECT_EQ(mapped.prefilter, "none");
  EXPECT_NE(mapped.reason.find("set aside, more accurate on the mean but losing to no SAA on a scene of the content: "), std::string::npos)
      << mapped.reason;
  EXPECT_NE(mapped.reason.find("deferred-aniso:geometric+hdrp/tail (loses on pmndrs-0014)"), std::string::npos) << mapped.reason;
  EXPECT_NE(mapped.measure_advice.find("this advice held on content it was not derived from (held-out scenes pmndrs-0000"),
            std::string::npos)
      << mapped.measure_advice;
  // Named, a normal-mapped filter gets the same decision among its own feeds and bakes: deferred-sum
  // on the geometric normal without a bake (the map-fed form and the bake lose on pmndrs-0014).
  const auto named = plan_of("", "\"deferred\"\nnormal_maps = true\nvariant = \"deferred-sum\"\n");
  EXPECT_EQ(named.variant, "deferred-sum");
  EXPECT_EQ(named.feed, "geometric");
  EXPECT_EQ(named.prefilter, "none");
  EXPECT_EQ(named.normal_advice.rfind("deferred-sum:geometric/tail (image ", 0), 0u) << named.normal_advice;
  EXPECT_NE(named.normal_advice.find("deferred-sum/tail (loses on pmndrs-0014)"), std::string::npos) << named.normal_advice;
  EXPECT_NE(named.normal_advice.find("this advice held on content it was not derived from"), std::string::npos) << named.normal_advice;
  EXPECT_EQ(named.normal_advice.find("--method"), std::string::npos) << named.normal_advice;
  // Clearcoat: deferred-aniso/tail beats no SAA on ClearCoatTest's coat; no held-out content to
  // report on.
  const auto coat = plan_of("", "\"deferred\"\ncontent = \"clearcoat\"\n");
  EXPECT_EQ(coat.variant, "deferred-aniso");
  EXPECT_NE(coat.reason.find("deferred-aniso/tail (image -"), std::string::npos) << coat.reason;
  EXPECT_NE(coat.reason.find("on clearcoat content in saagen's trade (ClearCoatTest-coat"), std::string::npos) << coat.reason;
  EXPECT_NE(coat.measure_advice.find("has no held-out clearcoat content"), std::string::npos) << coat.measure_advice;
  // Every table-free plan says how to measure one's own asset.
  for (const auto* plan : {&forward, &deferred, &speed, &mapped, &coat})
    EXPECT_NE(plan->measure_advice.find("saagen plan --gltf ASSET.glb -o MANIFEST --measure"), std::string::npos) << plan->measure_advice;
  // Under TAA the committed rows measured under TAA decide, each against none+taa: curved content
  // gets the filter that beats TAA alone there and on the held-out models; normal-mapped content
  // no filter (its best form is worse in the image error on the held-out maps, as without TAA).
  const auto taa_forward = plan_of("taa = true\n", "\"forward\"\ntangents = true\n");
  EXPECT_EQ(taa_forward.variant, "forward-axis-projected");
  EXPECT_NE(taa_forward.reason.find("against none+taa; "), std::string::npos) << taa_forward.reason;
  EXPECT_NE(taa_forward.reason.find("curved content under TAA in saagen's trade (sphere, torus"), std::string::npos) << taa_forward.reason;
  EXPECT_NE(taa_forward.measure_advice.find("this advice held on content it was not derived from (held-out scenes duck, WusonOBJ, teapots"),
            std::string::npos)
      << taa_forward.measure_advice;
  EXPECT_NE(taa_forward.measure_advice.find("saagen bench --scene ASSET.glb --taa --sigma2 0.0625"), std::string::npos)
      << taa_forward.measure_advice;
  const auto taa_mapped = plan_of("taa = true\n", "\"deferred\"\nnormal_maps = true\n");
  EXPECT_EQ(taa_mapped.variant, "none");
  EXPECT_NE(taa_mapped.reason.find("but it does not hold on the held-out scenes"), std::string::npos) << taa_mapped.reason;
  EXPECT_NE(taa_mapped.reason.find("against none+taa: mixed"), std::string::npos) << taa_mapped.reason;
  // A named variant, a Beckmann material and an engine's preset keep what they say.
  EXPECT_EQ(plan_of("taa = true\n", "\"deferred\"\nvariant = \"deferred-sum\"\n").variant, "deferred-sum");
  EXPECT_EQ(plan_of("taa = true\n", "\"deferred\"\nndf = \"beckmann\"\n").variant, "deferred-avg");
}

// `budget`: the most accurate configuration within that shading cost over no SAA (vega10 ISA) that
// beats no SAA, else no filter with the reason; a budget outside [1, 16] is one line.
TEST(Planner, BudgetTakesTheMostAccurateWithinIt) {
  const auto plan_of = [](const std::string& keys) {
    return saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = " + keys)).materials.at(0);
  };
  // Curved content, deferred: only deferred-aniso/tail (1.69x) beats no SAA.
  const auto tight = plan_of("\"deferred\"\nbudget = 1.5\n");
  EXPECT_EQ(tight.variant, "none");
  EXPECT_NE(tight.reason.find("costs more than the budget 1.5"), std::string::npos) << tight.reason;
  const auto loose = plan_of("\"deferred\"\nbudget = 2\nprefer = \"speed\"\n");  // the budget decides, not prefer
  EXPECT_EQ(loose.variant, "deferred-aniso");
  EXPECT_NE(loose.reason.find("within the budget 2"), std::string::npos) << loose.reason;
  // Bumps, forward: deferred-aniso:geometric/tail is the most accurate; within 1.4 a cheaper form
  // that also beats no SAA is taken.
  const auto mapped = plan_of("\"forward\"\ntangents = true\ncontent = \"bumps\"\nbudget = 1.4\n");
  EXPECT_NE(mapped.variant, "none");
  EXPECT_NE(mapped.variant, "deferred-aniso");
  EXPECT_NE(mapped.reason.find("within the budget 1.4"), std::string::npos) << mapped.reason;
  EXPECT_EQ(error_of(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nbudget = 0.5\n").rfind("scene.toml:5:10: key 'budget'", 0),
            0u)
      << error_of(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nbudget = 0.5\n");
  EXPECT_NE(error_of(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nbudget = \"a lot\"\n").find("budget"), std::string::npos);
}

// The ISA ratios at a material's light count, from the committed table (vega10, every target).
double committed_ratio(const std::string& configuration, int lights) {
  const auto ratio = saagen::committed_isa_costs().forward_ratio("vega10", configuration, {}, lights);
  EXPECT_TRUE(ratio.has_value()) << configuration << " at " << lights << " lights";
  return ratio.value_or(0.0);
}

// deferred-aniso computes its tensor once per pixel and evaluates a 2x2 matrix lobe per light, so
// its cost over no SAA moves with the lights (in the committed table it falls: the tensor's share
// shrinks, and its lobe per light costs less over no SAA's BRDF than the one-light ratio): a budget
// between its one-light and 16-light ratios fits at one of the two counts and not at the other, and
// the plan names the light count the cost was read at.
TEST(Planner, BudgetIsReadAtTheMaterialsLightCount) {
  const double one = committed_ratio("deferred-aniso/tail", 1), four = committed_ratio("deferred-aniso/tail", 4),
               sixteen = committed_ratio("deferred-aniso/tail", 16);
  ASSERT_NE(one, sixteen);
  ASSERT_NE(four, sixteen);
  const auto plan_of = [](double budget, const std::string& lights) {
    return saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\n" +
                                                          fmt::format("budget = {:.6f}\n", budget) + lights))
        .materials.at(0);
  };
  const double between = (one + sixteen) / 2;
  const auto at_one = plan_of(between, "");
  const auto at_sixteen = plan_of(between, "lights = 16\n");
  EXPECT_EQ(at_one.cost_lights, 1);
  EXPECT_NE(at_one.reason.find(fmt::format("{:.3g}x no SAA's shading cost at 1 light", one)), std::string::npos) << at_one.reason;
  EXPECT_NE(at_sixteen.reason.find(fmt::format("{:.3g}x no SAA's shading cost at 16 lights", sixteen)), std::string::npos)
      << at_sixteen.reason;
  const auto& within = one < sixteen ? at_one : at_sixteen;
  const auto& over = one < sixteen ? at_sixteen : at_one;
  EXPECT_EQ(within.variant, "deferred-aniso") << within.reason;
  EXPECT_EQ(over.variant, "none") << over.reason;
  EXPECT_NE(over.reason.find("deferred-aniso/tail (image"), std::string::npos) << over.reason;
  EXPECT_NE(over.reason.find("costs more than the budget"), std::string::npos) << over.reason;
  // Between measured counts the cost is the nearest measured count's not above: 15 lights read
  // the 4-light ratio, so a budget between the 4- and 16-light ratios decides as at 4 lights.
  const auto at_fifteen = plan_of((four + sixteen) / 2, "lights = 15\n");
  EXPECT_EQ(at_fifteen.variant, four < sixteen ? "deferred-aniso" : "none") << at_fifteen.reason;
  EXPECT_EQ(at_fifteen.lights, 15);
  EXPECT_EQ(at_fifteen.cost_lights, 4);
  EXPECT_NE(at_fifteen.reason.find("at 4 lights (the nearest measured count not above 15)"), std::string::npos) << at_fifteen.reason;
}

// The papers' deferred forms compute the roughness once per pixel and then shade with the plain
// BRDF: their overhead shrinks as the lights grow. Every lobe saagen shades with costs per light
// (the forward forms filter per light too), so theirs stays.
TEST(Planner, CommittedCostsGrowPerLightAndShrinkPerPixel) {
  for (const std::string per_pixel : {"deferred-avg", "deferred-sum"}) {
    EXPECT_LT(committed_ratio(per_pixel, 4), committed_ratio(per_pixel, 1)) << per_pixel;
    EXPECT_LT(committed_ratio(per_pixel, 16), committed_ratio(per_pixel, 4)) << per_pixel;
  }
  // The forward forms filter and shade per light: their cost grows.
  for (const std::string per_light : {"forward-aniso-projected", "forward-aniso-projected/tail", "forward-axis-projected/tail"}) {
    EXPECT_GT(committed_ratio(per_light, 4), committed_ratio(per_light, 1)) << per_light;
    EXPECT_GT(committed_ratio(per_light, 16), committed_ratio(per_light, 4)) << per_light;
  }
  // A deferred form with saagen's lobe pays its roughness once per pixel and the lobe per light:
  // its ratio tends to the lobe's own over no SAA's BRDF (from above in the committed table, where
  // the lobe takes G2 and the cosines in one reciprocal), which does not vanish as the papers'
  // per-pixel overhead does: at 16 lights at least ten times deferred-avg's.
  const double papers_overhead = committed_ratio("deferred-avg", 16) - 1.0;
  for (const std::string per_light : {"deferred-avg/tail", "deferred-sum/tail", "deferred-aniso/tail"}) {
    EXPECT_GT(committed_ratio(per_light, 16) - 1.0, 10.0 * papers_overhead) << per_light;
  }
  // A table without light counts (written before they were measured) is one light's.
  const saagen::IsaTable old = saagen::parse_isa_table(
      R"({"families": ["vega10"], "rows": [{"family": "vega10", "shader": "forward", "target": "glsl", "variant": "deferred-avg",
          "instructions": 1, "vgprs": 1, "sgprs": 1, "subgroups_per_simd": 1, "latency": 1, "inverse_throughput": 1,
          "inverse_throughput_ratio": 1.25}]})",
      "old.json");
  EXPECT_EQ(old.rows.at(0).lights, 1);
  EXPECT_EQ(old.cost_light_count("vega10", 16), 1);
  EXPECT_EQ(old.forward_ratio("vega10", "deferred-avg", {}, 16), 1.25);
  const saagen::IsaTable& committed = saagen::committed_isa_costs();
  EXPECT_EQ(committed.light_counts("vega10"), (std::vector<int>{1, 4, 16}));
  EXPECT_EQ(committed.cost_light_count("vega10", 3), 1);
  EXPECT_EQ(committed.cost_light_count("vega10", 4), 4);
  EXPECT_EQ(committed.cost_light_count("vega10", 64), 16);
  const auto bad_lights = [](const std::string& value) -> std::string {
    try {
      (void)saagen::parse_isa_table(R"({"families": ["vega10"], "rows": [{"family": "vega10", "shader": "forward", "target": "glsl",
          "variant": "deferred-avg", "instructions": 1, "vgprs": 1, "sgprs": 1, "subgroups_per_simd": 1, "latency": 1,
          "inverse_throughput": 1, "inverse_throughput_ratio": 1.25, "lights": )" +
                                        value + "}]}",
                                    "bad.json");
    } catch (const saagen::Error& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_NE(bad_lights("0").find("bad.json: a row's \"lights\" must be an integer from 1 to 64"), std::string::npos) << bad_lights("0");
  EXPECT_NE(bad_lights("2.5").find("must be an integer"), std::string::npos) << bad_lights("2.5");
  EXPECT_EQ(bad_lights("64"), "");
}

// prefer = "speed" at any light count: the decision's costs are the committed ratios at that
// count, and it never takes the most expensive form the material can use (unless it is the only
// one), on every content type and path of saagen's committed measurement.
TEST(Planner, SpeedAtEveryLightCountNeverTakesTheDearestForm) {
  int decided = 0;
  for (const saagen::advice::Content content : {saagen::advice::Content::curved, saagen::advice::Content::normal_mapped,
                                                saagen::advice::Content::bumps, saagen::advice::Content::clearcoat}) {
    const saagen::AdviceMeasurement* measured = saagen::committed_advice().find(saagen::advice::table_content(content));
    if (!measured) continue;
    for (const saagen::RenderPath path : {saagen::RenderPath::forward, saagen::RenderPath::deferred}) {
      for (const int lights : {1, 4, 16, 40}) {
        saagen::Material material = saagen::reference_material(path, content);
        material.prefer = saagen::Preference::speed;
        material.lights = lights;
        const saagen::MaterialDecision made = saagen::decide_material(Catalogue::builtin(), material, "", measured->rows);
        std::optional<double> dearest;
        int usable = 0;
        for (const saagen::decision::Candidate& candidate : made.candidates) {
          if (candidate.configuration == "deferred-aniso/tail") {
            EXPECT_EQ(candidate.cost_ratio, committed_ratio("deferred-aniso/tail", lights)) << lights;
          }
          if (!candidate.usable) continue;
          ++usable;
          if (candidate.cost_ratio && (!dearest || *candidate.cost_ratio > *dearest)) dearest = candidate.cost_ratio;
        }
        if (!made.decision.chosen || usable == 1) continue;
        ++decided;
        const saagen::decision::Candidate& chosen = made.candidates[*made.decision.chosen];
        ASSERT_TRUE(chosen.cost_ratio.has_value());
        EXPECT_LT(*chosen.cost_ratio * (1.0 + saagen::decision::kCostTieTolerance), *dearest)
            << saagen::advice::name(content) << " " << saagen::to_string(path) << " at " << lights << ": " << made.decision.reason;
        const std::string words = lights == 1 ? "at 1 light" : fmt::format("at {} lights", std::min(lights, 16));
        EXPECT_NE(made.decision.reason.find(words), std::string::npos) << made.decision.reason;
      }
    }
  }
  EXPECT_GE(decided, 8);  // normal-mapped and bump content on both paths at every count
}

// The rules' speed ranking reads the light count too, and a trade table's ISA figures (one
// light, as `saagen bench` measures) serve only materials costed at one light.
TEST(Planner, RuleSpeedRankingStatesItsLightCount) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [
      {"variant": "deferred-sum", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.0},
      {"variant": "deferred-avg", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.5}]})",
                                                                     "bench.json");
  const auto plan_of = [&](const std::string& lights) {
    return saagen::plan_scene(
               Catalogue::builtin(),
               parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nprefer = \"speed\"\nndf = \"beckmann\"\n" + lights), &table)
        .materials.at(0);
  };
  const auto one = plan_of("");
  EXPECT_EQ(one.variant, "deferred-sum") << one.reason;
  EXPECT_NE(one.reason.find("bench.json (at 1 light)"), std::string::npos) << one.reason;
  const auto sixteen = plan_of("lights = 16\n");
  EXPECT_NE(sixteen.reason.find("generator/data/isa_cost.json (vega10, Mesa"), std::string::npos) << sixteen.reason;
  EXPECT_NE(sixteen.reason.find("at 16 lights"), std::string::npos) << sixteen.reason;
  EXPECT_NE(sixteen.reason.find(fmt::format("deferred-avg {:.4g}", committed_ratio("deferred-avg", 16))), std::string::npos)
      << sixteen.reason;
}

// The goal of the table-free advice, on every content type, path and preference: what a plan
// gives beats no SAA beyond its interval on saagen's scenes and does not lose to it (in either
// metric) on the held-out scenes; where it gives nothing, the decision found nothing there or its
// choice lost on the held-out scenes.
TEST(Planner, TableFreeAdviceNeverGivesWhatLosesOnHeldOutContent) {
  const saagen::AdviceTable& table = saagen::committed_advice();
  ASSERT_FALSE(table.contents.empty());
  int given = 0, withheld = 0;
  for (const bool taa : {false, true}) {
    for (const auto content : {saagen::advice::Content::curved, saagen::advice::Content::normal_mapped, saagen::advice::Content::bumps,
                               saagen::advice::Content::clearcoat}) {
      const saagen::AdviceMeasurement* measured = table.find(saagen::advice::table_content(content), taa);
      ASSERT_NE(measured, nullptr) << saagen::advice::name(content);
      for (const auto path : {saagen::RenderPath::forward, saagen::RenderPath::deferred}) {
        for (const auto prefer : {saagen::Preference::accuracy, saagen::Preference::speed}) {
          saagen::Material material = saagen::reference_material(path, content);
          material.prefer = prefer;
          saagen::Manifest manifest = parse(header + "[[material]]\nname = \"m\"\npath = \"forward\"\n");
          manifest.taa = taa;
          manifest.materials = {material};
          const saagen::MaterialPlan plan = saagen::plan_scene(Catalogue::builtin(), manifest).materials.at(0);
          const saagen::MaterialDecision made =
              saagen::decide_material(Catalogue::builtin(), material, "", measured->rows, taa ? "none+taa" : "no SAA");
          const std::string where =
              std::string(saagen::advice::name(content)) + " " + std::string(saagen::to_string(path)) + (taa ? " taa" : "");
          if (!made.decision.chosen) {
            EXPECT_EQ(plan.variant, "none") << where;
            continue;
          }
          const saagen::decision::Candidate& chosen = made.candidates[*made.decision.chosen];
          EXPECT_EQ(saagen::decision::outcome(chosen.against_none), saagen::decision::Outcome::beats) << where;
          EXPECT_TRUE(chosen.loses_on.empty()) << where;  // it loses on none of the content's own scenes
          const auto held_out = measured->held_out(chosen.configuration);
          const bool loses_there = held_out && (saagen::decision::outcome(*held_out) == saagen::decision::Outcome::loses ||
                                                saagen::decision::outcome(*held_out) == saagen::decision::Outcome::mixed);
          EXPECT_EQ(plan.variant == "none", loses_there) << where << ": " << plan.reason;
          (loses_there ? withheld : given) += 1;
        }
      }
    }
  }
  EXPECT_GT(given, 0);
  EXPECT_GT(withheld, 0);  // the gate is exercised by the committed measurement (normal-mapped under TAA)
}

// The held-out check on a measurement of our own making: the decision's pick beats no SAA on the
// scenes it is derived from and loses on the held-out ones, so it is withheld: no filter for a
// material the planner chooses for; for one that names its variant, that variant's own input (the
// normal-mapped normal without a bake), with that row's figures.
TEST(Planner, APickThatFailsOnTheHeldOutScenesIsWithheld) {
  const auto comparison = [](double image, double temporal) {
    return fmt::format(R"({{"image": {{"mean": {0}, "low": {0}, "high": {0}}}, "temporal": {{"mean": {1}, "low": {1}, "high": {1}}}}})",
                       image, temporal);
  };
  const std::string rows =
      fmt::format(R"([{{"configuration": "none", "image_error": 0.05, "video_error": 4}},
        {{"configuration": "deferred-sum:geometric+hdrp/tail", "image_error": 0.04, "video_error": 2, "against_none": {0}, "held_out": {1}}},
        {{"configuration": "deferred-sum/tail", "image_error": 0.045, "video_error": 3, "against_none": {2}, "held_out": {3}}}])",
                  comparison(-0.01, -2.0), comparison(0.005, -1.0), comparison(-0.005, -1.0), comparison(-0.004, -0.8));
  const saagen::AdviceTable advice = saagen::parse_advice_table(
      R"({"schema": "saagen advice 1", "content": [{"content": "normal-mapped", "scenes": ["a"], "held_out_scenes": ["b"], "rows": )" +
          rows + "}]}",
      "advice.json");
  const std::string material = "[[material]]\nname = \"m\"\npath = \"deferred\"\nnormal_maps = true\n";
  const saagen::MaterialPlan chosen = saagen::plan_scene(Catalogue::builtin(), parse(header + material), nullptr, advice).materials.at(0);
  EXPECT_EQ(chosen.variant, "none") << chosen.reason;
  EXPECT_NE(chosen.reason.find("but it does not hold on the held-out scenes (b: image error +0.005"), std::string::npos) << chosen.reason;
  const saagen::MaterialPlan named =
      saagen::plan_scene(Catalogue::builtin(), parse(header + material + "variant = \"deferred-sum\"\n"), nullptr, advice).materials.at(0);
  EXPECT_EQ(named.variant, "deferred-sum");
  EXPECT_EQ(named.feed, "shading");
  EXPECT_EQ(named.prefilter, "none");
  EXPECT_NE(
      named.normal_advice.find("saagen's decision takes deferred-sum:geometric+hdrp/tail, but it does not hold on the held-out scenes"),
      std::string::npos)
      << named.normal_advice;
  EXPECT_NE(named.normal_advice.find("measured: deferred-sum/tail (image error -0.005"), std::string::npos) << named.normal_advice;
}

// `saagen plan --advice`'s table is what examples/INTEGRATION.md holds.
TEST(Planner, IntegrationGuideHoldsTheAdviceTable) {
  const std::string guide = read_text(fs::path(SAAGEN_SOURCE_DIR) / "examples" / "INTEGRATION.md");
  const std::string begin = "<!-- saagen plan --advice -->\n", end = "<!-- end saagen plan --advice -->";
  const auto from = guide.find(begin), to = guide.find(end);
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  EXPECT_EQ(guide.substr(from + begin.size(), to - from - begin.size()), saagen::advice_markdown(Catalogue::builtin()))
      << "regenerate the table with `saagen plan --advice`";
}

// A material advised no filter has nothing in the bundle; the plan says so; a scene whose every
// material is advised none emits no file.
TEST(Planner, NoFilterMaterialsEmitNothing) {
  const saagen::Manifest manifest = parse(header + "[[material]]\nname = \"coat\"\npath = \"deferred\"\nprefer = \"speed\"\n" +
                                          "[[material]]\nname = \"ball\"\npath = \"deferred\"\n");
  saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest);
  saagen::measure_costs(Catalogue::builtin(), manifest, plan);
  EXPECT_TRUE(plan.materials.at(0).cost.empty());
  const auto files = saagen::emit_scene(Catalogue::builtin(), manifest, plan);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].content.find("coat ("), std::string::npos);
  EXPECT_NE(files[0].content.find("ball ("), std::string::npos);
  const std::string text = saagen::format_plan(Catalogue::builtin(), manifest, plan);
  EXPECT_NE(text.find("  variant   none  [advice]\n"), std::string::npos) << text;
  EXPECT_NE(text.find("no SAA filter, nothing in the bundle"), std::string::npos) << text;
  const saagen::Manifest taa = parse(header + "taa = true\n[[material]]\nname = \"m\"\npath = \"deferred\"\nprefer = \"speed\"\n");
  EXPECT_TRUE(saagen::emit_scene(Catalogue::builtin(), taa, saagen::plan_scene(Catalogue::builtin(), taa)).empty());
  EXPECT_EQ(error_of(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\ncontent = \"normal-mapped\"\n"),
            "scene.toml:5:11: key 'content' of material 'm': \"normal-mapped\" needs normal_maps = true; allowed: normal_maps = true, or "
            "another content type");
}

// With a trade table's rows for the material's content, the planner never keeps a configuration
// that loses to the table's no-SAA row (in the error, and in TDE where both have it): it takes the
// best allowed configuration that beats it, or no filter.
TEST(Planner, WithATableNoFilterWinsWhereNothingBeatsIt) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [], "by_content": [
      {"content": "curved", "configuration": "none", "error": 0.03, "tde": 0.010},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.04, "tde": 0.012},
      {"content": "curved", "configuration": "deferred-avg/tail", "error": 0.05, "tde": 0.009},
      {"content": "normal-mapped", "configuration": "none", "error": 0.04, "tde": 0.010},
      {"content": "normal-mapped", "configuration": "deferred-avg:geometric+hdrp/tail", "error": 0.02, "tde": 0.011},
      {"content": "normal-mapped", "configuration": "deferred-sum:geometric/tail", "error": 0.03, "tde": 0.009}]})",
                                                                     "none-wins.json");
  const saagen::Manifest manifest = parse(header + "[[material]]\nname = \"a\"\npath = \"deferred\"\n" +
                                          "[[material]]\nname = \"b\"\npath = \"deferred\"\nnormal_maps = true\n");
  const saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest, &table);
  EXPECT_EQ(plan.materials.at(0).variant, "none");
  EXPECT_EQ(plan.materials.at(0).rule, "trade table");
  EXPECT_NE(plan.materials.at(0).reason.find("beats no SAA; the lowest temporal error, deferred-avg/tail (image +0.02, temporal -0.001"),
            std::string::npos)
      << plan.materials.at(0).reason;
  EXPECT_NE(plan.materials.at(0).reason.find("on curved content in none-wins.json"), std::string::npos) << plan.materials.at(0).reason;
  // The lowest error (deferred-avg with the bake) loses in TDE; deferred-sum on the geometric normal beats none in both.
  EXPECT_EQ(plan.materials.at(1).variant, "deferred-sum");
  EXPECT_EQ(plan.materials.at(1).feed, "geometric");
  EXPECT_EQ(plan.materials.at(1).prefilter, "none");
  EXPECT_NE(plan.materials.at(1).reason.find("deferred-sum:geometric/tail (image -0.01, temporal -0.001"), std::string::npos)
      << plan.materials.at(1).reason;
  EXPECT_NE(saagen::format_plan(Catalogue::builtin(), manifest, plan).find("material a"), std::string::npos);
}

// With a table, speed takes the cheapest configuration that beats no SAA, judged on the rows of the
// lobe the plan shades with (the papers' rows measure an engine's own BRDF), and never the most
// expensive form the material can use: where only that one beats no SAA, no filter.
TEST(Planner, WithATableSpeedTakesTheCheapestThatBeatsNeverTheDearest) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [], "by_content": [
      {"content": "curved", "configuration": "none", "error": 0.03, "tde": 0.010},
      {"content": "curved", "configuration": "deferred-sum", "error": 0.01, "tde": 0.005},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.02, "tde": 0.009},
      {"content": "curved", "configuration": "deferred-avg/tail", "error": 0.05, "tde": 0.012}]})",
                                                                     "speed.json");
  const saagen::MaterialPlan plan =
      saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nprefer = \"speed\"\n"),
                         &table)
          .materials.at(0);
  EXPECT_EQ(plan.variant, "none");
  EXPECT_EQ(plan.rule, "trade table");
  EXPECT_NE(plan.reason.find("most expensive form"), std::string::npos) << plan.reason;
  EXPECT_NE(plan.reason.find("deferred-aniso/tail (image -0.01, temporal -0.001"), std::string::npos) << plan.reason;
  // A cheaper form that beats no SAA is taken.
  const saagen::MeasuredTradeTable cheaper = saagen::parse_trade_table(R"({"rows": [], "by_content": [
      {"content": "curved", "configuration": "none", "error": 0.03, "tde": 0.010},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.02, "tde": 0.009},
      {"content": "curved", "configuration": "deferred-sum/tail", "error": 0.029, "tde": 0.0099},
      {"content": "curved", "configuration": "deferred-avg/tail", "error": 0.05, "tde": 0.012}]})",
                                                                       "cheaper.json");
  const saagen::MaterialPlan sum =
      saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nprefer = \"speed\"\n"),
                         &cheaper)
          .materials.at(0);
  EXPECT_EQ(sum.variant, "deferred-sum");
  EXPECT_NE(sum.reason.find("the lowest cost of the 2 usable configurations that do"), std::string::npos) << sum.reason;
}

// With a table, accuracy is judged on the material's content: the table's best configuration there
// that beats no SAA, not the variant with the lowest mean over every scene (there deferred-aniso,
// measured on curved content behind forward-aniso-projected). So a table made of the same
// measurement as saagen's advice plans what the advice says.
TEST(Planner, WithATableAccuracyTakesTheBestOnTheMaterialsContent) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [
      {"variant": "deferred-aniso", "error": 0.0655}, {"variant": "forward-aniso-projected", "error": 0.0656}], "by_content": [
      {"content": "curved", "configuration": "none", "error": 0.0308, "tde": 0.01436},
      {"content": "curved", "configuration": "forward-aniso-projected/tail", "error": 0.0253, "tde": 0.01184},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.0259, "tde": 0.01187},
      {"content": "curved", "configuration": "deferred-avg/tail", "error": 0.0497, "tde": 0.01553}]})",
                                                                     "content.json");
  const auto plan_of = [&](const std::string& keys) {
    return saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\n" + keys), &table).materials.at(0);
  };
  const saagen::MaterialPlan forward = plan_of("path = \"forward\"\ntangents = true\n");
  EXPECT_EQ(forward.variant, "forward-aniso-projected");
  EXPECT_EQ(forward.rule, "trade table");
  EXPECT_NE(
      forward.reason.find("saagen's decision on curved content in content.json: forward-aniso-projected/tail (image -0.0055, "
                          "temporal -0.00252 against no SAA; 1.2x no SAA's shading cost at 1 light) beats no SAA: the largest temporal "
                          "improvement of the 2 usable configurations that do; deferred-aniso (trade table) is not it"),
      std::string::npos)
      << forward.reason;
  // Without a table the committed measurement decides (TableFreeAdviceFollowsTheMeasuredContent):
  // the same form there, by the rule's own F3 since the advice agrees with it.
  const saagen::MaterialPlan table_free =
      saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = \"forward\"\ntangents = true\n"))
          .materials.at(0);
  EXPECT_EQ(table_free.variant, "forward-aniso-projected");
  EXPECT_EQ(table_free.rule, "F3");
  // A deferred material cannot use the forward form: deferred-aniso, the best it can use.
  EXPECT_EQ(plan_of("path = \"deferred\"\n").variant, "deferred-aniso");
  // Speed: the cheapest form, deferred-avg, loses to no SAA here, and deferred-aniso is the most
  // expensive one: forward-aniso-projected.
  const saagen::MaterialPlan speed = plan_of("path = \"forward\"\ntangents = true\nprefer = \"speed\"\n");
  EXPECT_EQ(speed.variant, "forward-aniso-projected");
  EXPECT_NE(speed.reason.find("the lowest cost of the 2 usable configurations that do"), std::string::npos) << speed.reason;
}

// A normal-mapped deferred material planned deferred-aniso with a prefiltered map gets the lighting
// pass with the texture covariance (A = diag(alpha^2) + (n.h)^2 K + C, as the trade's
// deferred-aniso:FEED+PREFILTER rows shade): with LEAN the geometry pass's
// deferred_aniso_covariance too, with a scalar bake the covariance (v, 0, v).
TEST(Planner, NormalMappedDeferredAnisoTakesTheTextureCovariance) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [], "by_content": [
      {"content": "normal-mapped", "configuration": "none", "error": 0.06, "tde": 0.0146},
      {"content": "normal-mapped", "configuration": "deferred-aniso:geometric+lean/tail", "error": 0.05, "tde": 0.0140}]})",
                                                                     "lean.json");
  const saagen::Manifest manifest = parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nnormal_maps = true\n");
  saagen::ScenePlan scene = saagen::plan_scene(Catalogue::builtin(), manifest, &table);
  const saagen::MaterialPlan& lean = scene.materials.at(0);
  ASSERT_EQ(lean.variant, "deferred-aniso") << lean.reason;
  EXPECT_EQ(lean.prefilter, "lean");
  EXPECT_EQ(lean.functions, (std::vector<std::string>{"deferred_aniso", "deferred_aniso_fragment", "deferred_aniso_covariance",
                                                      "deferred_aniso_roughness_with_covariance", "deferred_aniso_brdf_with_covariance"}));
  EXPECT_EQ(lean.brdf, std::optional<std::string>("deferred_aniso_brdf_with_covariance"));
  const std::string text = saagen::format_plan(Catalogue::builtin(), manifest, scene);
  EXPECT_NE(text.find("deferred_aniso_brdf_with_covariance(light_ws, view_ws, normal_ws, tensor, covariance, alpha2) per light"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("C = saa_deferred_aniso_covariance(slope_mean, slope_second, tangent_ws, bitangent_ws, normal_ws)"),
            std::string::npos)
      << text;
  // The cost kernel compiles with the covariance, and the bundle defines the three functions.
  saagen::measure_costs(Catalogue::builtin(), manifest, scene);
  EXPECT_GT(scene.materials.at(0).cost.at(saagen::OutputTarget::snippet("glsl")), 0);
  const std::set<std::string> defined =
      defined_functions(saagen::emit_scene(Catalogue::builtin(), manifest, scene).at(0).content, manifest.prefix);
  for (const char* name : {"deferred_aniso_covariance", "deferred_aniso_roughness_with_covariance", "deferred_aniso_brdf_with_covariance"})
    EXPECT_TRUE(defined.count(name)) << name;

  // Named, with a table whose decision takes the hdrp bake: the lighting pass takes (v, 0, v).
  const saagen::MeasuredTradeTable hdrp_table = saagen::parse_trade_table(R"({"rows": [], "by_content": [
      {"content": "normal-mapped", "configuration": "none", "error": 0.06, "tde": 0.0146},
      {"content": "normal-mapped", "configuration": "deferred-aniso:geometric+hdrp/tail", "error": 0.05, "tde": 0.0140}]})",
                                                                          "hdrp.json");
  const saagen::Manifest named =
      parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nnormal_maps = true\nvariant = \"deferred-aniso\"\n");
  const saagen::ScenePlan advised = saagen::plan_scene(Catalogue::builtin(), named, &hdrp_table);
  const saagen::MaterialPlan& hdrp = advised.materials.at(0);
  EXPECT_EQ(hdrp.prefilter, "hdrp");
  EXPECT_EQ(hdrp.functions, (std::vector<std::string>{"deferred_aniso", "deferred_aniso_fragment",
                                                      "deferred_aniso_roughness_with_covariance", "deferred_aniso_brdf_with_covariance"}));
  EXPECT_NE(saagen::format_plan(Catalogue::builtin(), named, advised).find("C = (v, 0, v) of the hdrp bake"), std::string::npos);
  // Without normal maps the plan keeps the plain lighting pass (D0).
  const saagen::MaterialPlan plain =
      saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\n")).materials.at(0);
  EXPECT_EQ(plain.brdf, std::optional<std::string>("deferred_aniso_brdf"));
}

// On bump content the trade's prefiltered rows are a procedural shader band-limited to its
// footprint (bump_plane "+lean"), code the plan does not write: a bumps material without normal
// maps is never planned from them, even where they are the only rows that beat no SAA.
TEST(Planner, BumpMaterialsAreNotPlannedFromBandLimitedRows) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [], "by_content": [
      {"content": "bump", "configuration": "none", "error": 0.34, "tde": 0.141},
      {"content": "bump", "configuration": "deferred-aniso:geometric+lean/tail", "error": 0.20, "tde": 0.098},
      {"content": "bump", "configuration": "deferred-aniso/tail", "error": 0.23, "tde": 0.198}]})",
                                                                     "bump.json");
  const saagen::MaterialPlan plan =
      saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\ncontent = \"bumps\"\n"),
                         &table)
          .materials.at(0);
  EXPECT_EQ(plan.variant, "none") << plan.reason;
  EXPECT_EQ(plan.rule, "trade table");
  EXPECT_NE(plan.reason.find("deferred-aniso/tail (image -0.11, temporal +0.057"), std::string::npos) << plan.reason;
  EXPECT_EQ(plan.reason.find("+lean"), std::string::npos) << plan.reason;
}

// deferred-aniso (D0): the G-buffer tensor from the wrapper, then its lighting pass's BRDF per
// light; isotropic GGX materials only.
TEST(Planner, DeferredAnisoShadesWithItsLightingPass) {
  const saagen::Catalogue& catalogue = Catalogue::builtin();
  const saagen::Manifest manifest = parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\n");
  const saagen::ScenePlan plan = saagen::plan_scene(catalogue, manifest);
  EXPECT_EQ(plan.materials.at(0).wrapper, "deferred_aniso_fragment");
  EXPECT_EQ(plan.materials.at(0).brdf, std::optional<std::string>("deferred_aniso_brdf"));
  const std::string text = saagen::format_plan(catalogue, manifest, plan);
  EXPECT_NE(text.find("deferred_aniso_brdf(light_ws, view_ws, normal_ws, tensor, alpha2) per light"), std::string::npos) << text;
  for (const char* keys : {"ndf = \"beckmann\"\n", "anisotropic = true\ntangents = true\n"}) {
    try {
      saagen::plan_scene(catalogue,
                         parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nvariant = \"deferred-aniso\"\n" + keys));
      ADD_FAILURE() << "deferred-aniso accepted with " << keys;
    } catch (const saagen::Error& error) {
      EXPECT_NE(std::string(error.what()).find("deferred-aniso"), std::string::npos) << error.what();
    }
  }
}

TEST(Planner, AnisotropicDeferredMaterialsFilterPerAxis) {
  const saagen::Manifest manifest =
      parse(header +
            "[[material]]\nname = \"m\"\npath = \"deferred\"\nanisotropic = true\ntangents = true\nnormal_maps = true\n"
            "variant = \"deferred-sum\"\n");
  EXPECT_TRUE(saagen::plan_scene(Catalogue::builtin(), manifest).materials.at(0).per_axis);
}

TEST(Planner, ManifestsBuiltInCodeAreCheckedToo) {
  saagen::Manifest manifest;
  manifest.source_name = "engine";
  manifest.targets = {"glsl"};
  saagen::Material material;
  material.name = "x\n#define evil";
  material.path = saagen::RenderPath::deferred;
  manifest.materials.push_back(material);
  EXPECT_THROW((void)saagen::plan_scene(Catalogue::builtin(), manifest), saagen::Error);
  manifest.materials[0].name = "ok";
  manifest.materials[0].variant = "brdf-ggx";
  EXPECT_THROW((void)saagen::plan_scene(Catalogue::builtin(), manifest), saagen::Error);
  manifest.materials[0].variant.reset();
  const saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest);
  EXPECT_EQ(plan.materials.at(0).variant, "deferred-aniso");  // rule D0: GGX, no normal maps, accuracy
  EXPECT_EQ(saagen::emit_scene(Catalogue::builtin(), manifest, plan).at(0).file_name, "saa_scene.glsl");
}

TEST(Planner, TradeTablePicksTheCheapestForSpeedAndTheMostAccurateForAccuracy) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [
      {"target": "glsl", "variant": "deferred-avg", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.05, "ratio_median": 0.9, "error": 0.02},
      {"target": "hlsl", "variant": "deferred-avg", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.07, "error": 0.02},
      {"target": "glsl", "variant": "deferred-sum", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.02, "error": 0.05},
      {"target": "glsl", "variant": "deferred-sum", "isa_family": "navi21", "isa_inverse_throughput_ratio": 2.0},
      {"target": "glsl", "variant": "deferred-projected-space", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.10, "error": 0.01},
      {"target": "glsl", "variant": "forward-axis-projected", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.00, "error": 0.00}]})",
                                                                     "trade.json");
  // Beckmann: saagen's advice for GGX (advice.hpp) would replace a filter that loses to no SAA.
  const saagen::Manifest manifest =
      parse(header + "[[material]]\nname = \"fast\"\npath = \"deferred\"\nprefer = \"speed\"\nndf = \"beckmann\"\n" +
            "[[material]]\nname = \"exact\"\npath = \"deferred\"\nndf = \"beckmann\"\n");
  const saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest, &table);
  EXPECT_EQ(plan.trade_table, "trade.json");
  // forward-axis-projected is cheaper still, but a deferred material cannot use it.
  EXPECT_EQ(plan.materials.at(0).variant, "deferred-sum");
  EXPECT_EQ(plan.materials.at(0).rule, "trade table");
  EXPECT_NE(plan.materials.at(0).reason.find("deferred-sum 1.02, deferred-avg 1.06, deferred-projected-space 1.1"), std::string::npos)
      << plan.materials.at(0).reason;
  EXPECT_EQ(plan.materials.at(1).variant, "deferred-projected-space");
}

// Speed is ranked by the ISA cost model (the committed table for the manifest's gpu_family,
// default vega10), never by lavapipe time: a table with only time ratios does not decide it.
TEST(Planner, SpeedFollowsTheCommittedIsaTableNotLavapipeTime) {
  const saagen::IsaTable& isa = saagen::committed_isa_costs();
  ASSERT_FALSE(isa.rows.empty());
  const saagen::MeasuredTradeTable table =
      saagen::parse_trade_table(R"({"rows": [{"variant": "deferred-projected-space", "ratio_median": 0.5}]})", "time.json");
  for (const std::string family : {"vega10", "navi21"}) {
    const saagen::Manifest manifest =
        parse("name = \"s\"\ntargets = [\"glsl\"]\ngpu_family = \"" + family +
              "\"\n[[material]]\nname = \"m\"\npath = \"deferred\"\nprefer = \"speed\"\nndf = \"beckmann\"\n");
    EXPECT_EQ(manifest.gpu_family, family);
    const saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest, &table);
    // The cheapest eligible variant on this family's ISA figures; the rule's deferred-avg when it
    // is within kIsaTieTolerance of it.
    std::string cheapest = "deferred-avg";
    double lowest = *isa.forward_ratio(family, "deferred-avg", {"glsl"});
    for (const std::string variant : {"deferred-sum", "deferred-projected-space", "deferred-max"}) {
      const double ratio = *isa.forward_ratio(family, variant, {"glsl"});
      if (ratio < lowest) lowest = ratio, cheapest = variant;
    }
    if (*isa.forward_ratio(family, "deferred-avg", {"glsl"}) <= lowest * (1.0 + saagen::kIsaTieTolerance)) cheapest = "deferred-avg";
    EXPECT_EQ(plan.materials.at(0).variant, cheapest) << family << ": " << plan.materials.at(0).reason;
    EXPECT_NE(plan.materials.at(0).variant, "deferred-projected-space") << "lavapipe time decided";
  }
  EXPECT_THROW(
      (void)parse("name = \"s\"\ntargets = [\"glsl\"]\ngpu_family = \"gfx3000\"\n[[material]]\nname = \"m\"\npath = \"deferred\"\n"),
      saagen::Error);
}

// `saagen bench --json` measures a variant's tangent-free form as a configuration of its own;
// for a material without tangents, speed ranks deferred-max by that form's ISA figure.
TEST(Planner, TangentFreeConfigurationsAreKnownIdsAndCostTheirOwnForm) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [
      {"variant": "deferred-max-tangent-free", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.01},
      {"variant": "deferred-max", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.5},
      {"variant": "deferred-avg", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.1}]})",
                                                                     "bench.json");
  const saagen::ScenePlan plan = saagen::plan_scene(
      Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nprefer = \"speed\"\nndf = \"beckmann\"\n"),
      &table);
  EXPECT_EQ(plan.materials.at(0).variant, "deferred-max") << plan.materials.at(0).reason;
  const saagen::MeasuredTradeTable unknown = saagen::parse_trade_table(
      R"({"rows": [{"variant": "deferred-sum-tangent-free", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.0}]})", "u.json");
  EXPECT_THROW(
      (void)saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\n"), &unknown),
      saagen::Error);
}

TEST(Planner, TradeTableWithoutErrorsLeavesAccuracyToTheRules) {
  const saagen::MeasuredTradeTable table =
      saagen::parse_trade_table(R"({"rows": [{"variant": "deferred-sum", "ratio_median": 1.0, "delta_spirv_instructions": 9}]})", "t.json");
  EXPECT_FALSE(table.has_errors());
  const saagen::ScenePlan plan =
      saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\n"), &table);
  EXPECT_EQ(plan.materials.at(0).variant, "deferred-aniso");
  EXPECT_EQ(plan.materials.at(0).rule, "D0");
  EXPECT_NE(plan.materials.at(0).reason.find("t.json has no error"), std::string::npos) << plan.materials.at(0).reason;
}

// With per-content rows, a normal-mapped material gets the feed and prefilter of the lowest-error
// configuration on normal-mapped content; an accuracy material may change variant for it, a
// material whose variant the manifest names keeps it and gets that variant's best handling.
TEST(Planner, NormalMappedMaterialsFollowTheMeasuredContentRows) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [], "by_content": [
      {"content": "curved", "configuration": "deferred-sum", "error": 0.01},
      {"content": "normal-mapped", "configuration": "deferred-avg", "error": 0.14},
      {"content": "normal-mapped", "configuration": "deferred-avg:geometric+toksvig", "error": 0.12},
      {"content": "normal-mapped", "configuration": "deferred-sum:geometric", "error": 0.11},
      {"content": "normal-mapped", "configuration": "engine-godot", "error": 0.01}]})",
                                                                     "trade.json");
  const saagen::Manifest manifest =
      parse(header + "[[material]]\nname = \"a\"\npath = \"deferred\"\nnormal_maps = true\n" +
            "[[material]]\nname = \"b\"\npath = \"deferred\"\nnormal_maps = true\nvariant = \"deferred-avg\"\n" +
            "[[material]]\nname = \"c\"\npath = \"deferred\"\n");
  const saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest, &table);
  EXPECT_EQ(plan.materials.at(0).variant, "deferred-sum");
  EXPECT_EQ(plan.materials.at(0).feed, "geometric");
  EXPECT_EQ(plan.materials.at(0).prefilter, "none");
  EXPECT_NE(plan.materials.at(0).normal_advice.find("deferred-sum:geometric 0.11"), std::string::npos)
      << plan.materials.at(0).normal_advice;
  EXPECT_EQ(plan.materials.at(1).variant, "deferred-avg");
  EXPECT_EQ(plan.materials.at(1).feed, "geometric");
  EXPECT_EQ(plan.materials.at(1).prefilter, "toksvig");
  EXPECT_TRUE(plan.materials.at(2).normal_advice.empty());  // no normal map, nothing to advise
  EXPECT_NE(saagen::format_plan(Catalogue::builtin(), manifest, plan).find("  normal    deferred-sum:geometric"), std::string::npos);
}

// The normal handling of a material that names its variant, with a trade table, is saagen's one
// decision among that variant's measured configurations: an engine's bake is recommended only where the decision takes it
// (it beats no SAA beyond its interval, the largest video gain), with the command that writes it
// and the decision's pick without a prefilter; a lower mean inside its interval is no win. A
// table without no SAA's row can only rank means, and the plan says so.
TEST(Planner, AnEngineBakeIsRecommendedOnlyWhereTheDecisionTakesIt) {
  const auto plan_with = [](const std::string& rows) {
    const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [], "by_content": [)" + rows + "]}", "t.json");
    return saagen::plan_scene(
               Catalogue::builtin(),
               parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nnormal_maps = true\nvariant = \"deferred-avg\"\n"), &table)
        .materials.at(0);
  };
  // A row against no SAA: image and video differences with their 95 % intervals.
  const auto row = [](const std::string& configuration, const std::string& image, const std::string& video) {
    return fmt::format(R"({{"content": "normal-mapped", "configuration": "{}", "error": 0.05,
        "against_none": {{"image": {}, "temporal": {}}}}})",
                       configuration, image, video);
  };
  const std::string none = R"({"content": "normal-mapped", "configuration": "none", "error": 0.05})";
  const std::string better = R"({"mean": -0.01, "low": -0.02, "high": -0.005})", tied = R"({"mean": -0.01, "low": -0.03, "high": 0.01})";
  const std::string much_better = R"({"mean": -2, "low": -3, "high": -1})", worse = R"({"mean": 0.01, "low": 0.005, "high": 0.02})";
  const auto wins =
      plan_with(none + "," + row("deferred-avg", better, better) + "," + row("deferred-avg:geometric+hdrp", better, much_better));
  EXPECT_EQ(wins.prefilter, "hdrp");
  EXPECT_NE(wins.normal_advice.find("saagen texture prefilter NORMAL_MAP -o OUT.ktx2 --method hdrp --roughness R --gltf"),
            std::string::npos)
      << wins.normal_advice;
  EXPECT_NE(wins.normal_advice.find("without a prefilter the best is deferred-avg (image error -0.01 [-0.02, -0.005]"), std::string::npos)
      << wins.normal_advice;
  // The bake's larger mean gain lies inside its interval (tied image error): not taken.
  const auto tie =
      plan_with(none + "," + row("deferred-avg", better, better) + "," + row("deferred-avg:geometric+filament-vmf", tied, tied));
  EXPECT_EQ(tie.prefilter, "none");
  EXPECT_NE(tie.normal_advice.find("no texture prefilter: the best prefiltered configuration is none (no prefiltered configuration beats "
                                   "no SAA)"),
            std::string::npos)
      << tie.normal_advice;
  // Nothing beats no SAA: no bake, and the plan says why.
  const auto nothing = plan_with(none + "," + row("deferred-avg", worse, better) + "," + row("deferred-avg:geometric+hdrp", tied, tied));
  EXPECT_EQ(nothing.prefilter, "none");
  EXPECT_EQ(nothing.normal_advice.rfind("no texture prefilter; on normal-mapped content in t.json no filter", 0), 0u)
      << nothing.normal_advice;
  // Means only (no row for no SAA): the lowest mean, said to be one.
  const auto means = plan_with(R"({"content": "normal-mapped", "configuration": "deferred-avg", "error": 0.05},
      {"content": "normal-mapped", "configuration": "deferred-avg:geometric+hdrp", "error": 0.04})");
  EXPECT_EQ(means.prefilter, "hdrp");
  EXPECT_NE(means.normal_advice.find("means without intervals: deferred-avg 0.05, deferred-avg:geometric+hdrp 0.04"), std::string::npos)
      << means.normal_advice;
}

// Without a trade table a normal-mapped GGX material gets saagen's advice: the measured
// configuration with the normal it was measured with, and, where it names its variant, the same
// decision among that variant's feeds and bakes, with its measured figures.
TEST(Planner, WithoutATradeTableNormalMapsGetTheMeasuredAdvice) {
  const std::string material = "[[material]]\nname = \"m\"\npath = \"deferred\"\nnormal_maps = true\n";
  // deferred-avg/tail on the normal-mapped normal (TableFreeAdviceFollowsTheMeasuredContent).
  const saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), parse(header + material));
  EXPECT_EQ(
      plan.materials.at(0).normal_advice.rfind("feed the shading normal; no texture prefilter; measured: deferred-avg/tail (image -", 0),
      0u)
      << plan.materials.at(0).normal_advice;
  // Named deferred-avg: the same configuration, decided among deferred-avg's own rows (its hdrp bake
  // loses on ClearCoatTest and pmndrs-0014).
  const saagen::ScenePlan named = saagen::plan_scene(Catalogue::builtin(), parse(header + material + "variant = \"deferred-avg\"\n"));
  EXPECT_EQ(named.materials.at(0).normal_advice.rfind("deferred-avg/tail (image -", 0), 0u) << named.materials.at(0).normal_advice;
  EXPECT_NE(named.materials.at(0).normal_advice.find("deferred-avg:geometric+hdrp/tail (loses on ClearCoatTest, pmndrs-0014)"),
            std::string::npos)
      << named.materials.at(0).normal_advice;
}

TEST(Planner, BadTradeTablesAreRejected) {
  const auto error_of_table = [](const std::string& text) -> std::string {
    try {
      (void)saagen::parse_trade_table(text, "t.json");
    } catch (const saagen::Error& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_EQ(error_of_table("{"), "t.json: not valid JSON (byte 2); pass the file `bench_shading --json` writes");
  EXPECT_EQ(error_of_table("[]"), "t.json: no \"rows\" array; pass the file `bench_shading --json` writes");
  EXPECT_NE(
      error_of_table(R"({"rows": [{"variant": "x", "ratio_median": "fast"}]})").find("t.json: rows[0]: \"ratio_median\" must be a number"),
      std::string::npos);
  EXPECT_EQ(error_of_table(R"({"rows": [], "by_content": [{"content": "curved", "error": 1}]})"),
            "t.json: by_content[0]: needs a string \"configuration\"");
  EXPECT_EQ(error_of_table(R"({"rows": [], "by_content": [{"content": "curved", "configuration": "none"}]})"),
            "t.json: by_content[0]: needs a number \"error\"");
  EXPECT_EQ(
      error_of_table(R"({"rows": [], "by_content": [{"content": "curved", "configuration": "none", "error": 1, "loses_on": "torus"}]})"),
      "t.json: by_content[0]: \"loses_on\" must be an array of scene names");
  EXPECT_EQ(
      error_of_table(R"({"rows": [], "taa_by_content": [{"content": "curved", "configuration": "none", "error": 1, "loses_on": [3]}]})"),
      "t.json: taa_by_content[0]: \"loses_on\" must be an array of scene names");
}

// A table's content row that beats no SAA on the content's mean but loses on one of its scenes
// ("loses_on", as `saagen bench --json` writes it) is never the plan; the next one is.
TEST(Planner, WithATableARowThatLosesOnASceneIsNotPlanned) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [], "by_content": [
      {"content": "curved", "configuration": "none", "error": 0.03, "tde": 0.010},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.02, "tde": 0.008, "loses_on": ["tubes"]},
      {"content": "curved", "configuration": "deferred-avg/tail", "error": 0.025, "tde": 0.009}]})",
                                                                     "t.json");
  const saagen::ScenePlan plan =
      saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"a\"\npath = \"deferred\"\n"), &table);
  EXPECT_EQ(plan.materials.at(0).variant, "deferred-avg") << plan.materials.at(0).reason;
  EXPECT_NE(plan.materials.at(0).reason.find("deferred-aniso/tail (loses on tubes)"), std::string::npos) << plan.materials.at(0).reason;
}

TEST(Planner, WithATableATieOfTheMostAccurateGoesToTheCheaper) {
  // deferred-aniso/tail improves TDE most on the mean, deferred-avg/tail ties with it (worse
  // beyond the interval in neither metric, "not_worse_than") and costs less in the committed ISA
  // table: deferred-avg is planned. Without the pairing the mean decides.
  const std::string rows = R"({"content": "curved", "configuration": "none", "error": 0.03, "tde": 0.010},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.02, "tde": 0.008},)";
  const auto plan_with = [&](const std::string& avg) {
    const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [], "by_content": [)" + rows + avg + "]}", "t.json");
    return saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"a\"\npath = \"deferred\"\n"), &table)
        .materials.at(0);
  };
  const saagen::MaterialPlan tied = plan_with(
      R"({"content": "curved", "configuration": "deferred-avg/tail", "error": 0.021, "tde": 0.0085, "not_worse_than": ["deferred-aniso/tail"]})");
  EXPECT_EQ(tied.variant, "deferred-avg") << tied.reason;
  EXPECT_NE(tied.reason.find("it ties with deferred-aniso/tail"), std::string::npos) << tied.reason;
  EXPECT_EQ(plan_with(R"({"content": "curved", "configuration": "deferred-avg/tail", "error": 0.021, "tde": 0.0085})").variant,
            "deferred-aniso");
}

TEST(Planner, ATableOfOtherContentLeavesTheMaterialToSaagensOwnFigures) {
  // A table measured on a curved asset only: its error means (curved) say nothing about a
  // normal-mapped material, which gets saagen's committed normal-mapped decision (the plan without
  // a table), and the reason says the table has no such rows. The curved material decides on it.
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [
      {"target": "glsl", "variant": "deferred-aniso", "error": 0.01}, {"target": "glsl", "variant": "forward-axis-projected", "error": 0.05}],
      "by_content": [
      {"content": "curved", "configuration": "none", "error": 0.03, "tde": 0.010},
      {"content": "curved", "configuration": "deferred-avg/tail", "error": 0.02, "tde": 0.008}]})",
                                                                     "curved.json");
  const std::string materials =
      "[[material]]\nname = \"m\"\npath = \"forward\"\ntangents = true\nnormal_maps = true\n"
      "[[material]]\nname = \"c\"\npath = \"deferred\"\n";
  const saagen::ScenePlan with_table = saagen::plan_scene(Catalogue::builtin(), parse(header + materials), &table);
  const saagen::ScenePlan without = saagen::plan_scene(Catalogue::builtin(), parse(header + materials));
  EXPECT_EQ(with_table.materials.at(0).variant, without.materials.at(0).variant) << with_table.materials.at(0).reason;
  EXPECT_EQ(with_table.materials.at(0).rule, "advice");
  EXPECT_NE(with_table.materials.at(0).reason.find("curved.json has no normal-mapped rows"), std::string::npos)
      << with_table.materials.at(0).reason;
  // The table's curved error means rank nothing for it: no clause of the reason comes from them.
  EXPECT_EQ(with_table.materials.at(0).reason.find("(trade table)"), std::string::npos) << with_table.materials.at(0).reason;
  EXPECT_EQ(with_table.materials.at(1).variant, "deferred-avg") << with_table.materials.at(1).reason;
  EXPECT_EQ(with_table.materials.at(1).rule, "trade table");
}

TEST(Planner, CostsAreMeasuredInOptimizedSpirv) {
  const saagen::Manifest manifest = saagen::load_manifest(example_manifest, Catalogue::builtin());
  saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest);
  saagen::measure_costs(Catalogue::builtin(), manifest, plan);
  for (const saagen::MaterialPlan& material : plan.materials) {
    if (material.variant == "none") {
      EXPECT_TRUE(material.cost.empty()) << material.material;  // no filter: nothing to cost
      continue;
    }
    for (const saagen::OutputTarget& target : manifest.targets) {
      ASSERT_TRUE(material.cost.count(target)) << material.material;
      EXPECT_GT(material.cost.at(target), 0) << material.material << " " << target.name();
    }
  }
  EXPECT_EQ(plan.materials.at(0).variant, "forward-axis-projected");  // car_paint: normal-mapped, saagen's decision
  const std::string text = saagen::format_plan(Catalogue::builtin(), manifest, plan);
  EXPECT_NE(text.find("material car_paint"), std::string::npos);
  EXPECT_NE(text.find("variant   forward-axis-projected  [advice]"), std::string::npos) << text;
  EXPECT_NE(text.find("variant   none  [advice]"), std::string::npos) << text;  // foliage: curved, deferred, speed
  EXPECT_NE(text.find("variant   forward-axis-projected  [F2]"), std::string::npos) << text;
  EXPECT_NE(text.find("optimized SPIR-V instructions"), std::string::npos);
  // The same filter plus the tail-preserving filtered GGX costs more than with the engine's own BRDF.
  const std::string same_filter =
      "[[material]]\npath = \"forward\"\nanisotropic = true\ntangents = true\nvariant = \"forward-axis-projected\"\n";
  const saagen::Manifest pair = parse(header + same_filter + "name = \"g\"\n" + same_filter + "name = \"b\"\nndf = \"beckmann\"\n");
  saagen::ScenePlan pair_plan = saagen::plan_scene(Catalogue::builtin(), pair);
  saagen::measure_costs(Catalogue::builtin(), pair, pair_plan);
  EXPECT_GT(pair_plan.materials.at(0).cost.at("glsl"), pair_plan.materials.at(1).cost.at("glsl"));
}

// ---------------------------------------------------------------------------------------------
// Minimal emission

TEST(Bundle, HoldsExactlyTheClosureOfTheMaterialsFunctions) {
  const saagen::Manifest manifest = saagen::load_manifest(example_manifest, Catalogue::builtin());
  const saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest);
  const auto files = saagen::emit_scene(Catalogue::builtin(), manifest, plan);
  // glsl + hlsl, fp32 only: the fp16 material, foliage, prefers speed and is planned no filter (on
  // curved content only deferred-aniso beats no SAA in the deferred path, its most expensive form).
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].file_name, "saa_scene.glsl");
  EXPECT_EQ(files[1].file_name, "saa_scene.hlsl");

  for (const saagen::EmittedFile& file : files) {
    const bool half = saagen::is_half(file.marker.precision);
    std::vector<std::string> roots;
    for (const saagen::MaterialPlan& material : plan.materials) {
      if (saagen::is_half(material.precision) != half) continue;
      for (const std::string& name : material.functions) {
        if (std::find(roots.begin(), roots.end(), name) == roots.end()) roots.push_back(name);
      }
    }
    EXPECT_EQ(file.marker.functions, roots) << file.file_name;
    // Catalogue functions only: a precision's target support (e.g. fp16 derivative helpers in
    // the target table's preamble) is not part of the catalogue's closure.
    std::set<std::string> defined;
    for (const std::string& name : defined_functions(file.content, "saa_")) {
      if (Catalogue::builtin().find_function(name)) defined.insert(name);
    }
    EXPECT_EQ(defined, closure_names(roots)) << file.file_name;
    // Nothing else of the catalogue appears, not even in a comment.
    for (const saagen::Function& function : Catalogue::builtin().functions()) {
      if (defined.count(function.name)) continue;
      EXPECT_FALSE(std::regex_search(file.content, std::regex("\\bsaa_" + function.name + "\\b")))
          << file.file_name << ": " << function.name;
    }
  }
  // The fp32 GLSL bundle: brushed_metal and terrain; not car_paint's nor foliage's filters
  // (advised no filter: nothing in the bundle).
  const std::set<std::string> defined = defined_functions(files[0].content, "saa_");
  EXPECT_TRUE(defined.count("forward_axis_projected_fragment"));    // brushed_metal
  EXPECT_TRUE(defined.count("forward_axis_projected"));             // the wrapper pulls its core
  EXPECT_FALSE(defined.count("forward_aniso_projected_fragment"));  // car_paint: no filter
  EXPECT_FALSE(defined.count("deferred_aniso_fragment"));
  EXPECT_TRUE(defined.count("deferred_sum_fragment"));
  EXPECT_TRUE(defined.count("ggx_brdf_filtered_axis"));  // GGX pulls the tail-preserving filtered GGX
  EXPECT_FALSE(defined.count("beckmann_brdf_matrix"));   // brushed_metal (Beckmann) prefers speed: axis filter, own BRDF
  EXPECT_FALSE(defined.count("deferred_aniso"));
  EXPECT_FALSE(defined.count("ggx_brdf_axis"));
}

TEST(Bundle, RemovingAMaterialRemovesItsCode) {
  const std::string full = read_text(example_manifest);
  // Without terrain (the only deferred-sum material).
  const auto start = full.find("[[material]]\nname = \"terrain\"");
  ASSERT_NE(start, std::string::npos);
  const auto end = full.find("[[material]]", start + 1);
  const std::string reduced = full.substr(0, start) + full.substr(end);

  const auto before = emit_text(full);
  const auto after = emit_text(reduced);
  ASSERT_EQ(before.size(), after.size());
  const std::set<std::string> had = defined_functions(before[0].content, "saa_");
  const std::set<std::string> has = defined_functions(after[0].content, "saa_");
  std::set<std::string> removed;
  for (const std::string& name : had) {
    if (!has.count(name)) removed.insert(name);
  }
  EXPECT_TRUE(removed.count("deferred_sum_fragment"));
  EXPECT_TRUE(removed.count("deferred_sum"));
  for (const std::string& name : has) EXPECT_TRUE(had.count(name)) << name;
  EXPECT_EQ(has, closure_names(after[0].marker.functions));
  EXPECT_EQ(after[0].content.find("saa_deferred_sum"), std::string::npos);
  EXPECT_EQ(after[0].content.find("terrain"), std::string::npos);
  // The other target's bundle loses it too.
  EXPECT_EQ(after[1].content.find("terrain"), std::string::npos);
  EXPECT_NE(before[1].content.find("terrain"), std::string::npos);
}

TEST(Bundle, IsDeterministicAndValidatesInProcess) {
  const std::string text = read_text(example_manifest);
  const auto first = emit_text(text);
  const auto second = emit_text(text);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t index = 0; index < first.size(); ++index) {
    EXPECT_EQ(first[index].content, second[index].content);
    const saagen::FileValidation validation = saagen::validate_file(Catalogue::builtin(), first[index].file_name, first[index].content);
    EXPECT_TRUE(validation.ok()) << validation.summary();
  }
}

// An all-GGX scene that does not set sigma2 gets the kernel measured best with the
// tail-preserving filtered GGX it is shaded with (the pixel filter's own 0.25, said with its
// reason); a scene with a Beckmann material, or one that sets sigma2, keeps what it says.
TEST(Planner, AllGgxScenesGetTheGgxFittedKernel) {
  const auto ggx = emit_text(header + forward_material);
  EXPECT_EQ(saagen::find_marker(ggx.at(0).content)->option_values.at("sigma2"), saagen::kGgxSigma2);
  EXPECT_EQ(saagen::kGgxSigma2, 0.25);
  const saagen::Manifest manifest = parse(header + forward_material);
  EXPECT_NE(saagen::format_plan(Catalogue::builtin(), manifest, saagen::plan_scene(Catalogue::builtin(), manifest))
                .find("options: sigma2 = 0.25 (every material is GGX, shaded with the tail-preserving filtered GGX"),
            std::string::npos);
  const auto mixed = emit_text(header + forward_material + "[[material]]\nname = \"b\"\npath = \"deferred\"\nndf = \"beckmann\"\n");
  EXPECT_EQ(saagen::find_marker(mixed.at(0).content)->option_values.at("sigma2"), 0.25);
  const auto set = emit_text(header + "sigma2 = 0.2\n" + forward_material);
  EXPECT_EQ(saagen::find_marker(set.at(0).content)->option_values.at("sigma2"), 0.2);
}

TEST(Bundle, MarkerRecordsThePublicFunctions) {
  const auto files = emit_text(header + "prefix = \"eng_\"\nsigma2 = 0.5\n" + forward_material);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].file_name, "eng_scene.glsl");
  const auto marker = saagen::find_marker(files[0].content);
  ASSERT_TRUE(marker);
  EXPECT_EQ(marker->target, saagen::OutputTarget::snippet("glsl"));
  EXPECT_EQ(marker->prefix, "eng_");
  // A forward GGX material without tangents on curved content: deferred-aniso (saagen/advice.hpp).
  EXPECT_EQ(marker->variants, (std::vector<std::string>{"deferred-aniso"}));
  EXPECT_EQ(marker->functions,
            (std::vector<std::string>{"deferred_aniso", "deferred_aniso_fragment", "deferred_aniso_roughness", "deferred_aniso_brdf"}));
  EXPECT_EQ(marker->option_values.at("sigma2"), 0.5);
  EXPECT_NE(files[0].content.find("#ifndef ENG_BUNDLE_SCENE_GLSL"), std::string::npos);
  EXPECT_NE(files[0].content.find("#ifndef ENG_CORE_ONLY"), std::string::npos);
  EXPECT_NE(files[0].content.find("const float eng_SIGMA2 = 0.5;"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// One advice (saagen/advice.hpp): the planner, emit's defaults, the emitted headers, the examples
// and examples/INTEGRATION.md say the same thing, so that they cannot drift apart again.

const saagen::MaterialPlan& planned(const saagen::ScenePlan& plan, const std::string& material) {
  for (const saagen::MaterialPlan& entry : plan.materials)
    if (entry.material == material) return entry;
  throw std::runtime_error("no material " + material);
}

TEST(Advice, EmitDefaultsAndHeadersAreTheAdvice) {
  const auto defaults = saagen::resolve_options(Catalogue::builtin(), {});
  EXPECT_EQ(defaults.at("sigma2"), saagen::advice::kSigma2);
  EXPECT_EQ(defaults.at("kappa"), saagen::advice::kKappa);
  EXPECT_EQ(saagen::kGgxSigma2, saagen::advice::kSigma2);
  EXPECT_EQ(saagen::kTaaSigma2, saagen::advice::kTaaSigma2);
  for (const std::string target : {"glsl", "gles", "hlsl", "wgsl"}) {
    saagen::EmitOptions options;
    options.target = target;
    options.variants = {"deferred-sum", "forward-axis-projected"};
    for (const saagen::EmittedFile& file : saagen::emit_variants(Catalogue::builtin(), options)) {
      EXPECT_NE(file.content.find(std::string(saagen::advice::kNormalText)), std::string::npos) << file.file_name;
      EXPECT_EQ(file.content.find("{advice:"), std::string::npos) << file.file_name;
    }
    // The prefilter snippets' headers say how to sample the map and its bake: the LOD bias.
    options.variants = {"prefilter-toksvig", "prefilter-lean"};
    const auto prefilter_files = saagen::emit_variants(Catalogue::builtin(), options);
    ASSERT_FALSE(prefilter_files.empty()) << target;
    for (const saagen::EmittedFile& file : prefilter_files) {
      EXPECT_NE(file.content.find(std::string(saagen::advice::kPrefilterSamplingText)), std::string::npos) << file.file_name;
      EXPECT_EQ(file.content.find("{advice:"), std::string::npos) << file.file_name;
    }
  }
  // The text quotes the constant: the bias argument of each language's sample.
  const std::string bias = std::to_string(saagen::advice::kPrefilterLodBias) + ".0";
  for (const std::string call : {"texture(map, uv, ", "SampleBias(s, uv, ", "textureSampleBias(map, s, uv, "}) {
    EXPECT_NE(std::string(saagen::advice::kPrefilterSamplingText).find(call + bias + ")"), std::string::npos) << call;
  }
}

TEST(Advice, ExamplesAndDocsAgreeWithThePlanner) {
  const fs::path root(SAAGEN_SOURCE_DIR);
  // The reference manifest's normal-mapped materials: car_paint follows the advice for
  // normal-mapped content; terrain names its filter and gets saagen's decision among its feeds and
  // bakes (the geometric normal, no bake), the three.js module's default.
  const saagen::Manifest example = saagen::load_manifest(example_manifest, Catalogue::builtin());
  const saagen::ScenePlan example_plan = saagen::plan_scene(Catalogue::builtin(), example);
  const bool normal_mapped_wins = planned(saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = "
                                                                                                  "\"deferred\"\nnormal_maps = true\n")),
                                          "m")
                                      .variant != "none";
  EXPECT_EQ(planned(example_plan, "car_paint").variant == "none", !normal_mapped_wins);
  const saagen::MaterialPlan& terrain = planned(example_plan, "terrain");
  EXPECT_EQ(terrain.rule, "manifest");
  EXPECT_EQ(terrain.variant, "deferred-sum");
  EXPECT_EQ(terrain.feed, "geometric");
  EXPECT_EQ(terrain.prefilter, "none");
  // A planned bake comes with the LOD bias its trade rows were measured with; no bake, no bias.
  EXPECT_EQ(terrain.normal_advice.find(std::string(saagen::advice::kPrefilterSamplingText)) != std::string::npos,
            terrain.prefilter != "none")
      << terrain.normal_advice;
  const std::string module = read_text(root / "examples" / "threejs" / "saagen-three.js");
  std::smatch defaults;
  ASSERT_TRUE(std::regex_search(module, defaults, std::regex("wrapper = '(\\w+)', normal = '(\\w+)'"))) << "installSaagen's defaults";
  EXPECT_EQ(defaults[1].str(), terrain.wrapper);
  EXPECT_EQ(defaults[2].str(), terrain.feed);
  std::smatch bias;
  ASSERT_TRUE(std::regex_search(module, bias, std::regex("PREFILTER_LOD_BIAS = (\\d+);"))) << "the module's LOD bias";
  EXPECT_EQ(std::stoi(bias[1].str()), saagen::advice::kPrefilterLodBias);
  const std::string page = read_text(root / "examples" / "threejs" / "index.html");
  // The page installs what its manifest's plan says per material (installPlan); what it claims
  // of the normal-mapped material is that plan.
  const saagen::Manifest three = saagen::load_manifest(root / "examples" / "threejs" / "scene.saagen.toml", Catalogue::builtin());
  const saagen::ScenePlan three_plan = saagen::plan_scene(Catalogue::builtin(), three);
  EXPECT_EQ(planned(three_plan, "bumpy").variant == "none", !normal_mapped_wins);
  // The page and the module claim no plan of their own: they point at `saagen plan --advice`.
  for (const std::string* text : {&page, &module}) {
    EXPECT_EQ(text->find("advice for normal-mapped content is no"), std::string::npos);
    EXPECT_NE(text->find("saagen plan --advice"), std::string::npos);
  }
  EXPECT_NE(page.find("saagen plan examples/threejs/scene.saagen.toml --json > examples/threejs/generated/plan.json"), std::string::npos);
  EXPECT_NE(page.find("saagen emit --manifest examples/threejs/scene.saagen.toml -o examples/threejs/generated"), std::string::npos);
  EXPECT_NE(page.find("planEntry("), std::string::npos);
  EXPECT_EQ(page.find("--sigma2"), std::string::npos);  // emit's default: the advice's sigma^2
  EXPECT_EQ(page.find("--kappa"), std::string::npos);

  // The WebGPU example calls what its manifest plans.
  const fs::path webgpu = root / "examples" / "webgpu";
  const saagen::Manifest beads = saagen::load_manifest(webgpu / "scene.saagen.toml", Catalogue::builtin());
  const saagen::ScenePlan beads_plan = saagen::plan_scene(Catalogue::builtin(), beads);
  const saagen::MaterialPlan& glossy = planned(beads_plan, "glossy_beads");
  EXPECT_EQ(glossy.rule, "manifest");  // named: the example shows the call whatever the advice
  EXPECT_EQ(glossy.variant, "forward-aniso-projected");
  const std::string render = read_text(webgpu / "render.mjs");
  EXPECT_NE(render.find("saa_" + glossy.wrapper + "("), std::string::npos) << glossy.wrapper;
  ASSERT_TRUE(glossy.brdf);
  EXPECT_NE(render.find("saa_" + *glossy.brdf + "("), std::string::npos) << *glossy.brdf;

  // The CMake consumer's shaders call what its manifest plans.
  const fs::path consumer = root / "examples" / "cmake-consumer";
  const saagen::Manifest consumer_manifest = saagen::load_manifest(consumer / "scene.saagen.toml", Catalogue::builtin());
  std::string shaders;
  for (const char* name : {"forward_lit.frag", "gbuffer.frag", "deferred_light.frag"}) shaders += read_text(consumer / "shaders" / name);
  // Its normal-mapped materials' shaders sample the map with the advised LOD bias.
  const std::string biased_read = "texture(normal_map, in_uv, " + std::to_string(saagen::advice::kPrefilterLodBias) + ".0)";
  EXPECT_EQ(std::regex_search(shaders, std::regex("texture\\(normal_map, in_uv\\)")), false) << "a normal map read without the bias";
  EXPECT_NE(shaders.find(biased_read), std::string::npos) << biased_read;
  for (const saagen::MaterialPlan& material : saagen::plan_scene(Catalogue::builtin(), consumer_manifest).materials) {
    EXPECT_NE(shaders.find("saa_" + material.wrapper + "("), std::string::npos) << material.material;
    if (material.brdf) {
      EXPECT_NE(shaders.find("saa_" + *material.brdf + "("), std::string::npos) << material.material;
    }
  }

  // INTEGRATION.md lists every target (its advice table: IntegrationGuideHoldsTheAdviceTable).
  const std::string integration = read_text(root / "examples" / "INTEGRATION.md");
  // INTEGRATION.md, the user guide and docs/PREFILTER.md give the same bias argument.
  const std::string bias_argument = "texture(map, uv, " + std::to_string(saagen::advice::kPrefilterLodBias) + ".0)";
  for (const char* doc : {"examples/INTEGRATION.md", "docs/GUIDE.md", "docs/PREFILTER.md"}) {
    EXPECT_NE(read_text(root / doc).find(bias_argument), std::string::npos) << doc << ": " << bias_argument;
  }
  const auto targets_row = integration.find("| `targets` |");
  ASSERT_NE(targets_row, std::string::npos);
  const std::string row = integration.substr(targets_row, integration.find('\n', targets_row) - targets_row);
  for (const char* target : {"glsl", "gles", "hlsl", "wgsl", "spirv"}) EXPECT_NE(row.find(target), std::string::npos) << target;
}

// ---------------------------------------------------------------------------------------------
// CLI

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

class SceneCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    scratch_ = fs::temp_directory_path() / (std::string("saagen-manifest-") + info->name() + "-" + std::to_string(::getpid()));
    fs::remove_all(scratch_);
    fs::create_directories(scratch_);
  }
  void TearDown() override { fs::remove_all(scratch_); }

  CliRun saagen(const std::string& arguments) const {
    const fs::path out = scratch_ / "stdout.txt";
    const fs::path err = scratch_ / "stderr.txt";
    const std::string command = std::string("'") + SAAGEN_CLI_PATH + "' " + arguments + " >'" + out.string() + "' 2>'" + err.string() + "'";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(out), read_text(err)};
  }

  void write(const fs::path& path, const std::string& text) const {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
  }

  fs::path scratch_;
};

TEST_F(SceneCli, PlanPrintsVariantWhyCallAndCost) {
  const CliRun run = saagen("plan '" + example_manifest.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("material terrain"), std::string::npos);
  EXPECT_NE(run.out.find("variant   deferred-sum  [manifest]"), std::string::npos) << run.out;  // terrain names it
  EXPECT_NE(run.out.find("variant   none  [advice]"), std::string::npos) << run.out;            // foliage
  EXPECT_NE(run.out.find("why       saagen's decision on normal-mapped content in saagen's trade"), std::string::npos)
      << run.out;  // car_paint
  EXPECT_NE(run.out.find("  measure   this advice"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("why       "), std::string::npos);
  EXPECT_NE(run.out.find("cost      glsl +"), std::string::npos) << run.out;
}

TEST_F(SceneCli, BadManifestIsOneLineWithPosition) {
  write(scratch_ / "bad.toml", header + forward_material + "ndf = \"phong\"\n");
  const CliRun run = saagen("plan '" + (scratch_ / "bad.toml").string() + "' --no-cost");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("bad.toml:5:7: key 'ndf' of material 'm': unknown value \"phong\"; allowed: \"ggx\", \"beckmann\""),
            std::string::npos)
      << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
}

TEST_F(SceneCli, EmitWritesOnlyWhenBytesChangeAndRefusesForeignFiles) {
  const fs::path out = scratch_ / "out";
  const std::string manifest = "--manifest '" + example_manifest.string() + "' -o '" + out.string() + "'";
  CliRun run = saagen("emit " + manifest);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("wrote     " + (out / "saa_scene.glsl").string()), std::string::npos) << run.out;
  run = saagen("emit " + manifest);
  EXPECT_NE(run.out.find("unchanged " + (out / "saa_scene.glsl").string()), std::string::npos) << run.out;
  run = saagen("validate '" + out.string() + "'");
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("2 file(s) validated, 0 failed"), std::string::npos) << run.out;

  run = saagen("emit " + manifest + " --list-outputs");
  EXPECT_EQ(run.out, (out / "saa_scene.glsl").string() + "\n" + (out / "saa_scene.hlsl").string() + "\n");

  write(out / "saa_scene.hlsl", "// my own file\n");
  run = saagen("emit " + manifest);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("exists and was not written by saagen; refusing to overwrite it (use --force)"), std::string::npos) << run.err;
  EXPECT_EQ(read_text(out / "saa_scene.hlsl"), "// my own file\n");
  run = saagen("emit " + manifest + " --force");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(saagen::find_marker(read_text(out / "saa_scene.hlsl")));
}

// A manifest whose every material is advised no filter writes nothing and says so.
TEST_F(SceneCli, EmitOfOnlyNoFilterMaterialsWritesNothing) {
  const fs::path manifest = scratch_ / "taa.toml";
  write(manifest, header + "taa = true\n[[material]]\nname = \"m\"\npath = \"deferred\"\nnormal_maps = true\n");
  const CliRun run = saagen("emit --manifest '" + manifest.string() + "' -o '" + (scratch_ / "out").string() + "'");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("nothing to write: every material of"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(scratch_ / "out"));
}

TEST_F(SceneCli, ManifestExcludesPerVariantOptions) {
  const CliRun run = saagen("emit --manifest '" + example_manifest.string() + "' --target hlsl -o '" + (scratch_ / "out").string() + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--target excludes --manifest"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(scratch_ / "out"));
}

TEST_F(SceneCli, CompileResolvesIncludesOfTheBundle) {
  const fs::path out = scratch_ / "gen";
  ASSERT_EQ(saagen("emit --manifest '" + example_manifest.string() + "' -o '" + out.string() + "'").exit_code, 0);
  write(scratch_ / "shaders" / "lit.frag",
        "#version 450\n"
        "#include \"saa_scene.glsl\"\n"
        "layout(location = 0) in vec3 normal_ws;\n"
        "layout(location = 0) out vec4 color;\n"
        "void main() { color = vec4(saa_deferred_sum_fragment(0.04, normalize(normal_ws))); }\n");
  CliRun run = saagen("compile '" + (scratch_ / "shaders" / "lit.frag").string() + "' -I '" + out.string() + "' -o '" +
                      (scratch_ / "lit.spv").string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_GT(fs::file_size(scratch_ / "lit.spv"), 100u);
  EXPECT_EQ(read_text(scratch_ / "lit.spv").substr(0, 4), std::string("\x03\x02\x23\x07", 4));  // SPIR-V magic

  // An error names the file and the line after the include.
  write(scratch_ / "shaders" / "bad.frag", "#version 450\n#include \"saa_scene.glsl\"\nvoid main() { undefined_call(); }\n");
  run = saagen("compile '" + (scratch_ / "shaders" / "bad.frag").string() + "' -I '" + out.string() + "' -o '" +
               (scratch_ / "bad.spv").string() + "'");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("bad.frag:3"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(scratch_ / "bad.spv"));
}

}  // namespace

namespace {

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
  EXPECT_NE(printed.find("call      saa_forward_aniso_projected_fragment(alpha2, half_ts)"), std::string::npos) << printed;
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

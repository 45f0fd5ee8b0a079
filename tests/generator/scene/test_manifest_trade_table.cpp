// Scene manifests (test_manifest): the planner with a trade table -- no filter where nothing beats
// no SAA, speed and accuracy on the material's content, normal-map handling and engine bakes, bad
// tables, and the ISA costs it ranks speed by.
#include "manifest_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace {

using saagen::Catalogue;
using namespace saagen::test::manifest;

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
// pass with the texture covariance (the tail-preserving lobe of A = diag(alpha^2) + K + C, as the
// trade's deferred-aniso:FEED+PREFILTER/tail rows shade): with LEAN the geometry pass's
// deferred_aniso_covariance too, with a scalar bake the covariance (v, 0, v); at more than one
// light the lobe of K + C once per pixel.
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
  // Four lights: the lobe of K + C once per pixel, then per light.
  const saagen::Manifest four = parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nnormal_maps = true\nlights = 4\n");
  saagen::ScenePlan four_scene = saagen::plan_scene(Catalogue::builtin(), four, &table);
  EXPECT_EQ(four_scene.materials.at(0).functions,
            (std::vector<std::string>{"deferred_aniso", "deferred_aniso_fragment", "deferred_aniso_covariance", "deferred_aniso_lobe",
                                      "deferred_aniso_brdf_lobe", "deferred_aniso_roughness_with_covariance"}));
  EXPECT_EQ(four_scene.materials.at(0).brdf, std::optional<std::string>("deferred_aniso_brdf_lobe"));
  const std::string four_text = saagen::format_plan(Catalogue::builtin(), four, four_scene);
  EXPECT_NE(four_text.find("lobe = saa_deferred_aniso_lobe(K, alpha2) once per pixel, then saa_deferred_aniso_brdf_lobe(light_ws, "
                           "view_ws, normal_ws, K, alpha2, lobe) per light"),
            std::string::npos)
      << four_text;
  EXPECT_NE(four_text.find("plus the texture covariance C = saa_deferred_aniso_covariance("), std::string::npos) << four_text;
  saagen::measure_costs(Catalogue::builtin(), four, four_scene);
  EXPECT_GT(four_scene.materials.at(0).cost.at(saagen::OutputTarget::snippet("glsl")), 0);

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
      {"target": "glsl", "variant": "deferred-avg", "isa_family": "vega10", "isa_inverse_throughput_ratio": 1.05, "cost_ratio": 0.9, "error": 0.02},
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
      saagen::parse_trade_table(R"({"rows": [{"variant": "deferred-projected-space", "cost_ratio": 0.5}]})", "time.json");
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
      saagen::parse_trade_table(R"({"rows": [{"variant": "deferred-sum", "cost_ratio": 1.0, "delta_spirv_instructions": 9}]})", "t.json");
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
  // deferred-aniso/tail on the normal-mapped normal (TableFreeAdviceFollowsTheMeasuredContent).
  const saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), parse(header + material));
  EXPECT_EQ(
      plan.materials.at(0).normal_advice.rfind("feed the shading normal; no texture prefilter; measured: deferred-aniso/tail (image -", 0),
      0u)
      << plan.materials.at(0).normal_advice;
  // Named deferred-avg: decided among deferred-avg's own rows, the geometric normal without a bake
  // (on the normal-mapped normal it loses close up, at LOD 0 on pmndrs-0010; its hdrp bake loses on
  // pmndrs-0014 and its sweep).
  const saagen::ScenePlan named = saagen::plan_scene(Catalogue::builtin(), parse(header + material + "variant = \"deferred-avg\"\n"));
  EXPECT_EQ(named.materials.at(0).normal_advice.rfind("deferred-avg:geometric/tail (image -", 0), 0u)
      << named.materials.at(0).normal_advice;
  EXPECT_NE(named.materials.at(0).normal_advice.find("deferred-avg/tail (loses on pmndrs-0010-lod0)"), std::string::npos)
      << named.materials.at(0).normal_advice;
  EXPECT_NE(named.materials.at(0).normal_advice.find("deferred-avg:geometric+hdrp/tail (loses on pmndrs-0014, "), std::string::npos)
      << named.materials.at(0).normal_advice;
}

// A content row has one schema wherever it is written (by_content, taa_by_content, the advice's
// rows): the verdict's image error and video error (else flicker error) are read, not the frame-0
// LDR-FLIP "error" and "tde" the bench also writes; a table written before those keys is read by
// "error" and "tde".
TEST(Planner, ContentRowsReadTheVerdictsFigures) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(
      R"({"rows": [], "by_content": [
      {"content": "curved", "configuration": "none", "error": 0.5, "tde": 0.4, "image_error": 0.02, "flicker_error": 0.3, "video_error": 0.9},
      {"content": "curved", "configuration": "deferred-avg", "error": 0.5, "tde": 0.4, "image_error": 0.03, "flicker_error": 0.2},
      {"content": "curved", "configuration": "deferred-sum", "error": 0.5, "tde": 0.4}],
      "taa_by_content": [{"content": "curved", "configuration": "none", "error": 0.1, "image_error": 0.1, "video_error": 2.2}]})",
      "t.json");
  ASSERT_EQ(table.content_rows.size(), 3u);
  EXPECT_EQ(table.content_rows[0].error, 0.02);
  EXPECT_EQ(table.content_rows[0].temporal, std::optional<double>(0.9));
  EXPECT_EQ(table.content_rows[1].temporal, std::optional<double>(0.2));
  EXPECT_EQ(table.content_rows[2].error, 0.5);
  EXPECT_EQ(table.content_rows[2].temporal, std::optional<double>(0.4));
  ASSERT_EQ(table.taa_content_rows.size(), 1u);
  EXPECT_EQ(table.taa_content_rows[0].temporal, std::optional<double>(2.2));
  // Without an against_none, the comparison is the difference of those means.
  const saagen::decision::Comparison c = saagen::comparison_against(table.content_rows[1], table.content_rows[0]);
  EXPECT_DOUBLE_EQ(c.image.mean, 0.01);
  EXPECT_DOUBLE_EQ(c.temporal.mean, 0.2 - 0.9);
  // The advice's rows are read by the same parser, and a bad row is named by its place.
  EXPECT_THROW(
      {
        try {
          (void)saagen::parse_advice_table(
              R"({"schema": "saagen advice 1", "content": [{"content": "curved", "rows": [{"configuration": "none"}]}]})", "a.json");
        } catch (const saagen::Error& error) {
          EXPECT_STREQ(error.what(), "a.json: content[0].rows[0]: needs a number \"image_error\" (tables written before it: \"error\")");
          throw;
        }
      },
      saagen::Error);
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
  EXPECT_NE(error_of_table(R"({"rows": [{"variant": "x", "cost_ratio": "fast"}]})")
                .find("t.json: rows[0]: \"cost_ratio\" must be a positive finite number"),
            std::string::npos);
  EXPECT_EQ(error_of_table(R"({"rows": [], "by_content": [{"content": "curved", "error": 1}]})"),
            "t.json: by_content[0]: needs a string \"configuration\"");
  EXPECT_EQ(error_of_table(R"({"rows": [], "by_content": [{"content": "curved", "configuration": "none"}]})"),
            "t.json: by_content[0]: needs a number \"image_error\" (tables written before it: \"error\")");
  EXPECT_EQ(error_of_table(
                R"({"rows": [], "by_content": [{"content": "curved", "configuration": "none", "image_error": 1, "against_none": {}}]})"),
            "t.json: by_content[0]: \"against_none\" needs \"image\": {\"mean\", \"low\", \"high\"}, finite numbers, low <= mean <= high");
  EXPECT_EQ(
      error_of_table(R"({"rows": [], "by_content": [{"content": "curved", "configuration": "none", "error": 1, "loses_on": "torus"}]})"),
      "t.json: by_content[0]: \"loses_on\" must be an array of scene names");
  EXPECT_EQ(
      error_of_table(R"({"rows": [], "taa_by_content": [{"content": "curved", "configuration": "none", "error": 1, "loses_on": [3]}]})"),
      "t.json: taa_by_content[0]: \"loses_on\" must be an array of scene names");
  EXPECT_EQ(
      error_of_table(
          R"({"rows": [], "by_content": [{"content": "curved", "configuration": "none", "error": 1, "loses_at": [{"scene": "torus"}]}]})"),
      "t.json: by_content[0]: \"loses_at\" must be an array of {\"scene\": NAME, \"alpha\": A}, A in (0, 1]");
  EXPECT_EQ(error_of_table(R"({"rows": [], "alphas": [0.1, 0.01]})"),
            "t.json: \"alphas\" must be an ascending array of GGX alphas in (0, 1]");
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

// A row that beats no SAA over every alpha pooled but loses on one cell (a scene at one alpha:
// "loses_at", as `saagen bench --json` writes it) is not planned for a material whose roughness
// that cell's alpha brackets; for another roughness, and without one, it is (the plan then names
// the cell and asks for the roughness).
TEST(Planner, AMaterialsRoughnessRefusesWhatLosesOnACellAtItsAlphas) {
  const saagen::MeasuredTradeTable table = saagen::parse_trade_table(R"({"rows": [], "alphas": [0.0025, 0.01, 0.1], "by_content": [
      {"content": "curved", "configuration": "none", "error": 0.03, "tde": 0.010},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.02, "tde": 0.008,
       "loses_at": [{"scene": "torus-knot", "alpha": 0.0025}]},
      {"content": "curved", "configuration": "deferred-avg/tail", "error": 0.025, "tde": 0.009}]})",
                                                                     "t.json");
  const auto plan_at = [&](const std::string& roughness) {
    return saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"a\"\npath = \"deferred\"\n" + roughness), &table)
        .materials.at(0);
  };
  // alpha 0.0025 itself; alpha 0.0036, bracketed by 0.0025 and 0.01; a range reaching down to it.
  for (const std::string roughness : {"roughness = 0.05\n", "roughness = 0.06\n", "roughness = [0.08, 0.2]\n"}) {
    const saagen::MaterialPlan smooth = plan_at(roughness);
    EXPECT_EQ(smooth.variant, "deferred-avg") << roughness << smooth.reason;
    EXPECT_NE(smooth.reason.find("deferred-aniso/tail (loses on torus-knot at alpha 0.0025)"), std::string::npos) << smooth.reason;
    EXPECT_NE(smooth.roughness_advice.find("decided on the measured cells (a scene at one alpha) at alpha 0.0025"), std::string::npos)
        << smooth.roughness_advice;
  }
  // alpha 0.04 is bracketed by 0.01 and 0.1 only.
  const saagen::MaterialPlan rough = plan_at("roughness = 0.2\n");
  EXPECT_EQ(rough.variant, "deferred-aniso") << rough.reason;
  EXPECT_NE(rough.roughness_advice.find(
                "0.2 (alpha 0.04): decided on the measured cells (a scene at one alpha) at alpha 0.01, 0.1 (the measured"),
            std::string::npos)
      << rough.roughness_advice;
  // A table without cells per alpha decides over them pooled, and the plan says so.
  const saagen::MeasuredTradeTable pooled_table = saagen::parse_trade_table(R"({"rows": [], "by_content": [
      {"content": "curved", "configuration": "none", "error": 0.03, "tde": 0.010},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.02, "tde": 0.008}]})",
                                                                            "old.json");
  const saagen::MaterialPlan old =
      saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"a\"\npath = \"deferred\"\nroughness = 0.05\n"),
                         &pooled_table)
          .materials.at(0);
  EXPECT_EQ(old.variant, "deferred-aniso") << old.reason;
  EXPECT_NE(old.roughness_advice.find("these figures have no cells per alpha"), std::string::npos) << old.roughness_advice;
  const saagen::MaterialPlan pooled = plan_at("");
  EXPECT_EQ(pooled.variant, "deferred-aniso") << pooled.reason;
  EXPECT_NE(pooled.roughness_advice.find("loses to it beyond its interval on 1 of the cells (a scene at one alpha): torus-knot at alpha "
                                         "0.0025; state the material's `roughness`"),
            std::string::npos)
      << pooled.roughness_advice;
}

TEST(Planner, WithATableATieOfTheMostAccurateGoesToTheCheaper) {
  // deferred-aniso/tail improves TDE most on the mean, deferred-avg/tail ties with it (each worse
  // than the other beyond the interval in neither metric, "not_worse_than") and costs less in the
  // committed ISA table: deferred-avg is planned. Without the pairing the mean decides.
  const std::string rows = R"({"content": "curved", "configuration": "none", "error": 0.03, "tde": 0.010},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.02, "tde": 0.008, "not_worse_than": ["deferred-avg/tail"]},)";
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
  EXPECT_EQ(with_table.materials.at(0).rule, without.materials.at(0).rule);
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
  EXPECT_EQ(plan.materials.at(0).variant, "forward-aniso-projected");  // car_paint: normal-mapped, saagen's decision (F1's form)
  const std::string text = saagen::format_plan(Catalogue::builtin(), manifest, plan);
  EXPECT_NE(text.find("material car_paint"), std::string::npos);
  EXPECT_NE(text.find("variant   forward-aniso-projected  [F1]"), std::string::npos) << text;
  EXPECT_NE(text.find("variant   none  [advice]"), std::string::npos) << text;                   // foliage: curved, deferred, speed
  EXPECT_NE(text.find("variant   forward-axis-slope  [isa table]"), std::string::npos) << text;  // brushed_metal: speed
  EXPECT_NE(text.find("optimized SPIR-V instructions"), std::string::npos);
  // The same filter plus the tail-preserving filtered GGX costs more than with the engine's own BRDF.
  const std::string same_filter =
      "[[material]]\npath = \"forward\"\nanisotropic = true\ntangents = true\nvariant = \"forward-axis-projected\"\n";
  const saagen::Manifest pair = parse(header + same_filter + "name = \"g\"\n" + same_filter + "name = \"b\"\nndf = \"beckmann\"\n");
  saagen::ScenePlan pair_plan = saagen::plan_scene(Catalogue::builtin(), pair);
  saagen::measure_costs(Catalogue::builtin(), pair, pair_plan);
  EXPECT_GT(pair_plan.materials.at(0).cost.at("glsl"), pair_plan.materials.at(1).cost.at("glsl"));
}

// A Beckmann anisotropic forward material preferring speed (the rules rank it by cost), planned
// with a device's timings.
saagen::MaterialPlan beckmann_speed_plan(const saagen::MeasuredTradeTable& timing) {
  const std::string material =
      "[[material]]\nname = \"b\"\npath = \"forward\"\nanisotropic = true\ntangents = true\n"
      "ndf = \"beckmann\"\nprefer = \"speed\"\n";
  return saagen::plan_scene(Catalogue::builtin(), parse(header + material), &timing).materials.at(0);
}

// bench_shading times the projected forms' transported wrappers too, which saagen plans: a plan
// costs them by those rows (the papers' lobe: the papers' wrapper's time plus the transported
// overhead timed with the tail-preserving lobe), here 1.05 + 0.30 against forward-axis-projected's
// 1.30 (no transported row: its papers' time).
TEST(Planner, ADeviceTimingOfTheTransportedWrappersCostsThem) {
  const saagen::MeasuredTradeTable timing = saagen::parse_trade_table(R"json({"device": "Some GPU (discrete GPU, Vulkan 1.4)", "lights": 1,
      "rows": [{"target": "glsl", "variant": "no-saa", "cost_ratio": 1.0},
               {"target": "glsl", "variant": "forward-aniso-projected", "cost_ratio": 1.05},
               {"target": "glsl", "variant": "forward-aniso-projected/tail", "cost_ratio": 1.10},
               {"target": "glsl", "variant": "forward-aniso-projected-transported/tail", "cost_ratio": 1.40},
               {"target": "glsl", "variant": "forward-axis-projected", "cost_ratio": 1.30}]})json",
                                                                      "timing.json");
  ASSERT_TRUE(saagen::committed_advice().forward_transported);
  const saagen::MaterialPlan beckmann = beckmann_speed_plan(timing);
  EXPECT_EQ(beckmann.variant, "forward-axis-projected") << beckmann.reason;
  EXPECT_NE(beckmann.reason.find("forward-aniso-projected 1.35"), std::string::npos) << beckmann.reason;
}

// A device's timings (bench_shading --json, marked by its "no-saa" baseline row) cost the
// decision at the light count they were timed with, instead of the committed ISA model: a budget
// that the ISA ratio of deferred-aniso/tail exceeds (vega10 1.24x) admits it at the device's
// 1.21x; at another light count the ISA model stays and the reason says which count was timed.
// The rules' speed ranking reads the same timings.
TEST(Planner, ADeviceTimingTableCostsThePlanAtItsLightCount) {
  const saagen::MeasuredTradeTable timing = saagen::parse_trade_table(R"json({"device": "Some GPU (discrete GPU, Vulkan 1.4)", "lights": 1,
      "rows": [{"target": "glsl", "variant": "no-saa", "cost_ratio": 1.0},
               {"target": "glsl", "variant": "deferred-aniso/tail", "cost_ratio": 1.20},
               {"target": "hlsl", "variant": "deferred-aniso/tail", "cost_ratio": 1.22},
               {"target": "glsl", "variant": "deferred-avg/tail", "cost_ratio": 1.19},
               {"target": "glsl", "variant": "forward-axis-projected", "cost_ratio": 1.30},
               {"target": "glsl", "variant": "forward-aniso-projected", "cost_ratio": 1.05}]})json",
                                                                      "timing.json");
  EXPECT_TRUE(timing.is_device_timing());
  EXPECT_NEAR(*timing.device_time_ratio("deferred-aniso/tail"), 1.21, 1e-12);
  const std::string curved = header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nbudget = 1.22\n";
  const saagen::MaterialPlan isa = saagen::plan_scene(Catalogue::builtin(), parse(curved)).materials.at(0);
  EXPECT_NE(isa.variant, "deferred-aniso") << isa.reason;
  const saagen::MaterialPlan timed = saagen::plan_scene(Catalogue::builtin(), parse(curved), &timing).materials.at(0);
  EXPECT_EQ(timed.variant, "deferred-aniso") << timed.reason;
  EXPECT_NE(timed.reason.find("1.21x no SAA's shading cost at 1 light on Some GPU (timing.json)"), std::string::npos) << timed.reason;
  const saagen::MaterialPlan four =
      saagen::plan_scene(Catalogue::builtin(), parse(curved + "lights = 4\nprefer = \"accuracy\"\n"), &timing).materials.at(0);
  EXPECT_NE(four.reason.find("at 4 lights (vega10's ISA model: timing.json was timed at 1 light)"), std::string::npos) << four.reason;
  // A Beckmann material preferring speed is ranked by the rules on the same timings.
  const saagen::MaterialPlan beckmann = beckmann_speed_plan(timing);
  EXPECT_EQ(beckmann.variant, "forward-aniso-projected") << beckmann.reason;
  EXPECT_NE(beckmann.reason.find("lowest GPU time ratio in timing.json (at 1 light on Some GPU)"), std::string::npos) << beckmann.reason;
  // A timing table's light count is checked; `saagen bench --json`'s rows (no "no-saa") are no device's timings.
  try {
    (void)saagen::parse_trade_table(R"({"lights": 0, "rows": []})", "t.json");
    ADD_FAILURE() << "a light count of 0 was read";
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(), "t.json: \"lights\" must be an integer from 1 to 64 (the lights bench_shading --lights timed)");
  }
  EXPECT_FALSE(saagen::parse_trade_table(R"({"rows": [{"variant": "none", "cost_ratio": 1.0}]})", "bench.json").is_device_timing());
  // A CPU's timings (lavapipe) never cost a plan: one line says so.
  const saagen::MeasuredTradeTable cpu = saagen::parse_trade_table(
      R"json({"device": "llvmpipe (LLVM 15.0.6, 256 bits) (CPU, Vulkan 1.3.230)", "rows": [{"variant": "no-saa", "cost_ratio": 1.0}]})json",
      "cpu.json");
  try {
    (void)saagen::plan_scene(Catalogue::builtin(), parse(curved), &cpu);
    ADD_FAILURE() << "a CPU's timings were planned with";
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(),
                 "cpu.json: bench_shading timed llvmpipe, a CPU: its time ratios do not stand for a GPU's; time it on your GPU "
                 "(bench_shading --device NAME --json FILE), or plan without it (vega10's ISA model)");
  }
}

// The H200 timings behind docs/GPU_TIMINGS.md, as `saagen plan --trade-table` reads them: at one
// light deferred-aniso/tail costs 1.36x no SAA there (vega10's ISA model: 1.32x), so a curved
// deferred material with budget 1.4 gets deferred-aniso; at 16 lights (1.49x) it does not.
TEST(Planner, TheCommittedH200TimingsPlanABudget) {
  const std::filesystem::path data = std::filesystem::path(SAAGEN_SOURCE_DIR) / "docs" / "data" / "h200";
  const saagen::MeasuredTradeTable one = saagen::load_trade_table(data / "shading_4k_1l.json");
  const saagen::MeasuredTradeTable sixteen = saagen::load_trade_table(data / "shading_4k_16l.json");
  ASSERT_TRUE(one.is_device_timing());
  EXPECT_EQ(sixteen.lights, 16);
  EXPECT_NEAR(*one.device_time_ratio("deferred-aniso/tail"), (1.3401 + 1.3752) / 2.0, 1e-3);
  const std::string curved = header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nbudget = 1.4\n";
  const saagen::MaterialPlan at_one = saagen::plan_scene(Catalogue::builtin(), parse(curved), &one).materials.at(0);
  EXPECT_EQ(at_one.variant, "deferred-aniso") << at_one.reason;
  EXPECT_NE(at_one.reason.find("at 1 light on NVIDIA H200 (" + (data / "shading_4k_1l.json").string() + ")"), std::string::npos)
      << at_one.reason;
  const saagen::MaterialPlan at_sixteen =
      saagen::plan_scene(Catalogue::builtin(), parse(curved + "lights = 16\n"), &sixteen).materials.at(0);
  EXPECT_EQ(at_sixteen.variant, "none") << at_sixteen.reason;
  EXPECT_NE(at_sixteen.reason.find("costs more than the budget 1.4"), std::string::npos) << at_sixteen.reason;
}

// The cost table is one form (cost_tables.hpp, "The cost table"): the committed ISA model and the
// H200's timings name what their ratios measure and give every row the same keys, and each parser
// reads cost_ratio as the figure the planner costs by.
TEST(CostTable, TheIsaModelAndTheTimedTablesShareOneSchema) {
  const std::filesystem::path source(SAAGEN_SOURCE_DIR);
  const auto document_of = [](const std::filesystem::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
  };
  const std::filesystem::path isa_path = source / "generator" / "data" / "isa_cost.json";
  const std::filesystem::path timed_path = source / "docs" / "data" / "h200" / "shading_4k_4l.json";
  const nlohmann::json isa = document_of(isa_path), timed = document_of(timed_path);
  for (const nlohmann::json* table : {&isa, &timed}) {
    EXPECT_TRUE((*table)["cost_model"].is_string());
    for (const nlohmann::json& row : (*table)["rows"]) {
      for (const char* key : {"device", "shader", "target", "variant"}) EXPECT_TRUE(row[key].is_string()) << key << " " << row;
      EXPECT_TRUE(row["cost_ratio"].is_number()) << row;
      if (row["shader"] == "forward") {
        EXPECT_TRUE(row["lights"].is_number_integer()) << row;
      }
    }
  }
  const saagen::IsaTable isa_table = saagen::parse_isa_table(isa.dump(), isa_path.string());
  const nlohmann::json& first = isa["rows"].at(1);
  EXPECT_EQ(isa_table.rows.at(1).inverse_throughput_ratio, first["cost_ratio"].get<double>());
  const saagen::MeasuredTradeTable timed_table = saagen::load_trade_table(timed_path);
  EXPECT_EQ(timed_table.lights, 4);
  for (const nlohmann::json& row : timed["rows"]) {
    EXPECT_EQ(row["lights"], 4);
    EXPECT_EQ(row["device"], timed_table.device_name());
  }
  const auto timed_ratio = [&](const std::string& target) {
    for (const nlohmann::json& row : timed["rows"])
      if (row["variant"] == "deferred-avg/tail" && row["target"] == target) return row["cost_ratio"].get<double>();
    return 0.0;
  };
  EXPECT_DOUBLE_EQ(*timed_table.device_time_ratio("deferred-avg/tail"), (timed_ratio("glsl") + timed_ratio("hlsl")) / 2.0);
}

}  // namespace

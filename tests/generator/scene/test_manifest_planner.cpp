// Scene manifests (test_manifest): the planner's rules without a trade table -- the documented
// variant per material, saagen's table-free advice per content type, path and TAA (held-out
// scenes included), the shading budget and the committed costs per light.
#include "manifest_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using saagen::Catalogue;
using namespace saagen::test::manifest;

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
    // an isotropic one takes deferred-aniso for speed (below); the Beckmann cases keep the rules'
    // choice.
    ::testing::Values(
        RuleCase{"path = \"forward\"\nanisotropic = true\ntangents = true\n",
                 "F1",
                 "forward-aniso-projected",
                 {"forward_aniso_projected", "forward_aniso_projected_transported_fragment", "ggx_brdf_filtered_matrix"}},
        RuleCase{"path = \"forward\"\nanisotropic = true\ntangents = true\nndf = \"beckmann\"\n",
                 "F1",
                 "forward-aniso-projected",
                 {"forward_aniso_projected", "forward_aniso_projected_transported_fragment", "beckmann_brdf_matrix", "ndf_clamp_tau"}},
        // Speed, Beckmann: the rule's forward-axis-projected costs 1.389x no SAA through its
        // transported wrapper (as the advice measured it), forward-axis-slope 1.163x (vega10
        // ISA): the cheapest, with the engine's own BRDF.
        RuleCase{"path = \"forward\"\nanisotropic = true\ntangents = true\nprefer = \"speed\"\nndf = \"beckmann\"\n",
                 "isa table",
                 "forward-axis-slope",
                 {"forward_axis_slope", "forward_axis_slope_fragment"}},
        RuleCase{"path = \"forward\"\nanisotropic = true\ntangents = true\nprefer = \"speed\"\n", "advice", "none", {}},
        RuleCase{"path = \"forward\"\ntangents = true\n",
                 "F3",
                 "forward-aniso-projected",
                 {"forward_aniso_projected", "forward_aniso_projected_transported_fragment", "ggx_brdf_filtered_matrix"}},
        // Curved, forward, speed: the cheapest form that beats no SAA, forward-axis-projected/tail
        // (1.439x), loses to it on a held-out model (teapots), and the transported
        // forward-aniso-projected/tail (1.463x) is the most expensive usable form, which speed
        // never takes: deferred-aniso/tail (1.433x, one tensor per pixel and its lobe per light).
        RuleCase{"path = \"forward\"\ntangents = true\nprefer = \"speed\"\n",
                 "advice",
                 "deferred-aniso",
                 {"deferred_aniso", "deferred_aniso_fragment", "deferred_aniso_roughness", "deferred_aniso_brdf"}},
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
        // Normal-mapped content: deferred-aniso/tail, the largest video gain of the forms that lose to
        // no SAA on none of saagen's maps at any distance (deferred-avg/tail loses close up, at
        // LOD 0 on pmndrs-0010; the hdrp bake on pmndrs-0014).
        RuleCase{"path = \"deferred\"\nnormal_maps = true\n",
                 "advice",
                 "deferred-aniso",
                 {"deferred_aniso", "deferred_aniso_fragment", "deferred_aniso_roughness", "deferred_aniso_brdf"}},
        RuleCase{"path = \"deferred\"\nnormal_maps = true\nndf = \"beckmann\"\n",
                 "D1",
                 "deferred-avg",
                 {"deferred_avg", "deferred_avg_fragment"}},
        RuleCase{"path = \"deferred\"\nndf = \"beckmann\"\n", "D1", "deferred-avg", {"deferred_avg", "deferred_avg_fragment"}},
        // Curved content: no filter an anisotropic deferred material can use beats no SAA.
        RuleCase{"path = \"deferred\"\nanisotropic = true\ntangents = true\n", "advice", "none", {}},
        // With normal maps an anisotropic material cannot take deferred-aniso (an isotropic
        // material's): the most accurate of the forms it can use that lose on none of the maps,
        // deferred-projected-space on the geometric normal, loses to no SAA on one held-out map
        // (pmndrs-0001 at LOD 4): no filter.
        RuleCase{"path = \"deferred\"\nanisotropic = true\ntangents = true\nnormal_maps = true\n", "advice", "none", {}},
        // Curved content, deferred, speed: only deferred-aniso beats no SAA, the most expensive deferred
        // form (1.60x); speed never takes it, and the cheaper deferred kernels lose: no filter.
        RuleCase{"path = \"deferred\"\nprefer = \"speed\"\n", "advice", "none", {}},
        RuleCase{"path = \"deferred\"\nprefer = \"speed\"\nndf = \"beckmann\"\n",
                 "D2",
                 "deferred-avg",
                 {"deferred_avg", "deferred_avg_fragment"}},
        // From 4 lights on the deferred forms' lobe is split per pixel and per light; 2 and 3
        // lights are costed at one light's row, and get its one-pass form.
        RuleCase{"path = \"deferred\"\nvariant = \"deferred-sum\"\nlights = 3\n",
                 "manifest",
                 "deferred-sum",
                 {"deferred_sum", "deferred_sum_fragment", "ggx_brdf_filtered_axis"}},
        RuleCase{"path = \"deferred\"\nvariant = \"deferred-sum\"\nlights = 4\n",
                 "manifest",
                 "deferred-sum",
                 {"deferred_sum", "deferred_sum_fragment", "ggx_filtered_lobe_isotropic", "ggx_brdf_filtered_lobe"}},
        RuleCase{
            "path = \"deferred\"\nlights = 4\n",
            "D0",
            "deferred-aniso",
            {"deferred_aniso", "deferred_aniso_fragment", "deferred_aniso_roughness", "deferred_aniso_lobe", "deferred_aniso_brdf_lobe"}},
        RuleCase{"path = \"deferred\"\ntangents = true\nvariant = \"deferred-max\"\n",
                 "manifest",
                 "deferred-max",
                 {"deferred_max", "deferred_max_fragment", "ggx_brdf_filtered_axis"}},
        RuleCase{"path = \"deferred\"\nvariant = \"deferred-max\"\n",
                 "manifest",
                 "deferred-max",
                 {"deferred_max_tangent_free", "deferred_max_tangent_free_fragment", "ggx_brdf_filtered_axis"}}),
    [](const ::testing::TestParamInfo<RuleCase>& info) {
      std::string rule = info.param.rule;  // "isa table": a test name has no spaces
      std::replace(rule.begin(), rule.end(), ' ', '_');
      return "case" + std::to_string(info.index) + "_" + rule;
    });

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
  // Normal-mapped: the content's scenes include the maps' minification sweep (LOD 0 - 4), on which
  // the isotropic forms lose close up (deferred-avg/tail at LOD 0 on pmndrs-0010); deferred-aniso/tail
  // beats no SAA on every one, with the largest video gain, and on the held-out maps.
  const auto mapped = plan_of("", "\"deferred\"\nnormal_maps = true\n");
  EXPECT_EQ(mapped.variant, "deferred-aniso");
  EXPECT_EQ(mapped.feed, "shading");
  EXPECT_EQ(mapped.prefilter, "none");
  EXPECT_NE(mapped.reason.find("deferred-aniso/tail (image -"), std::string::npos) << mapped.reason;
  EXPECT_NE(mapped.reason.find("pmndrs-0010-lod4; generator/data/advice.json"), std::string::npos) << mapped.reason;
  EXPECT_NE(mapped.measure_advice.find("this advice held on content it was not derived from (held-out scenes pmndrs-0000"),
            std::string::npos)
      << mapped.measure_advice;
  // Named, a normal-mapped filter gets the same decision among its own feeds and bakes: deferred-sum
  // on the geometric normal without a bake (the map-fed form loses on pmndrs-0014 and, close up,
  // more). It beats no SAA on the held-out maps pooled but loses on one of them (pmndrs-0001 at
  // LOD 4), and the plan says so; a material that names its variant is not given no filter, and
  // the variant's own input loses on more of saagen's scenes, so the pick stands.
  const auto named = plan_of("", "\"deferred\"\nnormal_maps = true\nvariant = \"deferred-sum\"\n");
  EXPECT_EQ(named.variant, "deferred-sum");
  EXPECT_EQ(named.feed, "geometric");
  EXPECT_EQ(named.prefilter, "none");
  EXPECT_EQ(named.normal_advice.rfind("deferred-sum:geometric/tail (image ", 0), 0u) << named.normal_advice;
  EXPECT_NE(named.normal_advice.find("deferred-sum/tail (loses on pmndrs-0014, pmndrs-0014-lod0, "), std::string::npos)
      << named.normal_advice;
  EXPECT_NE(named.normal_advice.find("this advice held pooled, not on each scene, on content it was not derived from (held-out scenes "),
            std::string::npos)
      << named.normal_advice;
  EXPECT_NE(named.normal_advice.find("; it loses to no SAA beyond its interval on pmndrs-0001-lod4); "), std::string::npos)
      << named.normal_advice;
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
  // gets the filter that beats TAA alone there and on the held-out models. Normal-mapped content,
  // its maps at every distance: deferred-avg/tail in the deferred path (it holds on each held-out
  // map); in the forward path forward-axis-projected/tail, which loses on one held-out map
  // (pmndrs-0002 at LOD 1), so no filter.
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
  EXPECT_EQ(taa_mapped.variant, "deferred-avg");
  EXPECT_NE(taa_mapped.reason.find("deferred-avg/tail (image -"), std::string::npos) << taa_mapped.reason;
  EXPECT_NE(taa_mapped.measure_advice.find("this advice held on content it was not derived from (held-out scenes pmndrs-0000"),
            std::string::npos)
      << taa_mapped.measure_advice;
  const auto taa_mapped_forward = plan_of("taa = true\n", "\"forward\"\ntangents = true\nnormal_maps = true\n");
  EXPECT_EQ(taa_mapped_forward.variant, "none");
  EXPECT_NE(taa_mapped_forward.reason.find("forward-axis-projected/tail (image -"), std::string::npos) << taa_mapped_forward.reason;
  EXPECT_NE(taa_mapped_forward.reason.find("; it loses to none+taa beyond its interval on pmndrs-0002-lod1), so it is not given"),
            std::string::npos)
      << taa_mapped_forward.reason;
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
  // Curved content, deferred: only deferred-aniso/tail (1.24x on vega10, GLSL) beats no SAA.
  const auto tight = plan_of("\"deferred\"\nbudget = 1.2\n");
  EXPECT_EQ(tight.variant, "none");
  EXPECT_NE(tight.reason.find("costs more than the budget 1.2"), std::string::npos) << tight.reason;
  const auto at_goal = plan_of("\"deferred\"\nbudget = 1.25\nprefer = \"speed\"\n");
  EXPECT_EQ(at_goal.variant, "deferred-aniso") << at_goal.reason;
  EXPECT_NE(at_goal.reason.find("1.24x no SAA's shading cost at 1 light"), std::string::npos) << at_goal.reason;
  const auto loose = plan_of("\"deferred\"\nbudget = 2\nprefer = \"speed\"\n");  // the budget decides, not prefer
  EXPECT_EQ(loose.variant, "deferred-aniso");
  EXPECT_NE(loose.reason.find("within the budget 2"), std::string::npos) << loose.reason;
  // Bumps, forward: forward-aniso-projected/tail (1.46x through its transported wrapper) ties
  // deferred-aniso/tail (1.24x), which is beaten by one of its ties in a pairing, so within 1.51 the
  // former is taken; within 1.25 only the deferred-aniso forms fit, and deferred-aniso/tail, beaten
  // by none of its ties there, is taken; within 1.2 nothing that beats no SAA fits.
  const auto mapped = plan_of("\"forward\"\ntangents = true\ncontent = \"bumps\"\nbudget = 1.51\n");
  EXPECT_EQ(mapped.variant, "forward-aniso-projected") << mapped.reason;
  EXPECT_NE(mapped.reason.find("within the budget 1.51"), std::string::npos) << mapped.reason;
  const auto tighter = plan_of("\"forward\"\ntangents = true\ncontent = \"bumps\"\nbudget = 1.25\n");
  EXPECT_EQ(tighter.variant, "deferred-aniso") << tighter.reason;
  EXPECT_NE(tighter.reason.find("within the budget 1.25"), std::string::npos) << tighter.reason;
  const auto tightest = plan_of("\"forward\"\ntangents = true\ncontent = \"bumps\"\nbudget = 1.2\n");
  EXPECT_EQ(tightest.variant, "none") << tightest.reason;
  EXPECT_NE(tightest.reason.find("costs more than the budget 1.2"), std::string::npos) << tightest.reason;
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
// BRDF: their overhead shrinks as the lights grow. So do the deferred forms with saagen's lobe,
// deferred-aniso's included, whose light-independent part is computed once per pixel
// (ggx_filtered_lobe_isotropic, deferred_aniso_lobe). The forward forms filter per light: theirs
// grows.
TEST(Planner, CommittedCostsGrowPerLightAndShrinkPerPixel) {
  for (const std::string per_pixel : {"deferred-avg", "deferred-sum", "deferred-avg/tail", "deferred-sum/tail", "deferred-aniso/tail"}) {
    EXPECT_LT(committed_ratio(per_pixel, 4), committed_ratio(per_pixel, 1)) << per_pixel;
    EXPECT_LT(committed_ratio(per_pixel, 16), committed_ratio(per_pixel, 4)) << per_pixel;
  }
  // The forward forms filter and shade per light: their cost grows.
  for (const std::string per_light : {"forward-aniso-projected", "forward-aniso-projected/tail", "forward-axis-projected/tail"}) {
    EXPECT_GT(committed_ratio(per_light, 4), committed_ratio(per_light, 1)) << per_light;
    EXPECT_GT(committed_ratio(per_light, 16), committed_ratio(per_light, 4)) << per_light;
  }
  // deferred-aniso's per-light lobe is a matrix lobe, dearer than no SAA's BRDF: its ratio tends
  // to that lobe's over the BRDF, above the papers' per-pixel overhead, which vanishes.
  const double papers_overhead = committed_ratio("deferred-avg", 16) - 1.0;
  EXPECT_GT(committed_ratio("deferred-aniso/tail", 16) - 1.0, papers_overhead);
  // A table without light counts (written before they were measured) is one light's.
  const saagen::IsaTable old = saagen::parse_isa_table(
      R"({"families": ["vega10"], "rows": [{"device": "vega10", "shader": "forward", "target": "glsl", "variant": "deferred-avg",
          "instructions": 1, "vgprs": 1, "sgprs": 1, "subgroups_per_simd": 1, "latency": 1, "inverse_throughput": 1,
          "cost_ratio": 1.25}]})",
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
      (void)saagen::parse_isa_table(R"({"families": ["vega10"], "rows": [{"device": "vega10", "shader": "forward", "target": "glsl",
          "variant": "deferred-avg", "instructions": 1, "vgprs": 1, "sgprs": 1, "subgroups_per_simd": 1, "latency": 1,
          "inverse_throughput": 1, "cost_ratio": 1.25, "lights": )" +
                                        value + "}]}",
                                    "bad.json");
    } catch (const saagen::Error& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_NE(bad_lights("0").find("bad.json: rows[0]: \"lights\" must be an integer from 1 to 64"), std::string::npos) << bad_lights("0");
  EXPECT_NE(bad_lights("2.5").find("must be an integer"), std::string::npos) << bad_lights("2.5");
  EXPECT_EQ(bad_lights("64"), "");
  // The committed table names each family's device and keeps every ratio to no SAA.
  EXPECT_EQ(committed.devices.at("vega10"), "Null hardware (RADV VEGA10)");
  for (const saagen::IsaRow& row : committed.rows) {
    if (row.variant == "no-saa") {
      EXPECT_EQ(row.instructions_ratio, 1.0) << row.family << " " << row.target.name();
    }
    if (row.variant == "deferred-avg" && row.lights == 1) {
      EXPECT_GT(row.instructions_ratio, 1.0) << row.family << " " << row.target.name();
    }
  }
  try {
    (void)saagen::parse_isa_table(R"({"families": ["vega10"], "devices": ["vega10"], "rows": []})", "devices.json");
    ADD_FAILURE() << "a devices array was read";
  } catch (const saagen::Error& error) {
    EXPECT_NE(std::string(error.what()).find("devices.json: \"devices\" must be an object of strings"), std::string::npos) << error.what();
  }
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
        const saagen::MaterialDecision made =
            saagen::decide_material(Catalogue::builtin(), material, "", measured->rows, saagen::committed_advice().forward_transported);
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

// The advice's measurement says which wrappers of the projected forward filters it measured
// (saagen bench --half-vector-frame): a plan calls those and never both; the committed advice's
// are the transported ones (Rules above), an advice measured in the tangent frames plans the
// papers'.
TEST(Planner, ForwardPlansCallTheWrapperTheAdviceWasMeasuredWith) {
  const saagen::Manifest manifest = parse(header + "[[material]]\nname = \"m\"\npath = \"forward\"\ntangents = true\n");
  ASSERT_TRUE(saagen::committed_advice().forward_transported);
  const saagen::MaterialPlan plan = saagen::plan_scene(Catalogue::builtin(), manifest).materials.at(0);
  EXPECT_EQ(plan.variant, "forward-aniso-projected") << plan.reason;
  EXPECT_EQ(plan.wrapper, "forward_aniso_projected_transported_fragment");
  EXPECT_EQ(plan.functions, (std::vector<std::string>{"forward_aniso_projected", "forward_aniso_projected_transported_fragment",
                                                      "ggx_brdf_filtered_matrix"}));
  saagen::AdviceTable tangent = saagen::committed_advice();
  tangent.forward_transported = false;
  const saagen::MaterialPlan papers = saagen::plan_scene(Catalogue::builtin(), manifest, nullptr, tangent).materials.at(0);
  EXPECT_EQ(papers.wrapper, "forward_aniso_projected_fragment");
  EXPECT_EQ(papers.functions,
            (std::vector<std::string>{"forward_aniso_projected", "forward_aniso_projected_fragment", "ggx_brdf_filtered_matrix"}));
  const auto frame_of = [](const std::string& value) {
    return saagen::parse_advice_table(R"({"schema": "saagen advice 1", "forward_half_vector_frame": )" + value + R"(, "content": []})",
                                      "advice.json");
  };
  EXPECT_TRUE(frame_of("\"transported\"").forward_transported);
  EXPECT_FALSE(frame_of("\"tangent\"").forward_transported);
  EXPECT_THROW(frame_of("\"sideways\""), saagen::Error);
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
// metric) on the held-out scenes, pooled or on any one of them; where it gives nothing, the
// decision found nothing there or its choice lost on the held-out scenes.
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
              saagen::decide_material(Catalogue::builtin(), material, "", measured->rows, saagen::committed_advice().forward_transported,
                                      taa ? "none+taa" : "no SAA");
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
                                                saagen::decision::outcome(*held_out) == saagen::decision::Outcome::mixed ||
                                                !measured->held_out_loses_on(chosen.configuration).empty());
          EXPECT_EQ(plan.variant == "none", loses_there) << where << ": " << plan.reason;
          (loses_there ? withheld : given) += 1;
        }
      }
    }
  }
  EXPECT_GT(given, 0);
  EXPECT_GT(withheld, 0);  // the gate is exercised by the committed measurement (normal-mapped: speed; under TAA)
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

// `map_lod`: a normal-mapped material seen only from afar is decided on saagen's scenes with maps
// that far away (the entry of the largest map_lod_min not above it), nearer ones on every distance.
TEST(Planner, MapLodTakesTheAdviceMeasuredThatFarAway) {
  const auto comparison = [](double image, double temporal) {
    return fmt::format(R"({{"image": {{"mean": {0}, "low": {0}, "high": {0}}}, "temporal": {{"mean": {1}, "low": {1}, "high": {1}}}}})",
                       image, temporal);
  };
  const auto entry = [&](const std::string& head, const std::string& configuration) {
    return fmt::format(R"({{"content": "normal-mapped", {}, "held_out_scenes": [], "rows": [
        {{"configuration": "none", "image_error": 0.05, "video_error": 4}},
        {{"configuration": "{}", "image_error": 0.04, "video_error": 2, "against_none": {}}}]}})",
                       head, configuration, comparison(-0.01, -2.0));
  };
  const saagen::AdviceTable advice =
      saagen::parse_advice_table(R"({"schema": "saagen advice 1", "content": [)" + entry(R"("scenes": ["near"])", "deferred-sum/tail") +
                                     "," + entry(R"("map_lod_min": 4, "scenes": ["far"])", "deferred-sum:geometric+hdrp/tail") + "]}",
                                 "advice.json");
  const auto plan_at = [&](const std::string& map_lod) {
    const std::string material = "[[material]]\nname = \"m\"\npath = \"deferred\"\nnormal_maps = true\n" + map_lod;
    return saagen::plan_scene(Catalogue::builtin(), parse(header + material), nullptr, advice).materials.at(0);
  };
  for (const char* near : {"", "map_lod = 3\n"}) {
    const saagen::MaterialPlan plan = plan_at(near);
    EXPECT_EQ(plan.prefilter, "none") << plan.reason;
    EXPECT_NE(plan.reason.find("saagen's trade (near;"), std::string::npos) << plan.reason;
  }
  for (const char* far : {"map_lod = 4\n", "map_lod = 9\n"}) {
    const saagen::MaterialPlan plan = plan_at(far);
    EXPECT_EQ(plan.variant, "deferred-sum") << plan.reason;
    EXPECT_EQ(plan.feed, "geometric");
    EXPECT_EQ(plan.prefilter, "hdrp");
    EXPECT_NE(plan.reason.find("saagen's trade (far;"), std::string::npos) << plan.reason;
  }
  EXPECT_THROW(saagen::parse_advice_table(
                   R"({"schema": "saagen advice 1", "content": [{"content": "curved", "map_lod_min": -1, "rows": []}]})", "advice.json"),
               saagen::Error);
  // Where the far entry's choice loses on one of its held-out maps, the advice of every distance
  // (whose scenes include the far ones) is given, and the plan says why.
  const std::string far_losing =
      fmt::format(R"({{"content": "normal-mapped", "map_lod_min": 4, "scenes": ["far"], "held_out_scenes": ["x", "y"], "rows": [
      {{"configuration": "none", "image_error": 0.05, "video_error": 4}},
      {{"configuration": "deferred-sum:geometric+hdrp/tail", "image_error": 0.04, "video_error": 2, "against_none": {0}, "held_out": {0},
        "held_out_loses_on": ["y"]}}]}})",
                  comparison(-0.01, -2.0));
  const saagen::AdviceTable withheld = saagen::parse_advice_table(
      R"({"schema": "saagen advice 1", "content": [)" + entry(R"("scenes": ["near"])", "deferred-sum/tail") + "," + far_losing + "]}",
      "advice.json");
  const saagen::MaterialPlan fallen =
      saagen::plan_scene(Catalogue::builtin(),
                         parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nnormal_maps = true\nmap_lod = 4\n"), nullptr,
                         withheld)
          .materials.at(0);
  EXPECT_EQ(fallen.prefilter, "none") << fallen.reason;
  EXPECT_NE(fallen.reason.find("saagen's trade (near; generator/data/advice.json); with maps at LOD >= 4 (far) the decision takes "
                               "deferred-sum:geometric+hdrp/tail, which does not hold on their held-out maps (x, y: "),
            std::string::npos)
      << fallen.reason;
  EXPECT_NE(fallen.reason.find("; it loses to no SAA beyond its interval on y), so the advice of every distance"), std::string::npos)
      << fallen.reason;
}

// saagen's committed figures at a material's roughness: the derivation scenes' cells decide, the
// held-out scenes' cells check (a choice that loses on a held-out cell at the material's alphas does
// not hold there and is withheld), and other alphas' cells count for nothing.
TEST(Planner, TheAdviceAtAMaterialsRoughnessIsCheckedOnTheHeldOutCellsThere) {
  const std::string beats =
      R"({"image": {"mean": -0.01, "low": -0.02, "high": -0.005}, "temporal": {"mean": -1, "low": -2, "high": -0.5}})";
  const saagen::AdviceTable advice = saagen::parse_advice_table(
      fmt::format(R"({{"schema": "saagen advice 1", "content": [{{"content": "curved", "scenes": ["a"], "held_out_scenes": ["b"],
        "alphas": [0.0025, 0.05, 0.3], "rows": [
        {{"configuration": "none", "image_error": 0.05, "video_error": 4}},
        {{"configuration": "deferred-aniso/tail", "image_error": 0.04, "video_error": 3, "against_none": {0}, "held_out": {0},
          "held_out_loses_at": [{{"scene": "b", "alpha": 0.3}}]}},
        {{"configuration": "deferred-avg/tail", "image_error": 0.04, "video_error": 3.5, "against_none": {0}, "held_out": {0},
          "loses_at": [{{"scene": "a", "alpha": 0.0025}}]}}]}}]}})",
                  beats),
      "advice.json");
  const auto plan_at = [&](const std::string& roughness) {
    return saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\n" + roughness),
                              nullptr, advice)
        .materials.at(0);
  };
  const saagen::MaterialPlan smooth = plan_at("roughness = 0.05\n");
  EXPECT_EQ(smooth.variant, "deferred-aniso") << smooth.reason;
  EXPECT_NE(smooth.measure_advice.find("this advice held on content it was not derived from"), std::string::npos) << smooth.measure_advice;
  const saagen::MaterialPlan rough = plan_at("roughness = 0.5\n");
  EXPECT_EQ(rough.variant, "none") << rough.reason;
  EXPECT_NE(rough.reason.find("it loses to no SAA beyond its interval on b at alpha 0.3), so it is not given"), std::string::npos)
      << rough.reason;
  EXPECT_EQ(plan_at("").variant, "deferred-aniso");
}

// saagen's committed figures under TAA carry their cells too: at a roughness where the TAA pick
// loses to TAA alone on a held-out cell (normal-mapped, deferred: deferred-avg/tail on
// pmndrs-0001 at LOD 4 at alpha 0.05), it is withheld; where it loses on none (alpha 0.01), it is given.
TEST(Planner, UnderTaaTheCommittedAdviceIsJudgedAtAMaterialsRoughness) {
  const auto plan_at = [&](const std::string& roughness) {
    const std::string material = "[[material]]\nname = \"m\"\npath = \"deferred\"\nnormal_maps = true\nroughness = ";
    return saagen::plan_scene(Catalogue::builtin(), parse(header + "taa = true\n" + material + roughness + "\n")).materials.at(0);
  };
  const saagen::MaterialPlan medium = plan_at("0.224");
  EXPECT_EQ(medium.variant, "none") << medium.reason;
  EXPECT_NE(medium.reason.find("pmndrs-0001-lod4 at alpha 0.05"), std::string::npos) << medium.reason;
  EXPECT_NE(medium.reason.find("so it is not given"), std::string::npos) << medium.reason;
  const saagen::MaterialPlan smooth = plan_at("0.1");
  EXPECT_EQ(smooth.variant, "deferred-avg") << smooth.reason;
  EXPECT_NE(smooth.roughness_advice.find("decided on the measured cells"), std::string::npos) << smooth.roughness_advice;
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
  // Under TAA a curved deferred material at roughness 0.548 (alpha 0.3) is advised none (`saagen
  // plan --advice`'s per-roughness table).
  const saagen::Manifest taa = parse(header + "taa = true\n[[material]]\nname = \"m\"\npath = \"deferred\"\nroughness = 0.548\n");
  EXPECT_TRUE(saagen::emit_scene(Catalogue::builtin(), taa, saagen::plan_scene(Catalogue::builtin(), taa)).empty());
  EXPECT_EQ(error_of(header + "[[material]]\nname = \"m\"\npath = \"deferred\"\ncontent = \"normal-mapped\"\n"),
            "scene.toml:5:11: key 'content' of material 'm': \"normal-mapped\" needs normal_maps = true; allowed: normal_maps = true, or "
            "another content type");
}

}  // namespace

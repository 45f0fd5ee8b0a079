// One answer: `saagen plan` and the bench's verdict ("what to use") come from the same decision
// (saagen/decision.hpp). On examples/scene.saagen.toml with a small trade table, every material
// the planner decides for is planned what the verdict says for its path and content (accuracy or
// speed); and prefer = "speed" never plans the most expensive form.
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/report/findings.hpp"
#include "saagen/report/report.hpp"
#include "saagen/scene/planner.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

namespace {

using namespace saagen;
using measure::Lobe;
using measure::NormalFeed;
using measure::Prefilter;
using measure::SceneId;
using measure::Variant;

measure::TradeRow row(SceneId scene, Variant variant, double flip, double tde, Lobe lobe = Lobe::tail,
                      NormalFeed feed = NormalFeed::shading, Prefilter prefilter = Prefilter::none) {
  measure::TradeRow r;
  r.scene = scene, r.variant = variant, r.lobe = variant == Variant::none || measure::is_engine(variant) ? Lobe::papers : lobe;
  r.feed = feed, r.prefilter = prefilter, r.alpha = 0.05, r.flip_ldr = flip, r.tde = tde;
  // The verdict's metrics (trade.hpp): the same values on every frame against both seeds, so that
  // every paired difference is exact (a zero-width interval) and the decision turns on the means.
  r.image_error = {flip, flip, flip};
  r.flicker_error = {tde, tde, tde};
  for (int seed = 0; seed < 2; ++seed) {
    r.series.image[seed].assign(16, flip);
    r.series.flicker[seed].assign(15, tde);
  }
  return r;
}

// A curved scene where the forward and deferred matrix forms beat no SAA and the cheaper
// deferred form loses; a normal-mapped scene where everything lowers LDR-FLIP and raises TDE.
measure::TradeTable small_table() {
  measure::TradeTable table;
  table.config.scenes = {SceneId::sphere, SceneId::nmap_sphere};
  table.config.alphas = {0.05};
  table.rows = {row(SceneId::sphere, Variant::none, 0.030, 0.0140),
                row(SceneId::sphere, Variant::forward_aniso_projected, 0.025, 0.0118),
                row(SceneId::sphere, Variant::forward_axis_projected, 0.028, 0.0130),
                row(SceneId::sphere, Variant::deferred_aniso, 0.026, 0.0119),
                row(SceneId::sphere, Variant::deferred_avg, 0.050, 0.0155),
                row(SceneId::sphere, Variant::engine_hdrp, 0.029, 0.0150),
                row(SceneId::nmap_sphere, Variant::none, 0.060, 0.0146),
                row(SceneId::nmap_sphere, Variant::forward_axis_projected, 0.050, 0.0160),
                row(SceneId::nmap_sphere, Variant::deferred_aniso, 0.055, 0.0165),
                row(SceneId::nmap_sphere, Variant::deferred_aniso, 0.057, 0.0158, Lobe::tail, NormalFeed::geometric, Prefilter::hdrp),
                row(SceneId::nmap_sphere, Variant::engine_hdrp, 0.059, 0.0150)};
  return table;
}

const report::Recommendation& verdict(const std::vector<report::Recommendation>& recs, RenderPath path, advice::Content content) {
  const report::Path p = path == RenderPath::forward ? report::Path::forward : report::Path::deferred;
  const report::Recommendation* found = report::find_recommendation(recs, p, content);
  if (!found) throw std::runtime_error("no verdict");
  return *found;
}

// "none", or the plan's configuration as the trade names it.
std::string planned_configuration(const MaterialPlan& plan) {
  if (plan.variant == "none") return "none";
  std::string id = plan.variant;
  if (plan.feed == "geometric") id += ":geometric";
  if (plan.prefilter != "none") id += "+" + plan.prefilter;
  return id + "/tail";
}

TEST(OneAnswer, ThePlanOfTheExampleSceneIsTheBenchVerdict) {
  const measure::TradeTable trade = small_table();
  const std::vector<report::Recommendation> recs = report::recommend(trade);
  const MeasuredTradeTable table = parse_trade_table(report::trade_json(trade, report::summarize(trade), nullptr).dump(), "small.json");
  const Catalogue& catalogue = Catalogue::builtin();
  const Manifest manifest = load_manifest(SAAGEN_SOURCE_DIR "/examples/scene.saagen.toml", catalogue);
  const ScenePlan plan = plan_scene(catalogue, manifest, &table);
  int decided = 0;
  for (std::size_t i = 0; i < manifest.materials.size(); ++i) {
    const Material& material = manifest.materials[i];
    if (material.variant || material.ndf != Ndf::ggx || manifest.preset) continue;  // the planner does not decide for these
    ++decided;
    const report::Recommendation& v = verdict(recs, material.path, content_of(material));
    const std::string expected = material.prefer == Preference::speed ? v.speed_configuration : v.configuration;
    if (material.anisotropic && expected != "none") continue;  // only the matrix forms: a narrower choice than the path's
    EXPECT_EQ(planned_configuration(plan.materials[i]), expected) << material.name << ": " << plan.materials[i].reason;
  }
  EXPECT_EQ(decided, 2);  // car_paint (forward, normal-mapped) and foliage (deferred, curved, prefer speed)
  // The values themselves: on the curved scene the deferred matrix form beats no SAA and is the most
  // expensive deferred form, so prefer speed plans no filter; on the normal-mapped scene nothing beats.
  EXPECT_EQ(verdict(recs, RenderPath::deferred, advice::Content::curved).configuration, "deferred-aniso/tail");
  EXPECT_EQ(verdict(recs, RenderPath::deferred, advice::Content::curved).speed_configuration, "none");
  EXPECT_EQ(verdict(recs, RenderPath::forward, advice::Content::curved).configuration, "forward-aniso-projected/tail");
  EXPECT_EQ(verdict(recs, RenderPath::forward, advice::Content::normal_mapped).configuration, "none");
  EXPECT_EQ(plan.materials[3].material, "foliage");
  EXPECT_EQ(plan.materials[3].variant, "none");
  EXPECT_EQ(plan.materials[0].variant, "none");  // car_paint
}

TEST(OneAnswer, TheJsonCarriesTheDecisionTheVerdictPrints) {
  const measure::TradeTable trade = small_table();
  const nlohmann::json json = report::trade_json(trade, report::summarize(trade), nullptr);
  const nlohmann::json& decisions = json.at("decisions");
  bool found = false;
  for (const nlohmann::json& entry : decisions.at("by_content")) {
    if (entry["content"] != "curved" || entry["path"] != "deferred") continue;
    found = true;
    EXPECT_EQ(entry["chosen"], "deferred-aniso/tail");
  }
  EXPECT_TRUE(found);
  for (const nlohmann::json& entry : decisions.at("per_scene")) {
    if (entry["scene"] != "sphere" || entry["path"] != "forward") continue;
    EXPECT_EQ(entry["chosen"], "forward-aniso-projected/tail");
    EXPECT_EQ(entry["against_engines"]["engine-hdrp"]["outcome"], "beats");
  }
}

TEST(OneAnswer, SpeedNeverPlansTheMostExpensiveFormWithoutATable) {
  const Catalogue& catalogue = Catalogue::builtin();
  const Manifest manifest = load_manifest(SAAGEN_SOURCE_DIR "/examples/scene.saagen.toml", catalogue);
  const ScenePlan plan = plan_scene(catalogue, manifest);
  ASSERT_EQ(plan.materials[3].material, "foliage");
  // saagen's committed curved figures: deferred-aniso/tail beats no SAA at 1.60x no SAA's cost,
  // deferred-avg/tail loses; prefer speed plans no filter, and says why.
  EXPECT_EQ(plan.materials[3].variant, "none");
  EXPECT_NE(plan.materials[3].reason.find("most expensive form"), std::string::npos) << plan.materials[3].reason;
  // Every table-free plan says how to measure one's own asset.
  EXPECT_NE(plan.materials[3].measure_advice.find("saagen bench --scene ASSET"), std::string::npos) << plan.materials[3].measure_advice;
  EXPECT_NE(format_plan(catalogue, manifest, plan).find("  measure   no filter chosen on saagen's scenes"), std::string::npos);
}

// Switching from an engine's form is the same decision with that form as the baseline: on the
// curved scene forward-aniso-projected beats engine-hdrp in both metrics; on the normal-mapped one
// every form lowers LDR-FLIP and raises TDE against it, so nothing is offered.
TEST(OneAnswer, SwitchingFromAnEngineIsTheDecisionAgainstIt) {
  const std::vector<report::EngineSwitch> switches = report::engine_switches(small_table(), nullptr);
  ASSERT_EQ(switches.size(), 2u);
  EXPECT_EQ(switches[0].content, report::Content::curved);
  EXPECT_EQ(switches[0].configuration, "forward-aniso-projected/tail");
  EXPECT_EQ(switches[1].content, report::Content::normal_mapped);
  EXPECT_EQ(switches[1].configuration, "");
}

// Under TAA a table's by_content rows (measured without TAA) do not decide: without the table's
// own rows under TAA, saagen's committed TAA figures do (generator/data/advice.json, each
// configuration against none+taa), as the plan without a table.
TEST(OneAnswer, UnderTaaATablesRowsWithoutTaaDoNotDecide) {
  const measure::TradeTable trade = small_table();
  const MeasuredTradeTable table = parse_trade_table(report::trade_json(trade, report::summarize(trade), nullptr).dump(), "small.json");
  Manifest manifest = parse_manifest("name = \"s\"\ntargets = [\"glsl\"]\n[[material]]\nname = \"m\"\npath = \"deferred\"\n", "s.toml",
                                     Catalogue::builtin());
  EXPECT_EQ(plan_scene(Catalogue::builtin(), manifest, &table).materials.at(0).variant, "deferred-aniso");
  manifest.taa = true;
  const MaterialPlan taa = plan_scene(Catalogue::builtin(), manifest, &table).materials.at(0);
  EXPECT_NE(taa.reason.find("curved content under TAA in saagen's trade"), std::string::npos) << taa.reason;
  EXPECT_EQ(taa.variant, plan_scene(Catalogue::builtin(), manifest, nullptr).materials.at(0).variant);
  const AdviceMeasurement* committed = committed_advice().find("curved", true);
  ASSERT_NE(committed, nullptr);
  EXPECT_EQ(committed->baseline, "none+taa");
  const MaterialDecision made = decide_material(Catalogue::builtin(), manifest.materials.at(0), "vega10", committed->rows,
                                                committed_advice().forward_transported, "none+taa");
  const std::string chosen = made.decision.chosen ? made.candidates[*made.decision.chosen].configuration : "none";
  EXPECT_EQ(taa.variant, chosen.substr(0, chosen.find_first_of(":+/")));  // the configuration's variant
}

// A table measured with --taa carries its rows under TAA ("taa_by_content", each against
// none+taa): under TAA they decide, and the reason names the baseline.
TEST(OneAnswer, UnderTaaATablesRowsUnderTaaDecide) {
  const MeasuredTradeTable table = parse_trade_table(R"({"rows": [], "by_content": [
      {"content": "curved", "configuration": "none", "error": 0.03},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.02,
       "against_none": {"image": {"mean": -0.01, "low": -0.012, "high": -0.008}, "temporal": {"mean": -1, "low": -1.2, "high": -0.8}}}],
      "taa_by_content": [
      {"content": "curved", "configuration": "none", "error": 0.04},
      {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.05,
       "against_none": {"image": {"mean": 0.01, "low": 0.008, "high": 0.012}, "temporal": {"mean": 0.5, "low": 0.3, "high": 0.7}}},
      {"content": "curved", "configuration": "deferred-avg/tail", "error": 0.03,
       "against_none": {"image": {"mean": -0.01, "low": -0.012, "high": -0.008}, "temporal": {"mean": -1, "low": -1.2, "high": -0.8}}}]})",
                                                     "taa.json");
  ASSERT_EQ(table.taa_content_rows.size(), 3u);
  Manifest manifest = parse_manifest("name = \"s\"\ntargets = [\"glsl\"]\n[[material]]\nname = \"m\"\npath = \"deferred\"\n", "s.toml",
                                     Catalogue::builtin());
  EXPECT_EQ(plan_scene(Catalogue::builtin(), manifest, &table).materials.at(0).variant, "deferred-aniso");
  manifest.taa = true;
  const MaterialPlan taa = plan_scene(Catalogue::builtin(), manifest, &table).materials.at(0);
  EXPECT_EQ(taa.variant, "deferred-avg");
  EXPECT_NE(taa.reason.find("against none+taa"), std::string::npos) << taa.reason;
  EXPECT_NE(taa.reason.find("curved content under TAA in taa.json"), std::string::npos) << taa.reason;
}

// The decision's costs: the committed vega10 ISA model, the lobe's own row where it has one, else
// the variant's papers row plus the lobe's overhead on the form sharing its BRDF (deferred-avg's
// for the axis BRDF), and the tangent-free form without tangents.
TEST(OneAnswer, CostsAreTheCommittedIsaModel) {
  const std::vector<ContentRow> rows = {{"bump", "none", 0.3, 0.1, std::nullopt},
                                        {"bump", "deferred-aniso/tail", 0.2, 0.09, std::nullopt},
                                        {"bump", "deferred-max/tail", 0.2, 0.09, std::nullopt}};
  const auto cost_of = [&](const Material& material, std::size_t index) {
    return *decide_material(Catalogue::builtin(), material, "vega10", rows, false).candidates.at(index).cost_ratio;
  };
  Material forward = reference_material(RenderPath::forward, advice::Content::bumps);
  const double avg_tail_overhead = 1.155195681511471 - 1.105263157894737;
  EXPECT_NEAR(cost_of(forward, 0), 1.2388663967611335, 1e-9);  // 918 / 741
  EXPECT_NEAR(cost_of(forward, 1), 1.3427800269905532 + avg_tail_overhead, 1e-9);
  Material deferred = reference_material(RenderPath::deferred, advice::Content::bumps);  // no tangents
  EXPECT_NEAR(cost_of(deferred, 1), 1.1592442645074224 + avg_tail_overhead, 1e-9);
}

// Rows measured with the projected forward filters' transported wrappers cost those wrappers: their
// own ISA rows with the tail-preserving lobe; with the papers' lobe, the papers' wrapper plus the
// transported wrapper's overhead measured with the tail-preserving lobe. Other variants as before.
TEST(OneAnswer, TransportedRowsCostTheTransportedWrappers) {
  const std::vector<ContentRow> rows = {{"curved", "none", 0.3, 0.1, std::nullopt},
                                        {"curved", "forward-aniso-projected/tail", 0.2, 0.09, std::nullopt},
                                        {"curved", "forward-aniso-projected", 0.2, 0.09, std::nullopt},
                                        {"curved", "forward-axis-projected/tail", 0.2, 0.09, std::nullopt},
                                        {"curved", "forward-aniso-slope/tail", 0.2, 0.09, std::nullopt}};
  const Material forward = reference_material(RenderPath::forward, advice::Content::curved);
  const auto costs = [&](bool transported) {
    std::vector<double> out;
    for (const auto& candidate : decide_material(Catalogue::builtin(), forward, "vega10", rows, transported).candidates)
      out.push_back(*candidate.cost_ratio);
    return out;
  };
  const std::vector<double> papers = costs(false), transported = costs(true);
  ASSERT_EQ(papers.size(), 4u);
  ASSERT_EQ(transported.size(), 4u);
  // generator/data/isa_cost.json, vega10, one light.
  EXPECT_NEAR(papers[0], 1.1970310391363024, 1e-9);
  EXPECT_NEAR(transported[0], 1.4615384615384615, 1e-9);
  EXPECT_NEAR(transported[1], 1.2091767881241566 + (1.4615384615384615 - 1.1970310391363024), 1e-9);
  EXPECT_NEAR(transported[2], 1.4345479082321189, 1e-9);
  EXPECT_EQ(transported[3], papers[3]);  // the slope forms have no transported wrapper
}

// A table whose rows carry their comparison with no SAA with intervals is decided by the
// intervals, not the means: a lower mean whose interval spans 0 ties, and plans no filter.
TEST(OneAnswer, IntervalsInTheTableDecide) {
  const auto plan_with = [](const std::string& temporal) {
    const MeasuredTradeTable table = parse_trade_table(R"({"rows": [], "by_content": [
        {"content": "curved", "configuration": "none", "error": 0.03, "tde": 0.010},
        {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.02, "tde": 0.009,
         "against_none": {"image": {"mean": -0.01, "low": -0.012, "high": )" +
                                                           temporal + R"(},
                          "temporal": {"mean": -0.001, "low": -0.003, "high": 0.001}}}]})",
                                                       "intervals.json");
    const Manifest manifest = parse_manifest("name = \"s\"\ntargets = [\"glsl\"]\n[[material]]\nname = \"m\"\npath = \"deferred\"\n",
                                             "s.toml", Catalogue::builtin());
    return plan_scene(Catalogue::builtin(), manifest, &table).materials.at(0);
  };
  const MaterialPlan beats = plan_with("-0.008");  // image better beyond its interval, temporal tied
  EXPECT_EQ(beats.variant, "deferred-aniso");
  EXPECT_NE(beats.reason.find("image -0.01 [-0.012, -0.008]"), std::string::npos) << beats.reason;
  const MaterialPlan ties = plan_with("0.002");  // both intervals span 0
  EXPECT_EQ(ties.variant, "none");
  EXPECT_NE(ties.reason.find("ties"), std::string::npos) << ties.reason;
  EXPECT_THROW(parse_trade_table(R"({"rows": [], "by_content": [{"content": "curved", "configuration": "x", "error": 0.1,
                                     "against_none": {"image": {"mean": 1, "low": 2, "high": 3}}}]})",
                                 "bad.json"),
               Error);
}

// A comparison the bench marks unconverged (more ground-truth samples would reverse it) is a tie
// for the plan too, whatever its intervals: no filter.
TEST(OneAnswer, AnUnconvergedComparisonInTheTableIsATie) {
  const auto plan_with = [](const std::string& mark) {
    const MeasuredTradeTable table = parse_trade_table(R"({"rows": [], "by_content": [
        {"content": "curved", "configuration": "none", "error": 0.03},
        {"content": "curved", "configuration": "deferred-aniso/tail", "error": 0.02,
         "against_none": {"image": {"mean": -0.01, "low": -0.012, "high": -0.008},
                          "temporal": {"mean": -1, "low": -1.2, "high": -0.8})" +
                                                           mark + R"(}}]})",
                                                       "unconverged.json");
    const Manifest manifest = parse_manifest("name = \"s\"\ntargets = [\"glsl\"]\n[[material]]\nname = \"m\"\npath = \"deferred\"\n",
                                             "s.toml", Catalogue::builtin());
    return plan_scene(Catalogue::builtin(), manifest, &table).materials.at(0);
  };
  EXPECT_EQ(plan_with("").variant, "deferred-aniso");
  const MaterialPlan unconverged = plan_with(R"(, "unconverged": true)");
  EXPECT_EQ(unconverged.variant, "none") << unconverged.reason;
  EXPECT_NE(unconverged.reason.find("ties"), std::string::npos) << unconverged.reason;
  EXPECT_THROW(plan_with(R"(, "unconverged": 1)"), Error);
}

// `saagen bench --cost GPU.json` costs the verdict's decisions by the GPU's time ratios (at one
// light, as the trade renders) and carries them in its JSON, so that `saagen plan` of that table
// costs alike: on the curved scene deferred-aniso/tail costs 1.36x no SAA on the H200 (vega10's
// ISA model: 1.324x), so a deferred material's budget 1.35 takes it on vega10's model and not on
// the H200, and the verdict, the frontier and the plan name the device.
TEST(OneAnswer, AGpuTimingCostsTheVerdictAndThePlanAlike) {
  const std::filesystem::path timing_file = std::filesystem::path(SAAGEN_SOURCE_DIR) / "docs" / "data" / "h200" / "shading_4k_1l.json";
  measure::TradeTable trade = small_table();
  const auto json_of = [](const measure::TradeTable& t) { return report::trade_json(t, report::summarize(t), nullptr); };
  const MeasuredTradeTable isa_costed = parse_trade_table(json_of(trade).dump(), "isa.json");
  EXPECT_EQ(isa_costed.timing(), nullptr);
  trade.decision_timing = std::make_shared<const MeasuredTradeTable>(load_trade_table(timing_file));
  const MeasuredTradeTable gpu_costed = parse_trade_table(json_of(trade).dump(), "gpu.json");
  ASSERT_NE(gpu_costed.timing(), nullptr);
  EXPECT_EQ(gpu_costed.timing()->source_name, timing_file.string());
  EXPECT_EQ(gpu_costed.timing()->device_name(), "NVIDIA H200");
  EXPECT_NEAR(*gpu_costed.timing()->device_time_ratio("deferred-aniso/tail"),
              *trade.decision_timing->device_time_ratio("deferred-aniso/tail"), 1e-12);

  const std::string on_h200 = "at 1 light on NVIDIA H200 (" + timing_file.string() + ")";
  const std::vector<report::Recommendation> recs = report::recommend(trade);
  const report::Recommendation& deferred = verdict(recs, RenderPath::deferred, advice::Content::curved);
  EXPECT_EQ(deferred.configuration, "deferred-aniso/tail");
  EXPECT_NE(deferred.reason.find("1.36x no SAA's shading cost " + on_h200), std::string::npos) << deferred.reason;
  EXPECT_NE(report::format_frontier(trade).find("cost = NVIDIA H200 GPU time ratio to no SAA at 1 light"), std::string::npos);

  const Manifest manifest =
      parse_manifest("name = \"s\"\ntargets = [\"glsl\"]\n[[material]]\nname = \"m\"\npath = \"deferred\"\nbudget = 1.35\n", "s.toml",
                     Catalogue::builtin());
  const MaterialPlan by_isa = plan_scene(Catalogue::builtin(), manifest, &isa_costed).materials.at(0);
  EXPECT_EQ(by_isa.variant, "deferred-aniso") << by_isa.reason;  // 1.324x on vega10's model
  const MaterialPlan by_gpu = plan_scene(Catalogue::builtin(), manifest, &gpu_costed).materials.at(0);
  EXPECT_EQ(by_gpu.variant, "none") << by_gpu.reason;
  EXPECT_NE(by_gpu.reason.find(on_h200), std::string::npos) << by_gpu.reason;
}

// A table's "device_timing" must be a GPU's timings as the bench writes them: one line otherwise.
TEST(OneAnswer, ADeviceTimingThatIsNoGpusIsRefused) {
  const auto error_of = [](const std::string& timing) {
    try {
      parse_trade_table(R"({"rows": [], "device_timing": )" + timing + "}", "t.json");
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of(R"({"device": "NVIDIA H200", "rows": [{"variant": "no-saa", "cost_ratio": 1.0}]})"),
            "t.json: \"device_timing\" must be an object with a string \"source\" (as `saagen bench --cost FILE --json` writes it)");
  EXPECT_EQ(error_of(R"({"source": "a.json", "device": "NVIDIA H200", "rows": [], "device_timing": {}})"),
            "t.json: \"device_timing\" must be an object with a string \"source\" (as `saagen bench --cost FILE --json` writes it)");
  EXPECT_EQ(error_of(R"json({"source": "l.json", "device": "llvmpipe (LLVM 15.0.6, 256 bits) (CPU, Vulkan 1.3.230)",
                             "rows": [{"variant": "no-saa", "cost_ratio": 1.0}]})json"),
            "t.json: \"device_timing\": not a GPU's timings (no \"no-saa\" row with a \"cost_ratio\", or a CPU device); pass the "
            "file `saagen bench --cost FILE --json` writes");
}

}  // namespace

// The frontier the bench prints is the decision's candidates read by cost: cheapest first, each
// lower in image error than every cheaper one; the budget line is the decision within each budget.
TEST(OneAnswer, TheFrontierIsTheDecisionsCandidatesByCost) {
  const measure::TradeTable trade = small_table();
  const std::string text = report::format_frontier(trade);
  const auto block = text.find("  deferred, curved:\n");
  ASSERT_NE(block, std::string::npos) << text;
  const auto budgets = text.find("    at x", block);
  ASSERT_NE(budgets, std::string::npos) << text;
  const std::string lines = text.substr(block, text.find('\n', budgets) - block);
  EXPECT_NE(lines.find("deferred-aniso/tail"), std::string::npos) << lines;  // the decision's choice is on the frontier
  EXPECT_NE(lines.find("at x1.05 (the papers' overhead): none; at x1.25: deferred-aniso/tail; unlimited: deferred-aniso/tail"),
            std::string::npos)
      << lines;
}

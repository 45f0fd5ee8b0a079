// The exact-lobe rows (saagen bench --exact-lobe, "VARIANT/exact") are a yardstick that no target
// emits: the verdict never recommends one and the planner's per-content table never carries one,
// however well they measure.
#include "saagen/report/findings.hpp"
#include "saagen/report/report.hpp"

#include <gtest/gtest.h>

#include <string>

namespace measure = saagen::measure;
namespace report = saagen::report;

namespace {

measure::TradeRow row(measure::Variant variant, measure::Lobe lobe, double flip, double tde) {
  measure::TradeRow r;
  r.variant = variant;
  r.lobe = lobe;
  r.scene = measure::SceneId::torus;
  r.alpha = 0.01;
  r.flip_ldr = flip;
  r.tde = tde;
  return r;
}

// A torus table in which the exact lobe is the best configuration by far (as it measures).
measure::TradeTable torus_table() {
  measure::TradeTable table;
  table.config.scenes = {measure::SceneId::torus};
  table.config.alphas = {0.01};
  table.config.fresnel_modes = {false};
  table.rows = {row(measure::Variant::none, measure::Lobe::papers, 0.0101, 0.0045),
                row(measure::Variant::engine_godot, measure::Lobe::papers, 0.0166, 0.0051),
                row(measure::Variant::forward_aniso_projected, measure::Lobe::tail, 0.0098, 0.0030),
                row(measure::Variant::forward_aniso_projected, measure::Lobe::exact, 0.0014, 0.0015)};
  return table;
}

}  // namespace

TEST(MeasurementRows, AreNeverRecommendedNorGivenToThePlanner) {
  EXPECT_TRUE(report::is_measurement_configuration("forward-aniso-projected/exact"));
  EXPECT_TRUE(report::is_measurement_configuration("deferred-sum:geometric+hdrp/exact"));
  EXPECT_FALSE(report::is_measurement_configuration("forward-aniso-projected/tail"));
  EXPECT_FALSE(report::is_measurement_configuration("none"));

  const measure::TradeTable table = torus_table();
  const std::string verdict = report::format_verdict(table);
  EXPECT_NE(verdict.find("forward-aniso-projected/tail"), std::string::npos) << verdict;
  EXPECT_EQ(verdict.find("/exact"), std::string::npos) << verdict;

  const nlohmann::json json = report::trade_json(table, report::summarize(table), nullptr);
  int configurations = 0;
  for (const nlohmann::json& entry : json["by_content"]) {
    EXPECT_EQ(entry["configuration"].get<std::string>().find("/exact"), std::string::npos);
    ++configurations;
  }
  EXPECT_EQ(configurations, 3);  // none, the engine, the tail lobe
  // The rows themselves stay in the table, for scripts/beats_baselines.py exact.
  bool exact_case = false;
  for (const nlohmann::json& entry : json["cases"]) exact_case |= entry["configuration"] == "forward-aniso-projected/exact";
  EXPECT_TRUE(exact_case);
}

// saagen's one decision (saagen/decision.hpp): each rule asserts a value a wrong rule would change.
#include "saagen/decision.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace {

using namespace saagen::decision;

Comparison means(double image, double temporal, double lag = 0.0) { return {exact(image), exact(temporal), exact(lag)}; }

Candidate candidate(const char* name, double image, double temporal, std::optional<double> cost = 1.2, bool usable = true) {
  return {name, means(image, temporal), cost, usable};
}

TEST(Decision, OutcomeIsDecidedByTheIntervalsNotTheMeans) {
  EXPECT_EQ(outcome(means(-0.01, -0.001)), Outcome::beats);
  EXPECT_EQ(outcome(means(-0.01, 0.0)), Outcome::beats);  // one better, the other tied
  EXPECT_EQ(outcome(means(0.01, 0.0)), Outcome::loses);
  EXPECT_EQ(outcome(means(-0.01, 0.002)), Outcome::mixed);
  EXPECT_EQ(outcome(means(0.0, 0.0)), Outcome::ties);
  // A negative mean whose interval spans 0 is a tie, not a win.
  EXPECT_EQ(outcome({{-0.01, -0.03, 0.01}, {-0.002, -0.004, 0.0005}, {}}), Outcome::ties);
  EXPECT_EQ(outcome({{-0.01, -0.03, -0.001}, {0.002, -0.004, 0.005}, {}}), Outcome::beats);
  EXPECT_EQ(outcome({{-0.01, -0.03, -0.001}, {0.002, 0.001, 0.005}, {}}), Outcome::mixed);
  EXPECT_EQ(outcome({{0.01, 0.001, 0.03}, {0.002, -0.001, 0.005}, {}}), Outcome::loses);
}

TEST(Decision, OnlyWhatBeatsNoSaaIsEligible) {
  // The lowest image error loses in the temporal metric: it is never chosen; nothing else beats.
  const std::vector<Candidate> c = {candidate("forward-axis-projected/tail", -0.02, 0.0013),
                                    candidate("forward-aniso-projected:geometric/mapped", 0.001, 0.002)};
  const Decision d = decide(c, {});
  EXPECT_FALSE(d.chosen);
  EXPECT_EQ(d.outcomes, (std::vector<Outcome>{Outcome::mixed, Outcome::loses}));
  EXPECT_NE(d.reason.find("no filter: none of the 2 usable configurations beats no SAA"), std::string::npos) << d.reason;
  EXPECT_NE(d.reason.find("forward-axis-projected/tail"), std::string::npos) << d.reason;
}

TEST(Decision, AccuracyTakesTheLargestTemporalImprovementAmongThoseThatBeat) {
  // The temporal metric ranks (the bench's is ColorVideoVDP's JOD loss): "large" improves it most
  // among the two that beat; "mixed-but-best" improves it more but loses in the image metric.
  const std::vector<Candidate> c = {candidate("mixed-but-best", 0.001, -0.05), candidate("small", -0.001, -0.001),
                                    candidate("large", -0.0001, -0.005), candidate("unusable", -0.01, -0.01, 1.1, false)};
  const Decision d = decide(c, {});
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(*d.chosen, 2u);
  EXPECT_NE(d.reason.find("large"), std::string::npos);
  EXPECT_NE(d.reason.find("largest temporal improvement of the 2"), std::string::npos) << d.reason;
}

TEST(Decision, EqualTemporalImprovementsAreBrokenByTheImageMean) {
  const std::vector<Candidate> c = {candidate("a", -0.001, -0.004), candidate("b", -0.003, -0.004), candidate("c", -0.002, -0.004)};
  EXPECT_EQ(decide(c, {}).chosen, std::optional<std::size_t>(1));
}

TEST(Decision, ALateConfigurationIsNeverTaken) {
  // The largest temporal improvement is late (its lag lies above 0: closer to the ground truth's
  // previous frames): the next one is taken; a lag whose interval spans 0 is not late.
  std::vector<Candidate> c = {candidate("late", -0.01, -2.0), candidate("on-time", -0.01, -1.0)};
  c[0].against_none.lag = {4e-4, 1e-4, 7e-4};
  c[1].against_none.lag = {1e-4, -2e-4, 4e-4};
  EXPECT_TRUE(late(c[0].against_none));
  EXPECT_FALSE(late(c[1].against_none));
  EXPECT_EQ(decide(c, {}).chosen, 1u);
  // Lagging less than no SAA is no merit: the outcome ignores it.
  EXPECT_EQ(outcome(means(0.0, 0.0, -1.0)), Outcome::ties);
  // Only late candidates beat: no filter, and the reason says why.
  const Decision d = decide(std::span(c).first(1), {});
  EXPECT_FALSE(d.chosen);
  EXPECT_NE(d.reason.find("is late"), std::string::npos) << d.reason;
}

// A content's recommendation must lose on none of its content: a candidate that beats no SAA on
// the content's mean but loses on one of its scenes is set aside, whatever its mean.
TEST(Decision, WhatLosesOnASceneOfTheContentIsNeverTaken) {
  Candidate bake = candidate("deferred-aniso:geometric+hdrp/tail", -0.005, -1.9);
  bake.loses_on = {"pmndrs-0014"};
  const Candidate plain = candidate("deferred-aniso/tail", -0.004, -1.7);
  const Decision d = decide(std::vector<Candidate>{bake, plain}, {});
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(*d.chosen, 1u);
  EXPECT_EQ(d.outcomes[0], Outcome::beats);  // on the mean it still beats; the rule sets it aside
  EXPECT_NE(d.reason.find("set aside, more accurate on the mean but losing to no SAA on a scene of the content: "
                          "deferred-aniso:geometric+hdrp/tail (loses on pmndrs-0014)"),
            std::string::npos)
      << d.reason;
  // Alone, it leaves no filter, and the reason names the scene.
  const Decision alone = decide(std::vector<Candidate>{bake}, {});
  EXPECT_FALSE(alone.chosen);
  EXPECT_NE(alone.reason.find("loses to it beyond the interval on a scene of the same content (deferred-aniso:geometric+hdrp/tail "
                              "loses on pmndrs-0014)"),
            std::string::npos)
      << alone.reason;
  // Speed obeys the same rule: the cheaper form that loses on a scene is not the cheapest eligible.
  Candidate cheap = candidate("deferred-avg:geometric+hdrp/tail", -0.003, -1.8, 1.1);
  cheap.loses_on = {"pmndrs-0014"};
  const Decision speed = decide(std::vector<Candidate>{cheap, candidate("deferred-avg/tail", -0.003, -1.7, 1.15),
                                                       candidate("deferred-aniso/tail", -0.004, -1.7, 1.7)},
                                {Prefer::speed, std::nullopt, "no SAA"});
  ASSERT_TRUE(speed.chosen);
  EXPECT_EQ(*speed.chosen, 1u) << speed.reason;
}

TEST(Decision, ALeadInsideTheIntervalIsATieAndTheCheaperOfATieWins) {
  // "aniso" has the largest temporal improvement on the mean, but "axis" is worse than it beyond
  // the interval in neither metric (the bench's paired comparison of the two): a tie, and the
  // cheaper "axis" is taken. "slope" is cheaper still but worse than "aniso": not a tie.
  Candidate aniso = candidate("forward-aniso-projected/tail", -0.012, -1.78, 1.385);
  Candidate axis = candidate("forward-axis-projected/tail", -0.0085, -1.63, 1.30);
  aniso.not_worse_than = {"forward-axis-projected/tail"};
  axis.not_worse_than = {"forward-aniso-projected/tail"};
  const Candidate slope = candidate("forward-axis-slope/tail", -0.002, -0.9, 1.16);
  const Decision d = decide(std::vector<Candidate>{aniso, axis, slope}, {});
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(*d.chosen, 1u) << d.reason;
  EXPECT_NE(
      d.reason.find("the lowest cost of the 3 usable configurations that do, as accurate as the most accurate and beaten by none of its "
                    "ties; it ties with "
                    "forward-aniso-projected/tail"),
      std::string::npos)
      << d.reason;
  // Without the pairing (a table that has none) the mean decides, as before.
  axis.not_worse_than.clear();
  EXPECT_EQ(decide(std::vector<Candidate>{aniso, axis, slope}, {}).chosen, std::optional<std::size_t>(0));
  // A tie that costs the same (within kCostTieTolerance) or more leaves the most accurate one.
  axis.not_worse_than = {"forward-aniso-projected/tail"};
  axis.cost_ratio = 1.385 * (1.0 + kCostTieTolerance / 2);
  EXPECT_EQ(decide(std::vector<Candidate>{aniso, axis}, {}).chosen, std::optional<std::size_t>(0));
  // Where the most accurate one's cost is unknown, nothing is known to be cheaper: it.
  aniso.cost_ratio.reset();
  axis.cost_ratio = 1.0;
  EXPECT_EQ(decide(std::vector<Candidate>{aniso, axis}, {}).chosen, std::optional<std::size_t>(0));
  // A tie that is not itself eligible (it loses on a scene) is never taken.
  aniso.cost_ratio = 1.385;
  axis.loses_on = {"torus"};
  EXPECT_EQ(decide(std::vector<Candidate>{aniso, axis}, {}).chosen, std::optional<std::size_t>(0));
}

TEST(Decision, AccuracyNeverTakesATieThatAnotherTieBeatsInThePairing) {
  // "deferred" has the largest temporal improvement on the mean, and "forward" ties with it on the
  // video metric but is better beyond the interval in image error: "forward" names "deferred" in
  // its not_worse_than, "deferred" does not name "forward". At costs equal within
  // kCostTieTolerance the mean would take "deferred"; the pairing says "forward" is better.
  Candidate deferred = candidate("deferred-aniso:geometric/tail", -0.0003, -2.0, 1.514);
  Candidate forward = candidate("forward-aniso-projected/tail", -0.086, -1.9, 1.506);
  forward.not_worse_than = {"deferred-aniso:geometric/tail"};
  const Decision d = decide(std::vector<Candidate>{deferred, forward}, {});
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(*d.chosen, 1u) << d.reason;
  EXPECT_NE(d.reason.find("paired with deferred-aniso:geometric/tail"), std::string::npos) << d.reason;
  EXPECT_NE(d.reason.find("better beyond the 95 % interval in one metric and worse in neither"), std::string::npos) << d.reason;
  // Where the pairing is a tie both ways, the mean decides the equal costs again.
  deferred.not_worse_than = {"forward-aniso-projected/tail"};
  EXPECT_EQ(decide(std::vector<Candidate>{deferred, forward}, {}).chosen, std::optional<std::size_t>(0));
  // A cheaper tie that a dearer tie beats is set aside for the dearer one: "mid" and "cheap" both
  // tie with "deferred" both ways, and "mid" beats "cheap" in their pairing.
  Candidate mid = candidate("deferred-avg/tail", -0.02, -1.95, 1.3);
  Candidate cheap = candidate("deferred-avg:geometric/tail", -0.001, -1.92, 1.1);
  deferred.not_worse_than = {"deferred-avg/tail", "deferred-avg:geometric/tail"};
  mid.not_worse_than = {"deferred-aniso:geometric/tail", "deferred-avg:geometric/tail"};
  cheap.not_worse_than = {"deferred-aniso:geometric/tail"};
  EXPECT_EQ(decide(std::vector<Candidate>{deferred, mid, cheap}, {}).chosen, std::optional<std::size_t>(1));
  // Pairings that go round in a circle set nothing aside: each of "mid", "cheap" and "third"
  // beats "deferred" and the next of them, so every member is beaten by another; then the group
  // is kept whole and its cheapest is taken.
  Candidate third = candidate("deferred-sum/tail", -0.01, -1.93, 1.2);
  deferred.not_worse_than.clear();
  mid.not_worse_than = {"deferred-aniso:geometric/tail", "deferred-avg:geometric/tail"};
  cheap.not_worse_than = {"deferred-aniso:geometric/tail", "deferred-sum/tail"};
  third.not_worse_than = {"deferred-aniso:geometric/tail", "deferred-avg/tail"};
  const std::vector<Candidate> circle{deferred, mid, cheap, third};
  EXPECT_EQ(decide(circle, {}).chosen, std::optional<std::size_t>(2));
}

TEST(Decision, SpeedTakesTheCheapestThatBeats) {
  const std::vector<Candidate> c = {candidate("deferred-aniso/tail", -0.02, -0.002, 1.874),
                                    candidate("deferred-avg/tail", -0.001, -0.0001, 1.355),
                                    candidate("deferred-sum/tail", -0.002, -0.0001, 1.349), candidate("deferred-avg", 0.01, 0.001, 1.105)};
  const Decision d = decide(c, {Prefer::speed, std::nullopt});
  ASSERT_TRUE(d.chosen);
  // deferred-sum/tail and deferred-avg/tail cost the same within 1 %: the more accurate of them.
  EXPECT_EQ(*d.chosen, 2u);
  EXPECT_NE(d.reason.find("lowest cost"), std::string::npos);
}

TEST(Decision, SpeedNeverTakesAnEqualCostTieThatAnotherBeatsInThePairing) {
  // The bump plane's forward candidates: the two deferred-aniso feeds cost the same (one kernel
  // on another normal), the transported forward form more. Speed skips that most expensive form;
  // of the two at the lowest cost the mean would take "geometric" (the larger temporal
  // improvement), but "mapped" ties with it on the video metric and is better beyond the interval
  // in image error, so the pairing takes "mapped", as accuracy would among the two.
  Candidate geometric = candidate("deferred-aniso:geometric/tail", -0.0003, -0.004, 1.433);
  Candidate mapped = candidate("deferred-aniso/tail", -0.086, -0.001, 1.433);
  const Candidate dearest = candidate("forward-aniso-projected/tail", -0.086, -0.002, 1.463);
  mapped.not_worse_than = {"deferred-aniso:geometric/tail"};
  const Decision d = decide(std::vector<Candidate>{geometric, mapped, dearest}, {Prefer::speed, std::nullopt});
  ASSERT_TRUE(d.chosen);
  EXPECT_EQ(*d.chosen, 1u) << d.reason;
  // Where they tie both ways, the mean decides between the equal costs again.
  geometric.not_worse_than = {"deferred-aniso/tail"};
  EXPECT_EQ(decide(std::vector<Candidate>{geometric, mapped, dearest}, {Prefer::speed, std::nullopt}).chosen,
            std::optional<std::size_t>(0));
}

TEST(Decision, SpeedNeverTakesTheMostExpensiveFormUnlessItIsTheOnlyOne) {
  // Only the most expensive usable form beats no SAA: speed plans no filter.
  const std::vector<Candidate> c = {candidate("deferred-aniso/tail", -0.02, -0.002, 1.874),
                                    candidate("deferred-avg/tail", 0.02, 0.001, 1.355)};
  const Decision d = decide(c, {Prefer::speed, std::nullopt});
  EXPECT_FALSE(d.chosen);
  EXPECT_NE(d.reason.find("most expensive form"), std::string::npos) << d.reason;
  EXPECT_EQ(decide(c, {}).chosen, std::optional<std::size_t>(0));  // accuracy takes it
  // The only usable candidate may be taken.
  const std::vector<Candidate> only = {candidate("deferred-aniso/tail", -0.02, -0.002, 1.874),
                                       candidate("forward-aniso-projected/tail", -0.03, -0.002, 1.385, false)};
  EXPECT_EQ(decide(only, {Prefer::speed, std::nullopt}).chosen, std::optional<std::size_t>(0));
}

TEST(Decision, ABudgetCapsTheCost) {
  const std::vector<Candidate> c = {candidate("expensive", -0.02, -0.002, 1.874), candidate("mid", -0.01, -0.001, 1.385),
                                    candidate("cheap", -0.001, -0.001, 1.105)};
  EXPECT_EQ(decide(c, {Prefer::accuracy, 1.5}).chosen, std::optional<std::size_t>(1));
  EXPECT_EQ(decide(c, {Prefer::accuracy, 1.9}).chosen, std::optional<std::size_t>(0));
  const Decision none = decide(c, {Prefer::accuracy, 1.05});
  EXPECT_FALSE(none.chosen);
  EXPECT_NE(none.reason.find("budget 1.05"), std::string::npos) << none.reason;
}

// Over the budget, a cost is printed with the digits that tell it from the budget, which is
// printed as given: 1.3333 against 1.33 reads 1.333x, not 1.33x.
TEST(Decision, ACostOverTheBudgetReadsAboveIt) {
  const std::vector<Candidate> c = {candidate("dear", -0.02, -0.002, 1.3333), candidate("cheap", 0.01, 0.01, 1.105)};
  const Decision close = decide(c, {Prefer::accuracy, 1.33});
  EXPECT_FALSE(close.chosen);
  EXPECT_NE(close.reason.find("costs more than the budget 1.33: dear ("), std::string::npos) << close.reason;
  EXPECT_NE(close.reason.find("; 1.333x no SAA's shading cost"), std::string::npos) << close.reason;
  const Decision finer = decide(c, {Prefer::accuracy, 1.333});
  EXPECT_NE(finer.reason.find("costs more than the budget 1.333: "), std::string::npos) << finer.reason;
  EXPECT_NE(finer.reason.find("; 1.3333x no SAA's shading cost"), std::string::npos) << finer.reason;
  const Decision far = decide(c, {Prefer::accuracy, 1.2});
  EXPECT_NE(far.reason.find("; 1.33x no SAA's shading cost"), std::string::npos) << far.reason;
}

TEST(Decision, ACandidateWithoutACostIsNotTakenForSpeed) {
  const std::vector<Candidate> c = {candidate("unknown", -0.02, -0.002, std::nullopt), candidate("known", -0.001, -0.001, 1.3),
                                    candidate("dear", 0.01, 0.01, 1.9)};
  EXPECT_EQ(decide(c, {Prefer::speed, std::nullopt}).chosen, std::optional<std::size_t>(1));
  EXPECT_EQ(decide(c, {}).chosen, std::optional<std::size_t>(0));
}

TEST(Decision, NothingUsableIsNoFilter) {
  const std::vector<Candidate> c = {candidate("x", -0.02, -0.002, 1.2, false)};
  const Decision d = decide(c, {});
  EXPECT_FALSE(d.chosen);
  EXPECT_EQ(d.reason, "no filter: none of the 1 measured configurations can be used here");
  const Decision empty = decide(std::vector<Candidate>{}, {});
  EXPECT_FALSE(empty.chosen);
  EXPECT_EQ(empty.reason, "no filter: no configuration was measured against no SAA here");
}

TEST(Decision, DescribePrintsTheIntervalOnlyWhenThereIsOne) {
  EXPECT_EQ(describe(exact(-0.0041)), "-0.0041");
  EXPECT_EQ(describe({-0.0041, -0.005, -0.0032}), "-0.0041 [-0.005, -0.0032]");
}

}  // namespace

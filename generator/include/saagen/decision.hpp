// saagen's one decision: given what each configuration a material (or a render path and content
// type) can use measured against no SAA, which one to use, or no filter. The bench's verdict
// (report/src/findings.cpp), the report, `saagen plan` with and without a trade table
// (saagen/scene/planner.hpp) and, through the bench's JSON, the scripts all read it; nothing
// else decides.
//
// A comparison is a configuration's error minus no SAA's on the same content (lower is better),
// for an image metric and a temporal metric, each with a 95 % interval. Where a table carries
// only means (today's trade JSON: LDR-FLIP and TDE means), low = high = mean
// (comparison_against in saagen/scene/cost_tables.hpp is the one adapter).
//
// The rules (decide()):
//   - outcome(): a metric is better when its whole interval lies below 0 (high < 0), worse when
//     it lies above 0 (low > 0), else tied. beats: no metric worse and at least one better;
//     loses: the mirror; mixed: one better and one worse; ties: every interval spans 0.
//   - Only usable candidates that beat no SAA, are not late (late(): they follow the ground
//     truth more than half a frame late beyond the interval), lose on none of the scenes their
//     comparison pools (Candidate::loses_on), and cost at most the budget when one is set, are
//     eligible; none eligible: no filter, with the reason.
//   - accuracy: the eligible one with the largest improvement in the temporal metric (the most
//     negative temporal mean), equal temporal means broken by the image mean, then by the order
//     of the candidates. The temporal metric ranks because the bench's is the video metric,
//     ColorVideoVDP's JOD of the animation (the field's perceptual video metric, Mantiuk et al.
//     2024), so the verdict orders configurations as it does; the image metric only has to be no
//     worse (beats). A lead inside the interval is a tie, not a win: the eligible candidates whose
//     paired comparison with that most accurate one is worse beyond the interval in neither
//     metric (Candidate::not_worse_than names it) are as accurate as it. Of it and them, any that
//     another of them beats in their paired comparison (better beyond the interval in one metric,
//     worse in neither: one names the other, the other does not name it) is set aside, and of
//     the rest the cheapest is taken (as for speed, but the most expensive form is allowed;
//     equal costs: the more accurate by the mean); where the most accurate one's cost is
//     unknown, the most accurate of the rest by the mean.
//   - speed: the cheapest eligible one (costs within kCostTieTolerance are equal, and of equals
//     the one accuracy would take among them: a tie that another of them beats in the pairing is
//     set aside); never the most expensive form among the usable candidates unless it is the only
//     usable candidate. A candidate without a known cost is never taken for speed.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace saagen::decision {

// configuration - baseline, with its 95 % interval (low <= mean <= high); lower is better.
struct Difference {
  double mean = 0, low = 0, high = 0;
};
// A difference known only by its mean (low = high = mean).
constexpr Difference exact(double mean) { return {mean, mean, mean}; }

enum class Outcome { beats, ties, loses, mixed };
std::string_view name(Outcome outcome);  // "beats", "ties", "loses", "mixed"

struct Comparison {
  Difference image;     // image metric (today: mean LDR-FLIP)
  Difference temporal;  // temporal metric (the bench's: 10 - ColorVideoVDP's JOD; older tables: TDE or flicker error)
  // The configuration's own lag, not a difference (the bench's report/comparison.hpp, lag_of):
  // above 0 beyond the interval, its frames are closer to the ground truth's previous frames than
  // to their own, i.e. more than half a frame late (latency, ghosting). Not a merit but a gate:
  // a late configuration is never taken. Tables without it: exact(0), never late.
  Difference lag;
  // The call would reverse (beats <-> loses or mixed) once the bias the ground truth's finite
  // samples leave is taken out (the bench's report/comparison.hpp): more samples would change it,
  // so it is a tie whatever the intervals say.
  bool unconverged = false;
};
// Whether the comparison says the configuration is late (its lag lies above 0 beyond the interval).
bool late(const Comparison& comparison);
Outcome outcome(const Comparison& comparison);

struct Candidate {
  std::string configuration;  // as `saagen bench` names it: VARIANT[:FEED][+PREFILTER][/LOBE]
  Comparison against_none;
  // Shading cost over no SAA (the vega10 ISA inverse-throughput ratio where known); nullopt: unknown.
  std::optional<double> cost_ratio;
  bool usable = true;  // whether the material (or path) can use it at all
  // Where the comparison pools several scenes (a content type's): the scenes on which the
  // configuration loses to the baseline beyond the interval in either metric (loses or mixed
  // there). A content's recommendation must lose on none of its content, so such a candidate is
  // never taken, whatever its mean.
  std::vector<std::string> loses_on = {};
  // The configurations this one is worse than beyond the interval in neither metric, paired on the
  // same cells (the bench's comparison of the two; empty where unknown): where one of them is the
  // most accurate candidate by the mean, this one ties with it, and the cheaper of the two wins.
  // The bench pairs every eligible candidate with every other, so where A names B and B does not
  // name A, A beats B in their paired comparison.
  std::vector<std::string> not_worse_than = {};
};

enum class Prefer { accuracy, speed };
struct Preference {
  Prefer prefer = Prefer::accuracy;
  std::optional<double> budget;  // at most this cost ratio over no SAA
  // What the comparisons are against, as the reasons print it ("none+taa" under TAA).
  std::string baseline = "no SAA";
};

// Costs within this fraction of each other rank as equal (one instruction of ACO's static
// estimate is ~0.5 % of these shaders; the same tolerance as the planner's kIsaTieTolerance).
inline constexpr double kCostTieTolerance = 0.01;

struct Decision {
  std::optional<std::size_t> chosen;  // index into the candidates; nullopt: no filter
  std::string reason;                 // one sentence: what was chosen and why, or why nothing was
  std::vector<Outcome> outcomes;      // per candidate, its outcome against no SAA
};

// `cost_basis`: how the costs were measured, as the reasons print it after "no SAA's shading
// cost" (the planner: "at 4 lights"); empty: nothing.
Decision decide(std::span<const Candidate> candidates, const Preference& preference, std::string_view cost_basis = {});

// "+0.0012" or "-0.0041 [-0.0050, -0.0032]": a difference as the reasons print it.
std::string describe(const Difference& difference);

}  // namespace saagen::decision

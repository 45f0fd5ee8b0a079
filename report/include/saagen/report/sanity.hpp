// The sanity suite: the verdict metrics must rank results whose ranking is known before they
// rank any configuration (trade.hpp, SanityResult). Per scene, over its materials (no Fresnel):
//
//   best             no result beats the ground truth with another seed, and none made from fewer
//                    samples (1-spp no SAA, blurred, frozen, no highlight) beats the one with a
//                    quarter of its samples ("beats": better beyond the interval in one metric and
//                    worse in none, the verdict's rule);
//   clearly worse    on every scene where the ground truth moves (frozen's flicker error, the
//                    ground truth's pooled motion, lies above another seed's): frozen and
//                    no-highlight are worse than the quarter-sample ground truth beyond the
//                    interval in at least one metric, and delayed is worse than the frames it is
//                    made of shown on time (another seed), in the image or temporal metric or the
//                    lag (animation_error.hpp);
//   stable           per alpha: the verdict calls no comparison with no SAA whose standing
//                    reverses (beats <-> loses or mixed) once the bias of the ground truth's
//                    samples is taken out (Richardson extrapolation from its reading against the
//                    quarter-sample ground truth). Where one does, more samples would change that
//                    comparison: the ground truth has not converged there, and the verdict reads
//                    it as a tie (comparison.hpp, PairedComparison::unconverged; docs/TEMPORAL.md).
//                    In a table with +taa rows, the same for each configuration under TAA against
//                    TAA alone (none+taa), the verdict under TAA;
//   never wins       entered as configurations beside every measured one (blurred too), no
//                    degenerate result (delayed, frozen, no highlight) is the configuration the
//                    verdict would choose against no SAA on the scene (the decision's rule: among
//                    those that beat no SAA and are not late, the best temporal error, then image
//                    error). The blurred result is the converged animation blurred by 1 px, what a
//                    pixel-footprint filter aims at: where it is chosen, the table says so.
// All comparisons are paired, frame by frame, against the first ground-truth seed (the results are
// made from the second seed's frames and a third seed's).
#pragma once

#include "saagen/measure/trade.hpp"
#include "saagen/report/comparison.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace saagen::report {

struct SanityEntry {
  std::string result;        // a sanity result's name, or "none" (1-spp no SAA)
  double image_error = 0.0;  // mean over the scene's materials
  double flicker_error = 0.0;
  MetricDifference image_vs_quarter, flicker_vs_quarter;  // against the quarter-sample ground truth
  double lag = 0.0;                                       // mean lag (animation_error.hpp)
};

// A configuration whose standing against no SAA on one cell moves once the ground truth's bias is
// taken out (the stable rule): "beats", "ties" or "against" (loses or mixed).
struct StandingMove {
  std::string configuration;
  std::string standing;      // as the verdict reads it
  std::string extrapolated;  // with the bias taken out
};

// The stable rule at one alpha: the configurations compared with no SAA (under TAA: the +taa ones
// with none+taa), those whose standing moves, those among them that reverse (beats <-> against),
// and those of these the verdict still calls (the rule's failures; the verdict reads them as ties).
struct Convergence {
  double alpha = 0.0;
  bool taa = false;
  int comparisons = 0;
  std::vector<StandingMove> moved;
  std::vector<std::string> reversed;  // configuration ids
  bool converged = false;             // none reversed
  std::vector<std::string> called;    // reversed, yet not read as a tie by the verdict
};

struct SceneSanity {
  measure::SceneId scene = measure::SceneId::sphere;
  bool moves = false;  // the ground truth moves (see the top of this file)
  // The temporal metric is the video error, 10 - ColorVideoVDP's JOD (comparison.hpp,
  // temporal_metric); else the flicker error. SanityEntry's flicker fields then hold it.
  bool video = false;
  std::vector<SanityEntry> entries;
  std::vector<std::string> failures;           // one line per broken rule; empty: passed
  std::string verdict_choice;                  // the verdict's choice with the degenerate results entered ("": no filter)
  std::vector<Convergence> convergence;        // per alpha
  std::vector<double> unconverged_alphas;      // the alphas where a comparison reverses (read as ties)
  std::vector<double> unconverged_taa_alphas;  // the same for the verdict under TAA
};

// Every scene of the table that has sanity rows.
std::vector<SceneSanity> check_sanity(const measure::TradeTable& table);
// The suite's table (one block per scene) and a last line: passed, or how many rules failed.
std::string format_sanity(const std::vector<SceneSanity>& scenes);
// One line naming the cells (scene, alpha) where a comparison with no SAA has not converged (the
// stable rule's reversals, read as ties), for the end of the verdict ("" when there are none).
std::string format_unconverged(const std::vector<SceneSanity>& scenes);
// The same for `saagen bench --json` ("sanity_checks").
nlohmann::json sanity_json(const std::vector<SceneSanity>& scenes);

}  // namespace saagen::report

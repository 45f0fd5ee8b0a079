// The short verdict as lines of text: per render path and content, what to use and by how much it
// beats no SAA and the best engine form, then plainly where it loses. Printed last by
// `saagen bench` and `saagen report` (terminal.hpp), and at the top of the report (pages.hpp).
#pragma once

#include "saagen/measure/trade.hpp"
#include "saagen/report/findings.hpp"

#include <string>
#include <vector>

namespace saagen::report {

inline constexpr const char* kVerdictTitle = "Verdict: what to use per render path and content";
// The verdict's note: what its comparisons and means are, and its image and temporal metrics
// (temporal_metric_description: the video error where the table has it).
std::string verdict_note(const measure::TradeTable& table);

// Verdicts grouped by render path, then content type.
std::vector<Verdict> ordered_verdicts(const measure::TradeTable& table);

// The verdict lines of one recommendation: the headline, then where it loses (or that it does not).
std::vector<std::string> verdict_lines(const Verdict& v);

inline constexpr const char* kByAlphaTitle = "At one roughness: the decision per measured alpha";
inline constexpr const char* kByAlphaNote =
    "what `saagen plan` gives a material whose `roughness` is sqrt(alpha): the same decision, with a configuration that loses to "
    "no SAA beyond its interval on any of the content's scenes at that alpha set aside; none: no filter";

// Per render path and content type, "CONTENT, PATH: alpha A X; alpha B Y; ..." (recommend_by_alpha).
std::vector<std::string> by_alpha_lines(const measure::TradeTable& table);
// The same lines of given decisions (recommend_taa_by_alpha under TAA).
std::vector<std::string> by_alpha_lines(const std::vector<AlphaRecommendation>& recs);

}  // namespace saagen::report

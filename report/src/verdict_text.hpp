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
inline constexpr const char* kVerdictNote =
    "the decision's comparison with no SAA, paired, 95 % intervals, then means over the content's scenes and alphas, no Fresnel; "
    "lower is better; image error = LDR-FLIP of every animation frame, flicker error = pooled frame-to-frame change against the "
    "ground truth's (docs/TEMPORAL.md); % = change from the baseline";

// Verdicts grouped by render path, then content type.
std::vector<Verdict> ordered_verdicts(const measure::TradeTable& table);

// The verdict lines of one recommendation: the headline, then where it loses (or that it does not).
std::vector<std::string> verdict_lines(const Verdict& v);

}  // namespace saagen::report

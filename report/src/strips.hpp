// The report's image strips: per scene, the ground truth, no SAA, the best engine form and the
// recommendations, at the alpha where no SAA errs most (largest LDR-FLIP). The report opens with
// these and the verdict.
#pragma once

#include "saagen/measure/trade.hpp"
#include "saagen/report/findings.hpp"

#include <string>
#include <vector>

namespace saagen::report {

// A PNG the report shows with a caption: its file name, the caption and the PNG bytes.
struct Strip {
  std::string file;
  std::string caption;
  std::string png;
};

// "strip_<scene>.png"
std::string strip_name(measure::SceneId scene);

// One strip per scene of the table that has images, with the columns the verdicts (`all`) name.
std::vector<Strip> strips(const measure::TradeTable& table, const std::vector<Verdict>& all);

}  // namespace saagen::report

// The report's plots (SVG): the trade of one content type and render path as a user reads it.
#pragma once

#include "saagen/report/findings.hpp"

#include <string>

namespace saagen::report {

// "trade_<content>_<path>.svg"
std::string trade_plot_name(Content content, Path path);
std::string trade_plot_name(const ContentTrade& trade);

// Cost (the planner's ratio to no SAA) against image error minus no SAA's, lower is better: the
// frontier labelled in a column beside the plot (leader lines, no label over another) with each
// point's 95 % interval; every other usable configuration an unlabelled grey dot; the engines'
// shipped forms as orange diamonds; no SAA the point (1, 0) on its dashed line; saagen's choice
// ringed.
std::string trade_plot_svg(const ContentTrade& trade);

}  // namespace saagen::report

// The report's strips under TAA: per scene, at the alpha where none+taa errs most (largest
// LDR-FLIP of the animation), a crop of the animation's last frame (flicker resolution) enlarged:
// the ground truth, none+taa, the best saagen configuration and the best engine form under TAA
// (taa_comparisons, by their scene means), captioned with that case's figures.
#pragma once

#include "strips.hpp"

#include "saagen/measure/trade.hpp"
#include "saagen/report/taa_summary.hpp"

#include <optional>
#include <string>

namespace saagen::report {

// "taa_<scene>.png"
std::string taa_strip_name(measure::SceneId scene);

// The strip of the comparison's scene from the table with its +taa rows and taa_images; nullopt
// when the table holds no none+taa image of the scene.
std::optional<Strip> taa_strip(const measure::TradeTable& taa, const TaaComparison& comparison);

}  // namespace saagen::report

// The report's PNG sheets: images beside the ground truth, labelled, over false-colour
// difference maps. The strips (strips.hpp, taa_strips.hpp) are sheets of a few chosen columns.
#pragma once

#include "saagen/measure/trade.hpp"

#include <string>
#include <vector>

namespace saagen::report {

// A labelled image (PNG tile) beside the ground truth.
struct Tile {
  std::string label;
  const measure::Image* image;
};

// One sheet (PNG bytes): a label band, then row 0 the ground truth and each tile, row 1 an empty
// cell then the difference maps; a 2-pixel grey gutter between tiles.
std::string grid_png(const measure::Image& reference, const std::vector<Tile>& tiles);

// A rendered image's configuration id (measure::configuration_id).
std::string configuration_of(const measure::ImageSet::Rendered& rendered);

// Every configuration of a (scene, material) beside the ground truth, and the sheet's file name
// ("sheet_<scene>_alpha<alpha>.png").
std::string sheet_png(const measure::ImageSet& set);
std::string sheet_name(const measure::ImageSet& set);

}  // namespace saagen::report

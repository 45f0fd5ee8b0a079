// The report's PNG sheets (see sheets.hpp).
#include "sheets.hpp"

#include "font.hpp"

#include "saagen/report/png.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace saagen::report {
namespace {

// Display values: Reinhard x / (1 + x) (the tonemapped metric's operator), then the
// sRGB transfer function. Difference maps: the tonemapped difference variant - ground truth,
// red where the variant is brighter, blue where darker, full colour at |d| >= 0.25.

constexpr double difference_full_scale = 0.25;

std::uint8_t to_byte(double value) { return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0)); }

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

Rgb display(double radiance) {
  const std::uint8_t v = to_byte(measure::display_value(radiance));
  return {v, v, v};
}

Rgb difference_colour(double radiance, double reference) {
  const double d = (measure::tonemap(radiance) - measure::tonemap(reference)) / difference_full_scale;
  const double m = measure::srgb_encode(std::min(std::fabs(d), 1.0));
  return d >= 0.0 ? Rgb{to_byte(m), 0, 0} : Rgb{0, 0, to_byte(m)};
}

// Images of 256 px and more are shown at half size (2x2 box) to keep the report light.
int display_scale(const measure::Image& image) { return image.width >= 256 ? 2 : 1; }

double box(const measure::Image& image, int x, int y, int scale) {
  double sum = 0.0;
  for (int dy = 0; dy < scale; ++dy)
    for (int dx = 0; dx < scale; ++dx) sum += image.at(x * scale + dx, y * scale + dy);
  return sum / (scale * scale);
}

}  // namespace

std::string grid_png(const measure::Image& reference, const std::vector<Tile>& tiles) {
  const int scale = display_scale(reference);
  const int tile_w = reference.width / scale, tile_h = reference.height / scale, gutter = 2;
  const int band = kLabelLines * kLabelLineHeight + 4;
  const int columns = 1 + static_cast<int>(tiles.size());
  const int width = columns * tile_w + (columns - 1) * gutter, height = band + 2 * tile_h + gutter;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width) * height * 3, 96);
  for (std::size_t i = 0; i < static_cast<std::size_t>(width) * band * 3; ++i) pixels[i] = 32;
  const auto put = [&](int column, int row, int x, int y, Rgb colour) {
    const std::size_t index = (static_cast<std::size_t>(band + row * (tile_h + gutter) + y) * width + column * (tile_w + gutter) + x) * 3;
    pixels[index] = colour.r, pixels[index + 1] = colour.g, pixels[index + 2] = colour.b;
  };
  const auto label = [&](int column, const std::string& text) {
    const std::vector<std::string> lines = wrap_label(text, tile_w - 4);
    for (std::size_t l = 0; l < lines.size() && l < kLabelLines; ++l)
      draw_text(pixels, width, height, column * (tile_w + gutter) + 2, 2 + static_cast<int>(l) * kLabelLineHeight, lines[l]);
  };
  label(0, "ground truth");
  for (std::size_t k = 0; k < tiles.size(); ++k) label(static_cast<int>(k) + 1, tiles[k].label);
  for (int y = 0; y < tile_h; ++y) {
    for (int x = 0; x < tile_w; ++x) {
      const double value_reference = box(reference, x, y, scale);
      put(0, 0, x, y, display(value_reference));
      put(0, 1, x, y, {0, 0, 0});
      for (std::size_t k = 0; k < tiles.size(); ++k) {
        const double value = box(*tiles[k].image, x, y, scale);
        put(static_cast<int>(k) + 1, 0, x, y, display(value));
        put(static_cast<int>(k) + 1, 1, x, y, difference_colour(value, value_reference));
      }
    }
  }
  return encode_tagged_png(width, height, 3, pixels, "report");
}

std::string configuration_of(const measure::ImageSet::Rendered& rendered) {
  return measure::configuration_id(rendered.variant, rendered.feed, rendered.prefilter, rendered.lobe);
}

// Every configuration of a (scene, material) beside the ground truth.
std::string sheet_png(const measure::ImageSet& set) {
  std::vector<Tile> tiles;
  for (const auto& rendered : set.variants) tiles.push_back({configuration_of(rendered), &rendered.image});
  return grid_png(set.reference, tiles);
}

std::string sheet_name(const measure::ImageSet& set) {
  return fmt::format("sheet_{}_alpha{:.4f}.png", measure::scene_name(set.scene), set.material.alpha);
}

}  // namespace saagen::report

// Labels drawn into the report's PNG sheets (so a PNG shared alone still says what it shows):
// stb_easy_font's glyphs, white on RGB pixels.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace saagen::report {

// A label line's height in pixels and the most lines a label keeps.
constexpr int kLabelLineHeight = 11, kLabelLines = 4;

// The label split after its '-', ':' and ' ' separators into lines of at most `max_width` pixels
// (a single token wider than that keeps its own line).
std::vector<std::string> wrap_label(const std::string& label, int max_width);

// Draws one line of text in white with its top left at (x, y) into RGB pixels of the given size,
// clipped at the image's edges.
void draw_text(std::vector<std::uint8_t>& pixels, int image_width, int image_height, int x, int y, const std::string& text);

}  // namespace saagen::report

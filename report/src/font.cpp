// The report's label font (see font.hpp): stb_easy_font builds each glyph from axis-aligned
// quads, filled here at integer pixels.
#include "font.hpp"

#include <stb/stb_easy_font.h>

namespace saagen::report {

std::vector<std::string> wrap_label(const std::string& label, int max_width) {
  std::vector<std::string> lines{""};
  std::string token;
  auto width_of = [](std::string text) { return stb_easy_font_width(text.data()); };
  auto flush = [&]() {
    if (!lines.back().empty() && width_of(lines.back() + token) > max_width) lines.push_back("");
    lines.back() += token;
    token.clear();
  };
  for (char c : label) {
    token += c;
    if (c == '-' || c == ':' || c == ' ') flush();
  }
  flush();
  return lines;
}

void draw_text(std::vector<std::uint8_t>& pixels, int image_width, int image_height, int x, int y, const std::string& text) {
  struct Vertex {
    float x, y, z;
    unsigned char colour[4];
  };
  std::vector<Vertex> vertices(4 * 600);
  std::string buffer = text;
  unsigned char white[4] = {255, 255, 255, 255};
  const int quads = stb_easy_font_print(static_cast<float>(x), static_cast<float>(y), buffer.data(), white, vertices.data(),
                                        static_cast<int>(vertices.size() * sizeof(Vertex)));
  for (int q = 0; q < quads; ++q) {
    const Vertex& a = vertices[4 * q];
    const Vertex& c = vertices[4 * q + 2];
    for (int py = static_cast<int>(a.y); py < static_cast<int>(c.y); ++py)
      for (int px = static_cast<int>(a.x); px < static_cast<int>(c.x); ++px) {
        if (px < 0 || py < 0 || px >= image_width || py >= image_height) continue;
        const std::size_t index = (static_cast<std::size_t>(py) * image_width + px) * 3;
        pixels[index] = pixels[index + 1] = pixels[index + 2] = 255;
      }
  }
}

}  // namespace saagen::report

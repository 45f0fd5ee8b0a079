// PNG files as saagen writes them: 8-bit pixels encoded by stb_image_write, carrying saagen's
// output tag (io/output.hpp) in a tEXt chunk so that the output layer recognises them as its own.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace saagen::report {

// PNG bytes of 8-bit pixels (1: grey, 3: RGB) carrying saagen's output tag (io/output.hpp) with
// `what` after it, so that the output layer recognises the file as saagen's.
std::string encode_tagged_png(int width, int height, int channels, const std::vector<std::uint8_t>& pixels, std::string_view what);

}  // namespace saagen::report

// libFuzzer target: the PNG normal-map reader of `texture prefilter` and `glints lean`
// (prefilter::read_normal_map; stb_image behind the header's dimension caps). Rejected input must
// fail with one "n.png: ..." line; an accepted map must hold unit tangent-space normals of a
// power-of-two size within the caps, and small ones must reduce to a 1x1 MIP chain.
#include "fuzz_support.hpp"

#include "saagen/error.hpp"
#include "saagen/products/prefilter.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using saagen::fuzz::finding;
  namespace prefilter = saagen::prefilter;
  constexpr const char* target = "png_fuzzer";
  prefilter::NormalImage image;
  try {
    image = prefilter::read_normal_map(std::span<const std::uint8_t>(data, size), "n.png");
  } catch (const saagen::Error& error) {
    saagen::fuzz::check_message(target, error.what(), "n.png: ");
    return 0;
  }
  const long long texels = static_cast<long long>(image.width) * image.height;
  if (image.width <= 0 || image.height <= 0 || (image.width & (image.width - 1)) != 0 || (image.height & (image.height - 1)) != 0) {
    finding(target, "accepted map is not a power-of-two size", std::to_string(image.width) + " x " + std::to_string(image.height));
  }
  if (image.width > prefilter::max_normal_map_side || image.height > prefilter::max_normal_map_side ||
      texels > prefilter::max_normal_map_texels) {
    finding(target, "accepted map is beyond the caps", std::to_string(image.width) + " x " + std::to_string(image.height));
  }
  if (image.normals.size() != static_cast<std::size_t>(texels) * 3) finding(target, "accepted map has inconsistent size", "normals");
  for (std::size_t texel = 0; texel < image.normals.size(); texel += 3) {
    const double x = image.normals[texel], y = image.normals[texel + 1], z = image.normals[texel + 2];
    if (!(z > 0.0) || std::abs(std::sqrt(x * x + y * y + z * z) - 1.0) > 1e-12) finding(target, "a normal is not unit or not z > 0", "");
  }
  if (texels <= 64 * 64) {
    const auto levels = prefilter::build_levels(image);
    if (levels.empty() || levels.back().width != 1 || levels.back().height != 1) finding(target, "MIP chain does not end at 1x1", "");
  }
  return 0;
}

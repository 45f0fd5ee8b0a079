// One-channel textures with a MIP chain (see scalar_map.hpp).
#include "saagen/measure/scalar_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace saagen::measure {

namespace {

// The checks of the constructor's contract, and level 0's hash (FNV-1a over the doubles' bytes).
std::uint64_t checked_hash(int width, int height, const std::vector<double>& values) {
  texture::check_level0("ScalarMap", width, height, values.size(), "values");
  std::uint64_t hash = texture::kFnvOffset;
  for (const double v : values) {
    if (!std::isfinite(v)) throw std::invalid_argument("ScalarMap: values must be finite");
    hash = texture::fnv1a(hash, v);
  }
  return hash;
}

}  // namespace

ScalarMap::ScalarMap(int width, int height, std::vector<double> values)
    : ScalarMap(checked_hash(width, height, values), width, height, std::move(values)) {}

ScalarMap::ScalarMap(std::uint64_t hash, int width, int height, std::vector<double>&& values)
    : MipChain<double>(width, height, std::move(values), [](double&) {}), hash_(hash) {}

std::pair<double, double> ScalarMap::value_range() const {
  std::pair<double, double> range{texel(0, 0, 0), texel(0, 0, 0)};
  for (int y = 0; y < height(0); ++y)
    for (int x = 0; x < width(0); ++x) range = {std::min(range.first, texel(0, x, y)), std::max(range.second, texel(0, x, y))};
  return range;
}

std::string ScalarMap::describe() const {
  if (empty()) return "scalar_map(none)";
  char text[96];
  std::snprintf(text, sizeof text, "scalar_map(%dx%d,%016llx)", width(0), height(0), static_cast<unsigned long long>(hash_));
  return text;
}

}  // namespace saagen::measure

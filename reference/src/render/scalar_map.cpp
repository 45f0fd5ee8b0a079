// One-channel textures with a MIP chain (see scalar_map.hpp).
#include "saagen/reference/render/scalar_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace saagen::render {

namespace {

bool is_power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

int wrap(int i, int size) {
  const int m = i % size;
  return m < 0 ? m + size : m;
}

}  // namespace

ScalarMap::ScalarMap(int width, int height, std::vector<double> values) {
  if (!is_power_of_two(width) || !is_power_of_two(height)) throw std::invalid_argument("ScalarMap: width and height must be powers of two");
  if (values.size() != static_cast<std::size_t>(width) * height) throw std::invalid_argument("ScalarMap: width * height values expected");
  hash_ = 0xcbf29ce484222325ULL;  // FNV-1a over the doubles' bytes
  for (double v : values) {
    if (!std::isfinite(v)) throw std::invalid_argument("ScalarMap: values must be finite");
    unsigned char bytes[sizeof v];
    std::memcpy(bytes, &v, sizeof v);
    for (unsigned char b : bytes) {
      hash_ ^= b;
      hash_ *= 0x100000001b3ULL;
    }
  }
  levels_.push_back({width, height, std::move(values)});
  // Box reduction down to 1 x 1 (a non-square map keeps halving its longer side alone).
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level& fine = levels_.back();
    Level coarse{std::max(1, fine.width / 2), std::max(1, fine.height / 2), {}};
    const int sx = fine.width / coarse.width, sy = fine.height / coarse.height;
    const double weight = 1.0 / (sx * sy);
    coarse.texels.resize(static_cast<std::size_t>(coarse.width) * coarse.height);
    for (int y = 0; y < coarse.height; ++y)
      for (int x = 0; x < coarse.width; ++x) {
        double sum = 0.0;
        for (int j = 0; j < sy; ++j)
          for (int i = 0; i < sx; ++i) sum += fine.texels[static_cast<std::size_t>(y * sy + j) * fine.width + x * sx + i];
        coarse.texels[static_cast<std::size_t>(y) * coarse.width + x] = weight * sum;
      }
    levels_.push_back(std::move(coarse));
  }
}

double ScalarMap::texel(int level, int x, int y) const {
  const Level& l = levels_[level];
  return l.texels[static_cast<std::size_t>(wrap(y, l.height)) * l.width + wrap(x, l.width)];
}

double ScalarMap::bilinear(int level, Vec2 uv) const {
  const Level& l = levels_[level];
  const double fx = uv.x * l.width - 0.5, fy = uv.y * l.height - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy);
  const double ax = fx - x0, ay = fy - y0;
  const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
  return ((1.0 - ax) * (1.0 - ay)) * texel(level, ix, iy) + (ax * (1.0 - ay)) * texel(level, ix + 1, iy) +
         ((1.0 - ax) * ay) * texel(level, ix, iy + 1) + (ax * ay) * texel(level, ix + 1, iy + 1);
}

double ScalarMap::trilinear(Vec2 uv, double lod) const {
  const double top = static_cast<double>(levels() - 1);
  const double lambda = std::isnan(lod) ? 0.0 : ref::min(ref::max(lod, 0.0), top);
  const int d = static_cast<int>(std::floor(lambda));
  const double t = lambda - d;
  if (t == 0.0 || d + 1 > levels() - 1) return bilinear(d, uv);
  return (1.0 - t) * bilinear(d, uv) + t * bilinear(d + 1, uv);
}

double ScalarMap::lod(Vec2 duv_dx, Vec2 duv_dy) const {
  const double w = levels_[0].width, h = levels_[0].height;
  const double rho_x = std::hypot(duv_dx.x * w, duv_dx.y * h);
  const double rho_y = std::hypot(duv_dy.x * w, duv_dy.y * h);
  return std::log2(ref::max(rho_x, rho_y));
}

std::string ScalarMap::describe() const {
  if (levels_.empty()) return "scalar_map(none)";
  char text[96];
  std::snprintf(text, sizeof text, "scalar_map(%dx%d,%016llx)", levels_[0].width, levels_[0].height,
                static_cast<unsigned long long>(hash_));
  return text;
}

}  // namespace saagen::render

// Normal maps with a MIP chain, sampled by the Vulkan rules (see normal_map.hpp).
#include "saagen/reference/render/normal_map.hpp"

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

std::uint64_t hash_normals(const std::vector<Vec3>& normals) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a over the doubles' bytes
  for (const Vec3& n : normals) {
    const double c[3] = {n.x, n.y, n.z};
    unsigned char bytes[sizeof c];
    std::memcpy(bytes, c, sizeof c);
    for (unsigned char b : bytes) {
      h ^= b;
      h *= 0x100000001b3ULL;
    }
  }
  return h;
}

NormalTexel level0_texel(Vec3 n) {
  const Vec2 s = normal_slope(n);
  return {n, n, s, Sym2{s.x * s.x, s.x * s.y, s.y * s.y}};
}

}  // namespace

NormalTexel operator*(double w, const NormalTexel& t) { return {w * t.normal, w * t.mean_normal, w * t.slope_mean, w * t.slope_second}; }

NormalTexel operator+(const NormalTexel& a, const NormalTexel& b) {
  return {a.normal + b.normal, a.mean_normal + b.mean_normal, a.slope_mean + b.slope_mean, a.slope_second + b.slope_second};
}

Vec2 normal_slope(Vec3 n) { return {-n.x / n.z, -n.y / n.z}; }

Sym2 slope_covariance(const NormalTexel& t) {
  const Vec2 m = t.slope_mean;
  Sym2 c{t.slope_second.xx - m.x * m.x, t.slope_second.xy - m.x * m.y, t.slope_second.yy - m.y * m.y};
  c.xx = ref::max(c.xx, 0.0);
  c.yy = ref::max(c.yy, 0.0);
  return c;
}

NormalMap::NormalMap(int width, int height, std::vector<Vec3> normals) {
  if (!is_power_of_two(width) || !is_power_of_two(height)) throw std::invalid_argument("NormalMap: width and height must be powers of two");
  if (normals.size() != static_cast<std::size_t>(width) * height) throw std::invalid_argument("NormalMap: width * height normals expected");
  for (const Vec3& n : normals)
    if (!(n.z > 0.0) || std::fabs(ref::length(n) - 1.0) > 1e-9)
      throw std::invalid_argument("NormalMap: normals must be unit vectors with z > 0");
  hash_ = hash_normals(normals);

  Level base{width, height, {}};
  base.texels.reserve(normals.size());
  for (const Vec3& n : normals) base.texels.push_back(level0_texel(n));
  levels_.push_back(std::move(base));

  // Box reduction down to 1 x 1 (a non-square map keeps halving its longer side alone).
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level& fine = levels_.back();
    Level coarse{std::max(1, fine.width / 2), std::max(1, fine.height / 2), {}};
    const int sx = fine.width / coarse.width, sy = fine.height / coarse.height;
    const double weight = 1.0 / (sx * sy);
    coarse.texels.resize(static_cast<std::size_t>(coarse.width) * coarse.height);
    for (int y = 0; y < coarse.height; ++y)
      for (int x = 0; x < coarse.width; ++x) {
        NormalTexel sum{};
        for (int j = 0; j < sy; ++j)
          for (int i = 0; i < sx; ++i) sum = sum + fine.texels[static_cast<std::size_t>(y * sy + j) * fine.width + x * sx + i];
        NormalTexel mean = weight * sum;
        mean.normal = ref::normalize(mean.normal);  // what a MIP generator stores
        coarse.texels[static_cast<std::size_t>(y) * coarse.width + x] = mean;
      }
    levels_.push_back(std::move(coarse));
  }
}

const NormalTexel& NormalMap::texel(int level, int x, int y) const {
  const Level& l = levels_[level];
  return l.texels[static_cast<std::size_t>(wrap(y, l.height)) * l.width + wrap(x, l.width)];
}

NormalTexel NormalMap::bilinear(int level, Vec2 uv) const {
  const Level& l = levels_[level];
  const double fx = uv.x * l.width - 0.5, fy = uv.y * l.height - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy);
  const double ax = fx - x0, ay = fy - y0;
  const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
  return ((1.0 - ax) * (1.0 - ay)) * texel(level, ix, iy) + (ax * (1.0 - ay)) * texel(level, ix + 1, iy) +
         ((1.0 - ax) * ay) * texel(level, ix, iy + 1) + (ax * ay) * texel(level, ix + 1, iy + 1);
}

NormalTexel NormalMap::trilinear(Vec2 uv, double lod) const {
  const double top = static_cast<double>(levels() - 1);
  const double lambda = std::isnan(lod) ? 0.0 : ref::min(ref::max(lod, 0.0), top);
  const int d = static_cast<int>(std::floor(lambda));
  const double t = lambda - d;
  if (t == 0.0 || d + 1 > levels() - 1) return bilinear(d, uv);
  return (1.0 - t) * bilinear(d, uv) + t * bilinear(d + 1, uv);
}

double NormalMap::lod(Vec2 duv_dx, Vec2 duv_dy) const {
  const double w = levels_[0].width, h = levels_[0].height;
  const double rho_x = std::hypot(duv_dx.x * w, duv_dx.y * h);
  const double rho_y = std::hypot(duv_dy.x * w, duv_dy.y * h);
  return std::log2(ref::max(rho_x, rho_y));
}

std::string NormalMap::describe() const {
  if (levels_.empty()) return "normal_map(none)";
  char text[96];
  std::snprintf(text, sizeof text, "normal_map(%dx%d,%016llx)", levels_[0].width, levels_[0].height,
                static_cast<unsigned long long>(hash_));
  return text;
}

}  // namespace saagen::render

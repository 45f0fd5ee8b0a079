// Normal maps with a MIP chain, sampled by the Vulkan rules (see normal_map.hpp).
#include "saagen/measure/normal_map.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace saagen::measure {

namespace {

// The checks of the constructor's contract, and level 0's hash (FNV-1a over the doubles' bytes).
std::uint64_t checked_hash(int width, int height, const std::vector<Vec3>& normals) {
  texture::check_level0("NormalMap", width, height, normals.size(), "normals");
  for (const Vec3& n : normals)
    if (!(n.z > 0.0) || std::fabs(ref::length(n) - 1.0) > 1e-9)
      throw std::invalid_argument("NormalMap: normals must be unit vectors with z > 0");
  std::uint64_t hash = texture::kFnvOffset;
  for (const Vec3& n : normals) hash = texture::fnv1a(texture::fnv1a(texture::fnv1a(hash, n.x), n.y), n.z);
  return hash;
}

NormalTexel level0_texel(Vec3 n) {
  const Vec2 s = normal_slope(n);
  return {n, n, s, Sym2{s.x * s.x, s.x * s.y, s.y * s.y}};
}

std::vector<NormalTexel> level0_texels(const std::vector<Vec3>& normals) {
  std::vector<NormalTexel> texels;
  texels.reserve(normals.size());
  for (const Vec3& n : normals) texels.push_back(level0_texel(n));
  return texels;
}

// What a MIP generator stores for a coarser texel: the renormalised mean normal (the moments
// stay means).
void renormalise(NormalTexel& mean) { mean.normal = ref::normalize(mean.normal); }

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

NormalMap::NormalMap(int width, int height, const std::vector<Vec3>& normals)
    : NormalMap(checked_hash(width, height, normals), width, height, normals) {}

NormalMap::NormalMap(std::uint64_t hash, int width, int height, const std::vector<Vec3>& normals)
    : MipChain<NormalTexel>(width, height, level0_texels(normals), renormalise), hash_(hash) {}

std::string NormalMap::describe() const {
  if (empty()) return "normal_map(none)";
  char text[96];
  std::snprintf(text, sizeof text, "normal_map(%dx%d,%016llx)", width(0), height(0), static_cast<unsigned long long>(hash_));
  return text;
}

}  // namespace saagen::measure

// KHR_materials_anisotropy's lobe (see anisotropy.hpp).
#include "saagen/measure/anisotropy.hpp"

#include <sstream>

namespace saagen::measure {

using ref::cross;
using ref::dot;
using ref::normalize;

std::string Anisotropy::describe() const {
  std::ostringstream s;
  s.precision(17);
  s << "aniso(" << strength << "," << rotation.x << "," << rotation.y;
  if (textured()) s << "," << red->describe() << "," << green->describe() << "," << blue->describe();
  s << ")";
  return s.str();
}

AnisotropySample anisotropy_from_texel(const Anisotropy& anisotropy, Vec3 rgb) {
  AnisotropySample out;
  Vec2 d{1.0, 0.0};
  double strength = anisotropy.strength;
  if (anisotropy.textured()) {
    const Vec2 encoded{2.0 * rgb.x - 1.0, 2.0 * rgb.y - 1.0};
    const double length = std::sqrt(encoded.x * encoded.x + encoded.y * encoded.y);
    if (length > 0.0) d = {encoded.x / length, encoded.y / length};
    strength *= rgb.z;
  }
  // d rotated counter-clockwise by anisotropyRotation: (c d.x - s d.y, s d.x + c d.y).
  const Vec2 r = anisotropy.rotation;
  out.direction = {r.x * d.x - r.y * d.y, r.y * d.x + r.x * d.y};
  out.strength = ref::saturate(strength);
  return out;
}

AnisotropySample anisotropy_level0(const Anisotropy& anisotropy, Vec2 uv) {
  if (!anisotropy.textured()) return anisotropy_from_texel(anisotropy, {});
  return anisotropy_from_texel(anisotropy,
                               {anisotropy.red->bilinear(0, uv), anisotropy.green->bilinear(0, uv), anisotropy.blue->bilinear(0, uv)});
}

AnisotropySample anisotropy_trilinear(const Anisotropy& anisotropy, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy) {
  if (!anisotropy.textured()) return anisotropy_from_texel(anisotropy, {});
  // The three channels are one texture: one LOD (the maps share the image's size).
  const double lod = anisotropy.red->lod(duv_dx, duv_dy);
  return anisotropy_from_texel(
      anisotropy, {anisotropy.red->trilinear(uv, lod), anisotropy.green->trilinear(uv, lod), anisotropy.blue->trilinear(uv, lod)});
}

void apply_anisotropy_frame(SurfaceHit& hit, Vec2 direction) {
  const Vec3 t = direction.x * hit.geometric_tangent + (hit.bitangent_sign * direction.y) * hit.geometric_bitangent;
  hit.geometric_tangent = normalize(t);
  hit.geometric_bitangent = cross(hit.geometric_normal, hit.geometric_tangent);
  const Vec3 n = hit.normal;
  hit.tangent = normalize(hit.geometric_tangent - dot(hit.geometric_tangent, n) * n);
  hit.bitangent = cross(n, hit.tangent);
}

Vec2 anisotropic_alpha2(double alpha, double strength) {
  const double alpha_t = alpha + (1.0 - alpha) * strength * strength;  // mix(alpha, 1, s^2)
  return {alpha_t * alpha_t, alpha * alpha};
}

ref::Sym2 to_anisotropy_frame(ref::Sym2 m, Vec2 d, double s) {
  // Rows of M: (d.x, d.y) and (-s d.y, s d.x).
  const double m00 = d.x, m01 = d.y, m10 = -s * d.y, m11 = s * d.x;
  const double r0x = m00 * m.xx + m01 * m.xy, r0y = m00 * m.xy + m01 * m.yy;
  const double r1x = m10 * m.xx + m11 * m.xy, r1y = m10 * m.xy + m11 * m.yy;
  return {r0x * m00 + r0y * m01, r0x * m10 + r0y * m11, r1x * m10 + r1y * m11};
}

}  // namespace saagen::measure

// Analytic Jacobians of the half-vector parameterisations (Tokuyoshi & Kaplanyan 2019
// Sec. 3.1-3.2, supplemental Sec. 2), with the template's slope sign (see jacobian.hpp).
#include "saagen/reference/jacobian.hpp"

#include <cmath>

namespace saagen::ref {

// Supplemental Sec. 2, Eq. 3: the columns of the rotation for m = (0, 0, 1) give the sphere's
// tangent directions at h: d h / d psi_x = (cos t cos p, cos t sin p, -sin t),
// d h / d psi_y = (-sin p, cos p, 0), with cos t = hz, sin t = s, (cos p, sin p) = h.xy / s.
SphereBasis sphere_tangent_basis(Vec3 h) {
  const double s = std::sqrt(1.0 - h.z * h.z);
  return {Vec3{h.x * h.z / s, h.y * h.z / s, -s}, Vec3{-h.y / s, h.x / s, 0.0}};
}

// Supplemental Eq. 4: J = 1/sqrt(1 - hz^2) [hx hz, -hy; hy hz, hx].
Mat2 J_sphere_to_projected(Vec3 h) {
  const double inv_s = 1.0 / std::sqrt(1.0 - h.z * h.z);
  return inv_s * Mat2{h.x * h.z, -h.y, h.y * h.z, h.x};
}

// Supplemental Eq. 6, for slope = h.xy / hz with hz = sqrt(1 - hx^2 - hy^2):
// d(hx/hz)/dhx = (1 - hy^2)/hz^3, d(hx/hz)/dhy = hx hy / hz^3, and symmetrically.
Mat2 J_projected_to_slope(Vec3 h) {
  const double inv_hz3 = 1.0 / (h.z * h.z * h.z);
  return inv_hz3 * Mat2{1.0 - h.y * h.y, h.x * h.y, h.x * h.y, 1.0 - h.x * h.x};
}

// Supplemental Eq. 7 = Eq. 6 x Eq. 4: J = 1/(hz^2 sqrt(1 - hz^2)) [hx, -hy hz; hy, hx hz].
Mat2 J_sphere_to_slope(Vec3 h) {
  const double scale = 1.0 / (h.z * h.z * std::sqrt(1.0 - h.z * h.z));
  return scale * Mat2{h.x, -h.y * h.z, h.y, h.x * h.z};
}

// d(h.xy / |hz|) = dh.xy / |hz| - h.xy sign(hz) dh.z / hz^2
//                = (dh.xy |hz| - h.xy sign(hz) dh.z) / hz^2.
Vec2 slope_differential(Vec3 h, Vec3 dh) {
  const double sign_z = h.z < 0.0 ? -1.0 : 1.0;
  return (dh.xy() * std::fabs(h.z) - h.xy() * (sign_z * dh.z)) / (h.z * h.z);
}

// d(h.xy) = dh.xy.
Vec2 projected_differential(Vec3 /*h*/, Vec3 dh) { return dh.xy(); }

}  // namespace saagen::ref

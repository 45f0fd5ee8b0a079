// saagen reference: analytic Jacobians of the half-vector parameterisations
// (Tokuyoshi & Kaplanyan 2019 Sec. 3.1-3.2 and supplemental Sec. 2) and exact differentials.
//
// Sign convention. The templates (and Listing 1) use the slope h.xy / |h.z|; the supplemental
// document (Eq. 5) uses -h.xy / h.z. The functions here follow the templates: for h.z > 0,
// J_projected_to_slope and J_sphere_to_slope are the negatives of supplemental Eqs. 6 and 7.
// Determinants of 2x2 matrices do not change under negation, so det(J_sphere_to_slope) =
// 1 / hz^3 and det(J_sphere_to_projected) = hz as in the paper.
//
// Spherical coordinates (supplemental Sec. 2): the first tangent direction of the sphere at h
// runs along the great circle through h and n = z (increasing polar angle theta), the second
// along the great circle through h and n x h (increasing azimuth phi). See sphere_tangent_basis.
// Preconditions: 0 < hz < 1 (h not at the pole, where the basis is undefined) for the
// spherical Jacobians; hz > 0 for J_projected_to_slope.
#pragma once

#include "saagen/reference/math.hpp"

namespace saagen::ref {

// Orthonormal tangent basis of the unit sphere at h: e_theta = (hx hz, hy hz, -(1 - hz^2)) / s,
// e_phi = (-hy, hx, 0) / s, s = sqrt(1 - hz^2). Derivatives of h with respect to the arc
// lengths (psi_x, psi_y) of the supplemental Sec. 2.
struct SphereBasis {
  Vec3 e_theta;
  Vec3 e_phi;
};
SphereBasis sphere_tangent_basis(Vec3 h);

// Supplemental Eq. 4 (T&K 2019 Sec. 3.2): J = 1/sqrt(1 - hz^2) [hx hz, -hy; hy hz, hx];
// det = hz.
Mat2 J_sphere_to_projected(Vec3 h);

// Supplemental Eq. 6 with the template's sign: J = 1/hz^3 [1 - hy^2, hx hy; hx hy, 1 - hx^2];
// det = 1 / hz^4.
Mat2 J_projected_to_slope(Vec3 h);

// Supplemental Eq. 7 with the template's sign (T&K 2019 Sec. 3.1):
// J = 1/(hz^2 sqrt(1 - hz^2)) [hx, -hy hz; hy, hx hz]; det = 1 / hz^3.
Mat2 J_sphere_to_slope(Vec3 h);

// Exact differential of half_vector_slope(h) = h.xy / |h.z| for a 3D derivative dh of h:
// d(slope) = (dh.xy |hz| - h.xy sign(hz) dh.z) / hz^2.
Vec2 slope_differential(Vec3 h, Vec3 dh);

// Exact differential of half_vector_projected(h) = h.xy: d(proj) = dh.xy.
Vec2 projected_differential(Vec3 h, Vec3 dh);

}  // namespace saagen::ref

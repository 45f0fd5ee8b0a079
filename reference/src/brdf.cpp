// Double-precision reference of templates/30-brdf.saa. Each body follows its template
// statement by statement (same guards and clamps).
#include "saagen/reference/brdf.hpp"

#include <cmath>

namespace saagen::ref {

namespace {
constexpr double kSqrtPi = 1.7724538509055160273;  // sqrt(pi)

// adj(A) of a symmetric 2x2 matrix: (a11, -a01, a00).
constexpr Sym2 adjugate(Sym2 a) { return {a.yy, -a.xy, a.xx}; }
}  // namespace

// Supplemental Sec. 1, "Practical Implementation": tau = ax^2 ay^2.
double ndf_clamp_tau(Vec2 alpha2) { return alpha2.x * alpha2.y; }

// ---------------------------------------------------------------------------------------------
// GGX

// Supplemental Sec. 1 (clamped form):
// D(h) = chi+(hz) / (pi sqrt(max(det A, tau)) (h.xy^T A^-1 h.xy + hz^2)^2),
// A^-1 = adj(A) / max(det A, tau).
double ggx_ndf_matrix(Vec3 h, Sym2 a, double tau) {
    if (h.z <= 0.0) return 0.0;
    const double det = max(sym2_determinant(a), tau);
    const double q = sym2_quadratic_form(adjugate(a), h.xy()) / det + h.z * h.z;
    return 1.0 / (kPi * std::sqrt(det) * q * q);
}

// Supplemental Sec. 1: Lambda(w) = -1/2 + sqrt(w.xy^T A w.xy + wz^2) / (2 |wz|).
double ggx_lambda_matrix(Vec3 w, Sym2 a) {
    return -0.5 + std::sqrt(sym2_quadratic_form(a, w.xy()) + w.z * w.z) / (2.0 * std::fabs(w.z));
}

// Supplemental Sec. 1 / Heitz 2014: G2 = chi+(i.h) chi+(o.h) / (1 + Lambda(i) + Lambda(o)).
double ggx_g2_matrix(Vec3 i, Vec3 o, Vec3 h, Sym2 a) {
    if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
    return 1.0 / (1.0 + ggx_lambda_matrix(i, a) + ggx_lambda_matrix(o, a));
}

// T&K 2019 Sec. 2.2: f = G2 D / (4 |i.n| |o.n|), Fresnel left to the caller.
double ggx_brdf_matrix(Vec3 i, Vec3 o, Sym2 a, double tau) {
    if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
    const Vec3 h = normalize(i + o);
    return ggx_ndf_matrix(h, a, tau) * ggx_g2_matrix(i, o, h, a) / (4.0 * i.z * o.z);
}

// Supplemental Sec. 1: D(h) = chi+(hz) / (pi ax ay (hx^2/ax^2 + hy^2/ay^2 + hz^2)^2).
double ggx_ndf_axis(Vec3 h, Vec2 alpha2) {
    if (h.z <= 0.0) return 0.0;
    const double q = h.x * h.x / alpha2.x + h.y * h.y / alpha2.y + h.z * h.z;
    return 1.0 / (kPi * std::sqrt(alpha2.x * alpha2.y) * q * q);
}

// Supplemental Sec. 1: Lambda(w) = -1/2 + sqrt(ax^2 wx^2 + ay^2 wy^2 + wz^2) / (2 |wz|).
double ggx_lambda_axis(Vec3 w, Vec2 alpha2) {
    return -0.5 + std::sqrt(alpha2.x * w.x * w.x + alpha2.y * w.y * w.y + w.z * w.z) /
                      (2.0 * std::fabs(w.z));
}

// T&K 2019 Sec. 2.2 with the axis-aligned GGX NDF and height-correlated G2.
double ggx_brdf_axis(Vec3 i, Vec3 o, Vec2 alpha2) {
    if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
    const Vec3 h = normalize(i + o);
    if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
    const double g2 = 1.0 / (1.0 + ggx_lambda_axis(i, alpha2) + ggx_lambda_axis(o, alpha2));
    return ggx_ndf_axis(h, alpha2) * g2 / (4.0 * i.z * o.z);
}

// ---------------------------------------------------------------------------------------------
// Beckmann

// Supplemental Sec. 1 applied to Beckmann (Heitz 2014): the slope distribution
// exp(-s^T A^-1 s) / (pi sqrt(det A)), s = h.xy / hz, divided by hz^4 for the NDF.
double beckmann_ndf_matrix(Vec3 h, Sym2 a, double tau) {
    if (h.z <= 0.0) return 0.0;
    const double det = max(sym2_determinant(a), tau);
    const Vec2 slope = h.xy() / h.z;
    const double cos2 = h.z * h.z;
    return std::exp(-sym2_quadratic_form(adjugate(a), slope) / det) /
           (kPi * std::sqrt(det) * cos2 * cos2);
}

// Walter et al. 2007 rational approximation of the Beckmann Smith Lambda.
double beckmann_lambda_from_a(double a_param) {
    if (a_param >= 1.6) return 0.0;
    return (1.0 - 1.259 * a_param + 0.396 * a_param * a_param) /
           (3.535 * a_param + 2.181 * a_param * a_param);
}

// Heitz 2014 (Beckmann Lambda): (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)).
double beckmann_lambda_exact(double a_param) {
    return 0.5 * (std::erf(a_param) - 1.0) +
           std::exp(-a_param * a_param) / (2.0 * a_param * kSqrtPi);
}

// Heitz 2014: a = |wz| / sqrt(w.xy^T A w.xy) (1 / (alpha_w tan theta_w)), Walter fit.
double beckmann_lambda_matrix(Vec3 w, Sym2 a) {
    const double projected_roughness2 = sym2_quadratic_form(a, w.xy());
    if (projected_roughness2 <= 0.0) return 0.0;
    return beckmann_lambda_from_a(std::fabs(w.z) / std::sqrt(projected_roughness2));
}

// T&K 2019 Sec. 2.2 with the matrix Beckmann NDF.
double beckmann_brdf_matrix(Vec3 i, Vec3 o, Sym2 a, double tau) {
    if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
    const Vec3 h = normalize(i + o);
    if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
    const double g2 = 1.0 / (1.0 + beckmann_lambda_matrix(i, a) + beckmann_lambda_matrix(o, a));
    return beckmann_ndf_matrix(h, a, tau) * g2 / (4.0 * i.z * o.z);
}

// Beckmann 1963, axis-aligned anisotropic.
double beckmann_ndf_axis(Vec3 h, Vec2 alpha2) {
    if (h.z <= 0.0) return 0.0;
    const Vec2 slope = h.xy() / h.z;
    const double cos2 = h.z * h.z;
    const double exponent = slope.x * slope.x / alpha2.x + slope.y * slope.y / alpha2.y;
    return std::exp(-exponent) / (kPi * std::sqrt(alpha2.x * alpha2.y) * cos2 * cos2);
}

// T&K 2019 Sec. 2.2 with the axis-aligned Beckmann NDF (Walter et al. 2007 Lambda).
double beckmann_brdf_axis(Vec3 i, Vec3 o, Vec2 alpha2) {
    const Sym2 a{alpha2.x, 0.0, alpha2.y};
    if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
    const Vec3 h = normalize(i + o);
    if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
    const double g2 = 1.0 / (1.0 + beckmann_lambda_matrix(i, a) + beckmann_lambda_matrix(o, a));
    return beckmann_ndf_axis(h, alpha2) * g2 / (4.0 * i.z * o.z);
}

// ---------------------------------------------------------------------------------------------
// Fragment wrappers on a quad

// Template ggx_brdf_filtered_fragment: A = forward_aniso_projected_fragment(alpha2,
// normalize(i + o)) (T&K 2019 Sec. 3.2), then the matrix GGX BRDF with tau = ax^2 ay^2.
double ggx_brdf_filtered_fragment_quad(const Params& p, const Quad<Vec3>& i, const Quad<Vec3>& o,
                                       Vec2 alpha2, int pixel, Derivative mode) {
    const Quad<Vec3> half{normalize(i.top_left + o.top_left), normalize(i.top_right + o.top_right),
                          normalize(i.bottom_left + o.bottom_left),
                          normalize(i.bottom_right + o.bottom_right)};
    const Sym2 a = forward_aniso_projected_fragment_quad(p, alpha2, half, pixel, mode);
    return ggx_brdf_matrix(i[pixel], o[pixel], a, ndf_clamp_tau(alpha2));
}

// Template beckmann_brdf_filtered_fragment: as above with the matrix Beckmann BRDF.
double beckmann_brdf_filtered_fragment_quad(const Params& p, const Quad<Vec3>& i,
                                            const Quad<Vec3>& o, Vec2 alpha2, int pixel,
                                            Derivative mode) {
    const Quad<Vec3> half{normalize(i.top_left + o.top_left), normalize(i.top_right + o.top_right),
                          normalize(i.bottom_left + o.bottom_left),
                          normalize(i.bottom_right + o.bottom_right)};
    const Sym2 a = forward_aniso_projected_fragment_quad(p, alpha2, half, pixel, mode);
    return beckmann_brdf_matrix(i[pixel], o[pixel], a, ndf_clamp_tau(alpha2));
}

}  // namespace saagen::ref

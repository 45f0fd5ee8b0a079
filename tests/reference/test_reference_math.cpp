// Tests of the double-precision reference (reference/): each expected number is derived by
// hand in the comment next to it, from Tokuyoshi & Kaplanyan 2019 (T&K19), its supplemental
// document, and the template formulas. Default tolerance: 1e-12 relative (double precision, a
// handful of rounded operations); any other tolerance carries its reason.
#include "saagen/reference/reference.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace saagen::ref;

namespace {

constexpr double kRel = 1e-12;

// |actual - expected| <= rel * max(|expected|, floor): relative, with an absolute floor for
// values that are (close to) zero.
::testing::AssertionResult near_rel(double actual, double expected, double rel = kRel, double floor = 1e-300) {
  const double tol = rel * std::max(std::fabs(expected), floor);
  if (std::fabs(actual - expected) <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "actual " << actual << " expected " << expected << " diff " << (actual - expected) << " tol "
                                       << tol;
}

void expect_sym2_near(Sym2 actual, Sym2 expected, double rel = kRel) {
  const double scale = std::max({std::fabs(expected.xx), std::fabs(expected.xy), std::fabs(expected.yy), 1e-300});
  EXPECT_NEAR(actual.xx, expected.xx, rel * scale);
  EXPECT_NEAR(actual.xy, expected.xy, rel * scale);
  EXPECT_NEAR(actual.yy, expected.yy, rel * scale);
}

Vec3 random_unit_upper(std::mt19937_64& rng, double min_z = 0.05) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    const Vec3 v{u(rng), u(rng), u(rng)};
    const double l = length(v);
    if (l < 0.1 || l > 1.0) continue;
    Vec3 n = v / l;
    if (n.z < 0) n.z = -n.z;
    if (n.z >= min_z) return n;
  }
}

Vec3 random_vec3(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

// Symmetric positive definite A = R(angle) diag(l0, l1) R(angle)^T.
Sym2 rotated_matrix(double l0, double l1, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * c * l0 + s * s * l1, c * s * (l0 - l1), s * s * l0 + c * c * l1};
}

// Gauss-Legendre nodes and weights on [-1, 1]: Newton's method on P_n from the Chebyshev
// initial guess, with the three-term recurrence for P_n and P_n' (textbook construction).
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::fabs(dz) < 1e-16) break;
    }
    x[i] = z;
    w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

// Integral over the hemisphere of D(h) h_z d omega. With h = (r cos phi, r sin phi,
// sqrt(1 - r^2)), h_z d omega is the area element of the projected unit disk, r dr dphi, so
// the integral is int_0^{2 pi} int_0^1 D r dr dphi. r: composite Gauss-Legendre (panels x
// order); phi: the periodic trapezoid rule (spectrally accurate for a smooth periodic
// integrand).
template <class Ndf>
double integrate_projected_area(Ndf&& ndf, int panels, int order, int n_phi) {
  std::vector<double> x, w;
  gauss_legendre(order, x, w);
  double total = 0.0;
  for (int j = 0; j < n_phi; ++j) {
    const double phi = 2.0 * kPi * (j + 0.5) / n_phi;
    const double c = std::cos(phi), s = std::sin(phi);
    double ring = 0.0;
    for (int pnl = 0; pnl < panels; ++pnl) {
      const double r0 = double(pnl) / panels, r1 = double(pnl + 1) / panels;
      for (int k = 0; k < order; ++k) {
        const double r = 0.5 * (r0 + r1) + 0.5 * (r1 - r0) * x[k];
        const Vec3 h{r * c, r * s, std::sqrt(1.0 - r * r)};
        ring += 0.5 * (r1 - r0) * w[k] * ndf(h) * r;
      }
    }
    total += ring;
  }
  return total * 2.0 * kPi / n_phi;
}

// Per-pixel orthonormal frame whose normal is n: t = normalize(x - (x.n) n), b = n x t.
struct Frame {
  Vec3 t, b, n;
};
Frame frame_from_normal(Vec3 n) {
  const Vec3 t = normalize(Vec3{1, 0, 0} - n.x * n);
  return {t, cross(n, t), n};
}

// Pixel coordinates (x, y) of the quad whose top-left pixel is (x0, y0) (both even), and the
// fragment coordinates at the pixel centres.
Quad<Vec2> frag_coords(int x0, int y0) {
  return {Vec2{x0 + 0.5, y0 + 0.5}, Vec2{x0 + 1.5, y0 + 0.5}, Vec2{x0 + 0.5, y0 + 1.5}, Vec2{x0 + 1.5, y0 + 1.5}};
}

// A sphere-like normal field: n(x, y) = normalize((x - 16) / 20, (y - 16) / 20, 1), evaluated
// at the pixel centres of the quad (x0, y0).
Quad<Vec3> sphere_normals(int x0, int y0) {
  return map(frag_coords(x0, y0), [](Vec2 p) { return normalize(Vec3{(p.x - 16.0) / 20.0, (p.y - 16.0) / 20.0, 1.0}); });
}

}  // namespace

// =============================================================================================
// Flat surface: zero derivatives give a zero kernel.

TEST(FlatSurface, ZeroDerivativesLeaveRoughnessUnchangedInEveryVariant) {
  const Params p;
  const Vec2 z2{0, 0};
  const Vec3 z3{0, 0, 0};
  const Vec2 a2{0.04, 0.09};
  // Kernel 2 sigma^2 Delta^T Delta with Delta = 0 is the zero matrix: A = diag(ax^2, ay^2).
  EXPECT_EQ(forward_aniso_slope(p, a2, z2, z2), (Sym2{0.04, 0.0, 0.09}));
  EXPECT_EQ(forward_aniso_projected(p, a2, z2, z2), (Sym2{0.04, 0.0, 0.09}));
  // Rectangle kernel min(0, kappa) = 0; saturate(a2) = a2 for a2 in [0, 1].
  EXPECT_EQ(forward_axis_slope(p, a2, z2, z2), a2);
  EXPECT_EQ(forward_axis_projected(p, a2, z2, z2), a2);
  for (double alpha2 : {0.0, 0.3, 1.0}) {
    EXPECT_EQ(deferred_previous(p, alpha2, z2, z2), alpha2);
    EXPECT_EQ(deferred_max(p, alpha2, z2, z2), alpha2);
    EXPECT_EQ(deferred_max_tangent_free(p, alpha2, z3, z3), alpha2);
    EXPECT_EQ(deferred_sum(p, alpha2, z3, z3), alpha2);
    EXPECT_EQ(deferred_avg(p, alpha2, z3, z3), alpha2);
    // (a + 0) / (1 + 0) = a exactly.
    EXPECT_EQ(deferred_projected_space(p, alpha2, z3, z3), alpha2);
  }
  // Saturating variants saturate the input: 1.2 -> 1, -0.1 -> 0.
  EXPECT_EQ(deferred_sum(p, 1.2, z3, z3), 1.0);
  EXPECT_EQ(deferred_avg(p, -0.1, z3, z3), 0.0);
  EXPECT_EQ(deferred_projected_space(p, 1.2, z3, z3), 1.0);
  EXPECT_EQ(forward_axis_projected(p, Vec2{1.5, -0.5}, z2, z2), (Vec2{1.0, 0.0}));
  // The matrix variants do not clamp: A keeps an input above 1.
  EXPECT_EQ(forward_aniso_projected(p, Vec2{1.5, 2.0}, z2, z2), (Sym2{1.5, 0.0, 2.0}));
}

// =============================================================================================
// Known derivative pairs -> known Sigma and eigenvalues.

TEST(KnownDerivatives, DiagonalPairGivesKnownSigma) {
  const Params p;  // sigma^2 = 0.25
  // Delta = [3 0; 0 4]: Delta^T Delta = diag(9, 16); Sigma = 0.25 diag(9, 16) = diag(2.25, 4).
  const Sym2 m = sym2_from_derivative_rows(Vec2{3, 0}, Vec2{0, 4});
  EXPECT_EQ(m, (Sym2{9, 0, 16}));
  const Sym2 sigma = p.sigma2 * m;
  EXPECT_EQ(sigma, (Sym2{2.25, 0, 4}));
  // Eigenvalues of a diagonal matrix: 2.25 and 4. Max = 3.125 + sqrt(0.875^2) = 4.
  EXPECT_TRUE(near_rel(sym2_max_eigenvalue(sigma), 4.0));
  EXPECT_TRUE(near_rel(trace(sigma) - sym2_max_eigenvalue(sigma), 2.25));
  EXPECT_EQ(sym2_determinant(sigma), 9.0);  // 2.25 * 4
  // A = diag(ax^2, ay^2) + 2 Sigma = diag(0.01 + 4.5, 0.04 + 8).
  const Sym2 a = forward_aniso_projected(p, Vec2{0.01, 0.04}, Vec2{3, 0}, Vec2{0, 4});
  expect_sym2_near(a, Sym2{4.51, 0.0, 8.04});
  // Unclamped deferred_max: scale the derivatives by 1/10: Sigma = diag(0.0225, 0.04),
  // 2 lambda_max = 0.08 < kappa = 0.18, so alpha'^2 = 0.01 + 0.08 = 0.09.
  EXPECT_TRUE(near_rel(deferred_max(p, 0.01, Vec2{0.3, 0}, Vec2{0, 0.4}), 0.09));
  // Sum: 2 tr(Sigma) = 2 (0.0225 + 0.04) = 0.125 -> 0.135; avg: tr = 0.0625 -> 0.0725.
  EXPECT_TRUE(near_rel(deferred_sum(p, 0.01, Vec3{0.3, 0, 0}, Vec3{0, 0.4, 0}), 0.135));
  EXPECT_TRUE(near_rel(deferred_avg(p, 0.01, Vec3{0.3, 0, 0}, Vec3{0, 0.4, 0}), 0.0725));
  // Previous: rect = |(0.3, 0)| + |(0, 0.4)| = (0.3, 0.4), width 0.4,
  // 2 sigma^2 width^2 = 0.5 * 0.16 = 0.08 -> 0.09.
  EXPECT_TRUE(near_rel(deferred_previous(p, 0.01, Vec2{0.3, 0}, Vec2{0, 0.4}), 0.09));
}

TEST(KnownDerivatives, ShearedPairEigenvaluesFromTheQuadraticFormula) {
  const Params p;
  // du = (1, 1), dv = (0, 2): Delta = [1 1; 0 2],
  // Delta^T Delta = [1*1 + 0*0, 1*1 + 0*2; ., 1*1 + 2*2] = [1 1; 1 5].
  const Sym2 m = sym2_from_derivative_rows(Vec2{1, 1}, Vec2{0, 2});
  EXPECT_EQ(m, (Sym2{1, 1, 5}));
  // Characteristic polynomial lambda^2 - 6 lambda + (5 - 1) = 0:
  // lambda = (6 +- sqrt(36 - 16)) / 2 = 3 +- sqrt(5) = 5.2360679..., 0.7639320...
  const double lmax = 3.0 + std::sqrt(5.0);
  const double lmin = 3.0 - std::sqrt(5.0);
  EXPECT_TRUE(near_rel(sym2_max_eigenvalue(m), lmax));
  EXPECT_TRUE(near_rel(sym2_determinant(m), lmax * lmin));  // = 4
  EXPECT_EQ(sym2_determinant(m), 4.0);
  // Sigma = m / 4: eigenvalues (3 +- sqrt 5) / 4 = 1.3090170, 0.1909830.
  EXPECT_TRUE(near_rel(sym2_max_eigenvalue(p.sigma2 * m), lmax / 4.0));
  // A rotated pair: Delta = diag(3, 4) R(0.3) has the same Delta^T Delta eigenvalues up to the
  // rotation, which leaves the spectrum unchanged: 9 and 16.
  const double c = std::cos(0.3), s = std::sin(0.3);
  const Vec2 du{3 * c, -3 * s}, dv{4 * s, 4 * c};  // rows of diag(3,4) [c -s; s c]
  const Sym2 r = sym2_from_derivative_rows(du, dv);
  EXPECT_TRUE(near_rel(sym2_max_eigenvalue(r), 16.0));
  EXPECT_TRUE(near_rel(trace(r) - sym2_max_eigenvalue(r), 9.0, 1e-12));
  EXPECT_TRUE(near_rel(sym2_determinant(r), 144.0, 1e-12));
  // The quadratic form: v = (1, -1): [1 1; 1 5] -> 1 - 2 + 5 = 4.
  EXPECT_EQ(sym2_quadratic_form(m, Vec2{1, -1}), 4.0);
}

TEST(Eigenvalues, TraceEqualsMinPlusMaxForRandomDerivativeRows) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int k = 0; k < 1000; ++k) {
    const Sym2 m = sym2_from_derivative_rows(Vec2{u(rng), u(rng)}, Vec2{u(rng), u(rng)});
    const double lmax = sym2_max_eigenvalue(m);
    // lambda_min from the smaller root: tr/2 - sqrt(((m00-m11)/2)^2 + m01^2).
    const double hd = 0.5 * (m.xx - m.yy);
    const double lmin = 0.5 * trace(m) - std::sqrt(hd * hd + m.xy * m.xy);
    // Sum of the roots of lambda^2 - tr lambda + det = tr (Vieta); product = det.
    // Tolerance: tr up to 16; lmin can be tiny when Delta is nearly singular, so the product
    // is compared with an absolute floor of 1e-12 * tr^2.
    EXPECT_TRUE(near_rel(lmin + lmax, trace(m)));
    EXPECT_NEAR(lmin * lmax, sym2_determinant(m), 1e-12 * trace(m) * trace(m));
    EXPECT_GE(lmin, -1e-12 * trace(m));  // Delta^T Delta is positive semi-definite
  }
}

// =============================================================================================
// Isotropic kernels: sum, avg, max.

TEST(Isotropic, AvgKernelIsHalfTheSumKernelBeforeClamps) {
  const Params p;
  // |dn_dx|^2 + |dn_dy|^2 = (0.01 + 0.0004 + 0.0009) + (0.0025 + 0.0016) = 0.0154;
  // sum kernel 2 * 0.25 * 0.0154 = 0.0077, avg kernel 0.00385: both below kappa, and with
  // alpha^2 = 0.2 both results are below 1, so neither min nor saturate binds.
  const Vec3 dx{0.1, 0.02, -0.03}, dy{0.05, -0.04, 0.0};
  const double a = 0.2;
  const double sum = deferred_sum(p, a, dx, dy);
  const double avg = deferred_avg(p, a, dx, dy);
  EXPECT_TRUE(near_rel(sum, 0.2077));
  EXPECT_TRUE(near_rel(avg, 0.20385));
  // (avg - a) = (sum - a) / 2 up to the rounding of two additions to ~0.2 (2 ulp(0.2) =
  // 5.6e-17 absolute on a 3.85e-3 difference: 1e-13 relative, asserted at 1e-12).
  EXPECT_TRUE(near_rel(avg - a, (sum - a) / 2.0, 1e-12));
  // Random inputs below the clamps.
  std::mt19937_64 rng(11);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 rx = random_vec3(rng, 0.15), ry = random_vec3(rng, 0.15);
    const double s = deferred_sum(p, 0.1, rx, ry), v = deferred_avg(p, 0.1, rx, ry);
    ASSERT_LT(2.0 * isotropic_kernel_sum(p, rx, ry), p.kappa);
    // The kernel here is >= 0 and as small as ~1e-4: the absolute rounding of the
    // additions (~3e-17) bounds the error, so compare with an absolute 1e-15.
    EXPECT_NEAR(v - 0.1, (s - 0.1) / 2.0, 1e-15);
  }
}

TEST(Isotropic, MaxNeverExceedsSumForRandomInputs) {
  const Params p;
  std::mt19937_64 rng(13);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 dx = random_vec3(rng, 0.5), dy = random_vec3(rng, 0.5);
    const double a = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    // lambda_max <= lambda_min + lambda_max = tr for a positive semi-definite matrix; min and
    // saturate are monotone, so the ordering carries through the clamps.
    EXPECT_LE(deferred_max_tangent_free(p, a, dx, dy), deferred_sum(p, a, dx, dy));
    // Same for the 2D (tangent-space) form fed the xy parts.
    EXPECT_LE(deferred_max(p, a, dx.xy(), dy.xy()), deferred_sum(p, a, Vec3{dx.x, dx.y, 0}, Vec3{dy.x, dy.y, 0}));
  }
}

TEST(Isotropic, MaxEqualsSumOnlyWhenSigmaHasRankOne) {
  const Params p;
  // dn_dy = 0: Gram = [g 0; 0 0], lambda_max = g/2 + sqrt((g/2)^2) = g exactly (halving is
  // exact and sqrt(fl(x*x)) = |x| for correctly rounded IEEE operations), tr = g + 0 = g.
  // So both kernels are bit-identical: 2 sigma^2 g.
  const Vec3 dx{0.13, -0.07, 0.02}, zero{0, 0, 0};
  EXPECT_EQ(deferred_max_tangent_free(p, 0.05, dx, zero), deferred_sum(p, 0.05, dx, zero));
  EXPECT_EQ(deferred_max_tangent_free(p, 0.05, zero, dx), deferred_sum(p, 0.05, zero, dx));
  // Parallel rows (rank 1): dn_dy = 2 dn_dx. Gram = g [1 2; 2 4], eigenvalues 5g and 0:
  // lambda_max = 5g/2 + sqrt((3g/2)^2 + (2g)^2) = 5g/2 + 5g/2 = 5g = tr. Rounding only.
  // g = 0.0169 + 0.0049 + 0.0004 = 0.0222, kernel 2 * 0.25 * 5 * 0.0222 = 0.0555.
  const Vec3 dy = 2.0 * dx;
  EXPECT_TRUE(near_rel(deferred_max_tangent_free(p, 0.05, dx, dy), 0.1055));
  EXPECT_TRUE(near_rel(deferred_sum(p, 0.05, dx, dy), 0.1055));
  // Rank 2 (orthogonal rows of lengths 0.1 and 0.2): lambda_max = 0.04 < tr = 0.05.
  // max: 0.05 + 2 * 0.25 * 0.04 = 0.07; sum: 0.05 + 2 * 0.25 * 0.05 = 0.075.
  const Vec3 ox{0.1, 0, 0}, oy{0, 0.2, 0};
  EXPECT_TRUE(near_rel(deferred_max_tangent_free(p, 0.05, ox, oy), 0.07));
  EXPECT_TRUE(near_rel(deferred_sum(p, 0.05, ox, oy), 0.075));
  EXPECT_LT(deferred_max_tangent_free(p, 0.05, ox, oy), deferred_sum(p, 0.05, ox, oy));
}

// =============================================================================================
// The kappa clamp.

TEST(Clamp, HugeDerivativesReachAlphaSquaredPlusKappaExactly) {
  const Params p;  // kappa = 0.18
  const Vec3 hx{50, 0, 0}, hy{0, 70, 0};
  const Vec2 h2x{50, 0}, h2y{0, 70};
  // min(huge, kappa) returns kappa itself, so the result is the rounded alpha^2 + kappa: the
  // same operation as the expression below, bit for bit.
  const double a = 0.3;
  EXPECT_EQ(deferred_sum(p, a, hx, hy), a + p.kappa);
  EXPECT_EQ(deferred_avg(p, a, hx, hy), a + p.kappa);
  EXPECT_EQ(deferred_max(p, a, h2x, h2y), a + p.kappa);
  EXPECT_EQ(deferred_max_tangent_free(p, a, hx, hy), a + p.kappa);
  EXPECT_EQ(deferred_previous(p, a, h2x, h2y), a + p.kappa);
  EXPECT_EQ(forward_axis_slope(p, Vec2{a, 0.1}, h2x, h2y), (Vec2{a + p.kappa, 0.1 + p.kappa}));
  // Saturated: 0.9 + 0.18 > 1 -> 1.
  EXPECT_EQ(deferred_sum(p, 0.9, hx, hy), 1.0);
  EXPECT_EQ(deferred_previous(p, 0.9, h2x, h2y), 1.0);
  EXPECT_EQ(forward_axis_projected(p, Vec2{0.9, 0.95}, h2x, h2y), (Vec2{1.0, 1.0}));
  // Projected space with the clamped kernel k = kappa: (a + k(1-a)) / (1 + k(1-a)).
  const double ks = p.kappa * (1.0 - a);
  EXPECT_EQ(deferred_projected_space(p, a, hx, hy), (a + ks) / (1.0 + ks));
  // The matrix variants are not clamped: A = diag + 2 sigma^2 diag(2500, 4900).
  expect_sym2_near(forward_aniso_projected(p, Vec2{a, a}, h2x, h2y), Sym2{a + 1250.0, 0.0, a + 2450.0});
  // kappa = 0 turns filtering off.
  const Params off{0.25, 0.0};
  EXPECT_EQ(deferred_sum(off, a, hx, hy), a);
}

TEST(Clamp, DeferredAnisoBoundsTheTraceAsEq4AndKeepsTheKernelsShape) {
  const Params p;  // sigma^2 = 0.25, kappa = 0.18
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int k = 0; k < 1000; ++k) {
    const Vec2 du{u(rng), u(rng)}, dv{u(rng), u(rng)};
    const Sym2 raw = sym2_from_derivative_rows(du, dv);
    const double bound = 0.01 + 0.5 * std::fabs(u(rng));
    const Sym2 bounded = sym2_trace_bounded(raw, bound);
    if (trace(raw) <= bound) {  // nothing to bound
      EXPECT_EQ(bounded.xx, raw.xx);
      EXPECT_EQ(bounded.xy, raw.xy);
      EXPECT_EQ(bounded.yy, raw.yy);
      continue;
    }
    // One factor s = bound / tr on every entry: orientation and anisotropy kept, the trace = bound.
    expect_sym2_near(bounded, (bound / trace(raw)) * raw);
    EXPECT_TRUE(near_rel(trace(bounded), bound));
    // The branch-free form with the scale gives scale times the same matrix.
    expect_sym2_near(sym2_scaled_to_trace_bound(raw, 2.0, 2.0 * bound), 2.0 * bounded);
  }
  // A kernel along one axis (an edge's): tr = lambda_max = 2 sigma^2 |d|^2 = 0.5 * 100 -> kappa,
  // the other axis 0: the bound of Eq. 4's clamp, min(2 sigma^2 (|dn_x|^2 + |dn_y|^2), kappa).
  const Sym2 line = deferred_aniso(p, Vec3{10, 0, 0}, Vec3{0, 0, 0}, Vec3{0, 0, 1});
  EXPECT_TRUE(near_rel(sym2_max_eigenvalue(line), p.kappa));
  EXPECT_NEAR(trace(line) - sym2_max_eigenvalue(line), 0.0, 1e-15);
  // Anisotropy 4:1 beyond the bound stays 4:1 (a per-eigenvalue clamp would make it 1:1):
  // eigenvalues 4 kappa / 5 and kappa / 5, whose sum is kappa.
  const Sym2 wide = deferred_aniso(p, Vec3{20, 0, 0}, Vec3{0, 10, 0}, Vec3{0, 0, 1});
  EXPECT_TRUE(near_rel(sym2_max_eigenvalue(wide), 0.8 * p.kappa));
  EXPECT_TRUE(near_rel(trace(wide) - sym2_max_eigenvalue(wide), 0.2 * p.kappa));
  // The fragment wrapper's form (bounded derivatives, no clamp) gives the same tensor.
  expect_sym2_near(deferred_aniso_from_bounded_derivatives(p, Vec3{1.5, 0, 0}, Vec3{0, 0.75, 0}, Vec3{0, 0, 1}),
                   deferred_aniso(p, Vec3{1.5, 0, 0}, Vec3{0, 0.75, 0}, Vec3{0, 0, 1}));
}

TEST(Clamp, AxisVariantsClampEachAxisSeparately) {
  const Params p;
  // du = (100, 0.01), dv = (0, 0.02): rect = (100, 0.03).
  // x: 2 * 0.25 * 100^2 = 5000 -> clamped to kappa: 0.04 + 0.18 = 0.22.
  // y: 2 * 0.25 * 0.03^2 = 0.00045 -> 0.09 + 0.00045 = 0.09045 (not clamped).
  const Vec2 r = forward_axis_projected(p, Vec2{0.04, 0.09}, Vec2{100, 0.01}, Vec2{0, 0.02});
  EXPECT_EQ(r.x, 0.04 + p.kappa);
  EXPECT_TRUE(near_rel(r.y, 0.09045));
  // Signs do not matter: |du| + |dv| per component.
  const Vec2 s = forward_axis_slope(p, Vec2{0.04, 0.09}, Vec2{-100, -0.01}, Vec2{0, -0.02});
  EXPECT_EQ(s, r);
  // The rectangle is a bound of the sheared kernel: rect = (|0.1| + |0.05|, |0.1| + |-0.05|)
  // = (0.15, 0.15): both axes get 0.5 * 0.0225 = 0.01125.
  const Vec2 t = filter_roughness_rectangle(p, Vec2{0, 0}, Vec2{0.1, 0.1}, Vec2{0.05, -0.05});
  EXPECT_TRUE(near_rel(t.x, 0.01125));
  EXPECT_TRUE(near_rel(t.y, 0.01125));
}

// =============================================================================================
// Slope space vs projected space (T&K19 Sec. 3.1-3.2, supplemental Sec. 2).

namespace {
// h with hz = 0.4: hx = 0.6, hy = -sqrt(1 - 0.16 - 0.36) = -sqrt(0.48).
Vec3 grazing_half() { return Vec3{0.6, -std::sqrt(0.48), 0.4}; }
}  // namespace

TEST(Jacobians, SlopeDifferentialIsProjectedToSlopeTimesProjectedDifferential) {
  const Vec3 h = grazing_half();
  const SphereBasis e = sphere_tangent_basis(h);
  // The basis is orthonormal and tangent to the sphere at h.
  EXPECT_NEAR(dot(e.e_theta, h), 0.0, 1e-15);
  EXPECT_NEAR(dot(e.e_phi, h), 0.0, 1e-15);
  EXPECT_NEAR(dot(e.e_theta, e.e_phi), 0.0, 1e-15);
  EXPECT_TRUE(near_rel(length(e.e_theta), 1.0));
  EXPECT_TRUE(near_rel(length(e.e_phi), 1.0));
  for (const Vec2 c : {Vec2{1, 0}, Vec2{0, 1}, Vec2{0.3, -0.7}}) {
    const Vec3 dh = c.x * e.e_theta + c.y * e.e_phi;
    const Vec2 ds = slope_differential(h, dh);
    const Vec2 dp = projected_differential(h, dh);
    // d(proj) = J_sphere_to_projected c (Eq. 4), d(slope) = J_proj_to_slope d(proj) (Eq. 6)
    // = J_sphere_to_slope c (Eq. 7). Entries are O(1 / hz^3) = O(16): relative 1e-12.
    const Vec2 dp_j = J_sphere_to_projected(h) * c;
    const Vec2 ds_j = J_projected_to_slope(h) * dp;
    const Vec2 ds_k = J_sphere_to_slope(h) * c;
    EXPECT_NEAR(dp.x, dp_j.x, 1e-14);
    EXPECT_NEAR(dp.y, dp_j.y, 1e-14);
    EXPECT_NEAR(ds.x, ds_j.x, 1e-12 * 16);
    EXPECT_NEAR(ds.y, ds_j.y, 1e-12 * 16);
    EXPECT_NEAR(ds.x, ds_k.x, 1e-12 * 16);
    EXPECT_NEAR(ds.y, ds_k.y, 1e-12 * 16);
    // The exact differential against a central difference of half_vector_slope along the
    // geodesic-ish path normalize(h +- eps dh): truncation O(eps^2 |d3 slope|) ~ 1e-10 * 1e2,
    // rounding ~1e-16 * 16 / eps ~ 1e-10, so 1e-7 absolute is a safe bound with margin.
    const double eps = 1e-5;
    const Vec2 fd = (half_vector_slope(normalize(h + eps * dh)) - half_vector_slope(normalize(h - eps * dh))) / (2.0 * eps);
    EXPECT_NEAR(ds.x, fd.x, 1e-7);
    EXPECT_NEAR(ds.y, fd.y, 1e-7);
  }
}

TEST(Jacobians, DeterminantsAreThoseOfSections31And32) {
  for (const double hz : {0.9, 0.4, 0.1}) {
    const double s = std::sqrt(1.0 - hz * hz);
    const Vec3 h{s * std::cos(1.1), s * std::sin(1.1), hz};
    // det J_sphere_to_projected = (hx hz hx + hy hy hz) / s^2 = hz (hx^2 + hy^2) / s^2 = hz.
    EXPECT_TRUE(near_rel(determinant(J_sphere_to_projected(h)), hz));
    // det J_sphere_to_slope = (hx^2 hz + hy^2 hz) / (hz^4 s^2) = 1 / hz^3 (T&K19 Sec. 3.1).
    EXPECT_TRUE(near_rel(determinant(J_sphere_to_slope(h)), 1.0 / (hz * hz * hz)));
    // det J_proj_to_slope = ((1 - hy^2)(1 - hx^2) - hx^2 hy^2) / hz^6 = hz^2 / hz^6 = hz^-4.
    // Relative tolerance 1e-11 at hz = 0.1: (1 - hy^2)(1 - hx^2) - hx^2 hy^2 cancels from
    // ~1 to hz^2 = 0.01, amplifying the rounding by ~100.
    EXPECT_TRUE(near_rel(determinant(J_projected_to_slope(h)), std::pow(hz, -4.0), 1e-11));
  }
}

TEST(Jacobians, SigmaDeterminantRatiosFromTheReferenceVariants) {
  const Params p;
  const Vec3 h = grazing_half();  // hz = 0.4
  const double hz = h.z;
  const SphereBasis e = sphere_tangent_basis(h);
  // Screen derivatives of h: arc-length coefficients (a, b) on (e_theta, e_phi).
  const Vec2 cu{0.03, 0.01}, cv{-0.01, 0.02};
  const Vec3 dhu = cu.x * e.e_theta + cu.y * e.e_phi;
  const Vec3 dhv = cv.x * e.e_theta + cv.y * e.e_phi;
  const Vec2 alpha2{0.001, 0.002};
  const Sym2 diag{alpha2.x, 0.0, alpha2.y};
  const Sym2 k_slope = forward_aniso_slope(p, alpha2, slope_differential(h, dhu), slope_differential(h, dhv)) - diag;
  const Sym2 k_proj = forward_aniso_projected(p, alpha2, projected_differential(h, dhu), projected_differential(h, dhv)) - diag;
  // Kernel on the sphere (the arc-length coefficients as the rows of Delta).
  const Sym2 k_sphere = (2.0 * p.sigma2) * sym2_from_derivative_rows(cu, cv);
  // Rows map as d -> J d, so Delta -> Delta J^T and Delta^T Delta -> J Delta^T Delta J^T:
  // det scales by det(J)^2.
  //   slope / sphere: (1/hz^3)^2 = hz^-6;  projected / sphere: hz^2;
  //   slope / projected: (det J_proj_to_slope)^2 = hz^-8.
  // Tolerance 1e-11: subtracting diag(alpha^2) (1e-3) from A loses up to ~1 digit on the
  // projected kernel entries (~1e-4), and the 2x2 determinants and the ratio of two of them
  // lose about one more (measured agreement: better than 1e-13).
  const double ds = sym2_determinant(k_slope), dp = sym2_determinant(k_proj), dsp = sym2_determinant(k_sphere);
  EXPECT_TRUE(near_rel(ds / dsp, std::pow(hz, -6.0), 1e-11));
  EXPECT_TRUE(near_rel(dp / dsp, hz * hz, 1e-11));
  EXPECT_TRUE(near_rel(ds / dp, std::pow(hz, -8.0), 1e-11));
  // The whole matrices, not only the determinants: kernel_slope = J kernel_proj J^T.
  expect_sym2_near(k_slope, congruence(J_projected_to_slope(h), k_proj), 1e-11);
  std::printf(
      "[ info ] hz = 0.4: det(Sigma_slope)/det(Sigma_proj) = %.6g (hz^-8 = %.6g), "
      "det(Sigma_slope)/det(Sigma_sphere) = %.6g (hz^-6 = %.6g)\n",
      ds / dp, std::pow(hz, -8.0), ds / dsp, std::pow(hz, -6.0));
}

// =============================================================================================
// Eq. 3 and the tangent-free maximum eigenvalue.

TEST(Eq3, DerivativeOfTheAverageNormalInTangentSpaceHasLengthOfTheChord) {
  // Two unit normals of contiguous pixels, 2 theta_u apart.
  const Vec3 n = normalize(Vec3{0.2, -0.1, 1.0});
  const Vec3 nu = normalize(Vec3{-0.15, 0.3, 0.9});
  const Vec3 avg = normalize(n + nu);  // n-bar_u, on the great circle, bisecting
  const double theta_u = std::acos(dot(n, avg));
  EXPECT_TRUE(near_rel(std::acos(dot(nu, avg)), theta_u, 1e-12));
  // (acos at cos ~ 0.98 has condition number ~25: a few ulp, far inside 1e-12.)
  // Chord: |n - nu| = 2 sin(angle / 2) = 2 sin(theta_u).
  EXPECT_TRUE(near_rel(length(n - nu), 2.0 * std::sin(theta_u), 1e-12));
  // Fig. 5: express n-bar_u in the tangent frames of n and of nu, related by the minimal
  // rotation taking n to nu (t along the great circle, b = the rotation axis). In the frame of
  // n, n-bar_u = (sin theta_u, 0, cos theta_u); in the frame of nu, (-sin theta_u, 0, cos
  // theta_u). The derivative of the projected average normal has length 2 sin theta_u.
  const Vec3 b = normalize(cross(n, nu));
  const Frame fn{normalize(nu - dot(nu, n) * n), b, n};
  const Frame fu{normalize(nu * dot(n, nu) - n), b, nu};  // t of nu: away from n
  const Vec2 pn = to_tangent_space(avg, fn.t, fn.b, fn.n).xy();
  const Vec2 pu = to_tangent_space(avg, fu.t, fu.b, fu.n).xy();
  EXPECT_TRUE(near_rel(pn.x, std::sin(theta_u), 1e-12));
  EXPECT_TRUE(near_rel(pu.x, -std::sin(theta_u), 1e-12));
  EXPECT_TRUE(near_rel(length(pn - pu), length(n - nu), 1e-12));
}

TEST(TangentFree, EqualsDeferredMaxWhenDerivativesLieInTheFramePlane) {
  const Params p;
  // Frame normal z; derivatives with z = 0 are unchanged by the projection onto xy, and
  // Delta Delta^T (Gram) and Delta^T Delta have the same eigenvalues.
  const Vec3 dx{0.1, -0.05, 0.0}, dy{0.02, 0.08, 0.0};
  // By hand: Delta^T Delta = [0.01 + 0.0004, -0.005 + 0.0016; ., 0.0025 + 0.0064]
  //   = [0.0104 -0.0034; -0.0034 0.0089]; lambda_max = 0.00965 + sqrt(0.00075^2 + 0.0034^2)
  //   = 0.00965 + sqrt(1.21225e-5) = 0.00965 + 0.00348173... = 0.01313173...
  // (Gram = Delta Delta^T = [0.0125 -0.002; -0.002 0.0068]: 0.00965 + sqrt(0.00285^2 +
  // 0.002^2) = 0.00965 + sqrt(1.21225e-5), the same.)
  const double lmax = 0.00965 + std::sqrt(1.21225e-5);
  const double expected = 0.02 + 2.0 * 0.25 * lmax;
  EXPECT_TRUE(near_rel(deferred_max(p, 0.02, dx.xy(), dy.xy()), expected));
  EXPECT_TRUE(near_rel(deferred_max_tangent_free(p, 0.02, dx, dy), expected));
  // A frame rotated about z is an isometry of the plane too.
  const Vec3 t{std::cos(0.7), std::sin(0.7), 0}, bt{-std::sin(0.7), std::cos(0.7), 0}, nz{0, 0, 1};
  EXPECT_TRUE(near_rel(deferred_max(p, 0.02, to_tangent_space(dx, t, bt, nz).xy(), to_tangent_space(dy, t, bt, nz).xy()), expected));
}

TEST(TangentFree, IsAtLeastDeferredMaxBecauseProjectionContracts) {
  const Params p;
  // dx = (0.1, 0, 0.08), dy = (0, 0.05, 0.03), frame (x, y, z).
  // Projected: rows (0.1, 0), (0, 0.05): lambda_max = 0.01, 2 sigma^2 lambda = 0.005.
  // Gram: [0.0164 0.0024; 0.0024 0.0034]: lambda_max = 0.0099 + sqrt(0.0065^2 + 0.0024^2)
  //     = 0.0099 + sqrt(4.801e-5) = 0.0168289...; 2 sigma^2 lambda = 0.00841447...
  const Vec3 dx{0.1, 0, 0.08}, dy{0, 0.05, 0.03};
  const double a = 0.01;
  const double tangent = deferred_max(p, a, dx.xy(), dy.xy());
  const double tfree = deferred_max_tangent_free(p, a, dx, dy);
  EXPECT_TRUE(near_rel(tangent, 0.015));
  EXPECT_TRUE(near_rel(tfree, a + 0.5 * (0.0099 + std::sqrt(4.801e-5))));
  EXPECT_GT(tfree, tangent);
  std::printf(
      "[ info ] tangent-free max %.9f vs tangent-space max %.9f: difference %.3g "
      "(alpha^2 domain)\n",
      tfree, tangent, tfree - tangent);
  // Random: Gram(D) - Gram(P D) = D (I - P^T P) D^T is positive semi-definite, so the largest
  // eigenvalue can only shrink under the projection (1e-15 absolute for rounding).
  std::mt19937_64 rng(17);
  double largest_gap = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 rx = random_vec3(rng, 0.3), ry = random_vec3(rng, 0.3);
    const double f = deferred_max_tangent_free(p, 0.0, rx, ry);
    const double g = deferred_max(p, 0.0, rx.xy(), ry.xy());
    EXPECT_GE(f + 1e-15, g);
    largest_gap = std::max(largest_gap, f - g);
  }
  std::printf(
      "[ info ] largest tangent-free minus tangent-space gap over 2000 random "
      "derivative pairs (|component| <= 0.3, kappa clamp included): %.4f\n",
      largest_gap);
  // Unit-normal derivatives of a curved surface, computed as a GPU does (differences of unit
  // normals), leave the tangent plane only to second order: the two forms agree closely.
  const Vec3 n0 = normalize(Vec3{0.1, 0.2, 1.0});
  const Vec3 n1 = normalize(Vec3{0.15, 0.2, 1.0});
  const Vec3 n2 = normalize(Vec3{0.1, 0.26, 1.0});
  const Frame f = frame_from_normal(n0);
  const Vec3 ex = n1 - n0, ey = n2 - n0;
  const double ws = deferred_max_tangent_free(p, 0.0, ex, ey);
  const double ts = deferred_max(p, 0.0, to_tangent_space(ex, f.t, f.b, f.n).xy(), to_tangent_space(ey, f.t, f.b, f.n).xy());
  std::printf(
      "[ info ] curved-surface example: tangent-free %.6e, tangent-space %.6e, "
      "relative difference %.3g\n",
      ws, ts, (ws - ts) / ts);
  EXPECT_GE(ws, ts);
  EXPECT_LT((ws - ts) / ts, 1e-2);  // second order in |dn| ~ 0.05: ~|dn|^2 / 4 relative
}

// =============================================================================================
// Projected-space variant (Tokuyoshi & Kaplanyan 2021).

TEST(ProjectedSpace, MapsThroughPAndBack) {
  const Params p;
  // dx = (0.2, 0, 0), dy = (0, 0.2, 0): k = 2 * 0.25 * (0.04 + 0.04) = 0.04 (< kappa).
  const Vec3 dx{0.2, 0, 0}, dy{0, 0.2, 0};
  const double k = 0.04;
  // alpha^2 = 0: p = 0, p' = k, alpha'^2 = k / (1 + k) = 0.04 / 1.04 = 0.0384615...
  EXPECT_TRUE(near_rel(deferred_projected_space(p, 0.0, dx, dy), k / (1.0 + k)));
  // alpha^2 = 1: k (1 - 1) = 0, (1 + 0) / (1 + 0) = 1 exactly.
  EXPECT_EQ(deferred_projected_space(p, 1.0, dx, dy), 1.0);
  for (const double a : {0.01, 0.3, 0.7, 0.99}) {
    // The long way: p = a / (1 - a), p' = p + k, alpha'^2 = p' / (1 + p').
    const double pp = a / (1.0 - a) + k;
    const double long_way = pp / (1.0 + pp);
    // 1e-12 relative: at a = 0.99, 1 - a is exact (Sterbenz) and p ~ 99 carries ~1e-16.
    EXPECT_TRUE(near_rel(deferred_projected_space(p, a, dx, dy), long_way));
    // The kernel is scaled by (1 - a) / (1 + k (1 - a)) <= 1 in the alpha^2 domain:
    // alpha'^2 - a = k (1 - a)^2 / (1 + k (1 - a)), so never above deferred_sum's a + k.
    const double scaled = k * (1 - a) * (1 - a) / (1.0 + k * (1 - a));
    // 1e-10: at a = 0.99 the difference is ~4e-6 while alpha'^2 carries ~1e-16 absolute
    // rounding, so the subtraction leaves ~3e-11 relative.
    EXPECT_TRUE(near_rel(deferred_projected_space(p, a, dx, dy) - a, scaled, 1e-10));
    EXPECT_LE(deferred_projected_space(p, a, dx, dy), deferred_sum(p, a, dx, dy));
  }
  std::mt19937_64 rng(19);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 rx = random_vec3(rng, 1.0), ry = random_vec3(rng, 1.0);
    const double a = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    const double r = deferred_projected_space(p, a, rx, ry);
    EXPECT_LE(r, deferred_sum(p, a, rx, ry));
    EXPECT_GE(r, a);
    EXPECT_LE(r, 1.0);
  }
}

// =============================================================================================
// BRDFs.

TEST(Ggx, MatrixFormWithDiagonalAEqualsAxisForm) {
  const Vec2 a2{0.04, 0.25};
  const Sym2 a{0.04, 0.0, 0.25};
  const double tau = ndf_clamp_tau(a2);  // = det A: the clamp does not change anything
  EXPECT_EQ(tau, 0.04 * 0.25);
  std::mt19937_64 rng(23);
  for (int k = 0; k < 500; ++k) {
    const Vec3 h = random_unit_upper(rng);
    // adj(A) h.xy / det = (0.25 hx^2 + 0.04 hy^2) / 0.01 = hx^2 / 0.04 + hy^2 / 0.25.
    EXPECT_TRUE(near_rel(ggx_ndf_matrix(h, a, tau), ggx_ndf_axis(h, a2), 1e-12));
    EXPECT_TRUE(near_rel(ggx_lambda_matrix(h, a), ggx_lambda_axis(h, a2), 1e-12, 1.0));
    EXPECT_TRUE(near_rel(beckmann_ndf_matrix(h, a, tau), beckmann_ndf_axis(h, a2), 1e-12, 1e-300));
    const Vec3 o = random_unit_upper(rng);
    EXPECT_TRUE(near_rel(ggx_brdf_matrix(h, o, a, tau), ggx_brdf_axis(h, o, a2), 1e-12));
    EXPECT_TRUE(near_rel(beckmann_brdf_matrix(h, o, a, tau), beckmann_brdf_axis(h, o, a2), 1e-12));
  }
  // A value by hand: h = z: D = 1 / (pi ax ay * 1) = 1 / (pi * 0.2 * 0.5) = 10 / pi.
  EXPECT_TRUE(near_rel(ggx_ndf_axis(Vec3{0, 0, 1}, a2), 10.0 / kPi));
  EXPECT_TRUE(near_rel(ggx_ndf_matrix(Vec3{0, 0, 1}, a, tau), 10.0 / kPi));
  // Below the horizon: 0.
  EXPECT_EQ(ggx_ndf_matrix(Vec3{0, 0.6, -0.8}, a, tau), 0.0);
  EXPECT_EQ(ggx_brdf_matrix(Vec3{0, 0.6, -0.8}, Vec3{0, 0, 1}, a, tau), 0.0);
}

TEST(Ggx, NdfIntegratesToOneInProjectedArea) {
  // int D(h) hz d omega = 1 (projected microfacet area equals the macro-surface area).
  // Quadrature error: the GGX integrand is a rational function of r on [0, 1] with its peak
  // width ~ alpha >= 0.22 here; 64 panels x 16 Gauss points in r and 512 points in phi (the
  // periodic trapezoid rule) converge to rounding: measured |I - 1| <= 4e-15, and halving
  // both resolutions moves I by <= 2e-15. Summing ~5e5 terms of O(1) accumulates at most
  // ~1e-13 of rounding, so 1e-12 leaves margin while still catching any wrong constant
  // (e.g. a factor 2 or a pi) by many orders of magnitude.
  struct Case {
    const char* name;
    Sym2 a;
  };
  const Case cases[] = {
      {"isotropic 0.25", Sym2{0.25, 0.0, 0.25}},
      {"anisotropic diag(0.05, 0.3)", Sym2{0.05, 0.0, 0.3}},
      {"rotated 30 deg", rotated_matrix(0.05, 0.3, kPi / 6.0)},
      {"rotated 100 deg, filtered", rotated_matrix(0.08, 0.6, 1.745)},
  };
  for (const Case& c : cases) {
    auto ndf = [&](Vec3 h) { return ggx_ndf_matrix(h, c.a, 0.0); };
    const double fine = integrate_projected_area(ndf, 64, 16, 512);
    const double coarse = integrate_projected_area(ndf, 32, 16, 256);
    EXPECT_NEAR(fine, coarse, 1e-12) << c.name;
    EXPECT_NEAR(fine, 1.0, 1e-12) << c.name;
  }
  // The axis form too.
  auto axis = [](Vec3 h) { return ggx_ndf_axis(h, Vec2{0.05, 0.3}); };
  EXPECT_NEAR(integrate_projected_area(axis, 64, 16, 512), 1.0, 1e-12);
}

TEST(Ggx, TauClampReplacesTheDeterminant) {
  // A = diag(0.01, 0.01): det = 1e-4 < tau = 0.02 * 0.02 = 4e-4.
  const Sym2 a{0.01, 0.0, 0.01};
  const double tau = ndf_clamp_tau(Vec2{0.02, 0.02});
  EXPECT_EQ(tau, 0.02 * 0.02);
  const Vec3 h = normalize(Vec3{0.1, 0.05, 1.0});
  // Formula with det -> tau: q = (A11 hx^2 - 2 A01 hx hy + A00 hy^2) / tau + hz^2
  //   = 0.01 (hx^2 + hy^2) / 4e-4 + hz^2 = 25 (hx^2 + hy^2) + hz^2;
  // D = 1 / (pi sqrt(tau) q^2) = 1 / (pi 0.02 q^2).
  const double q = 25.0 * (h.x * h.x + h.y * h.y) + h.z * h.z;
  EXPECT_TRUE(near_rel(ggx_ndf_matrix(h, a, tau), 1.0 / (kPi * 0.02 * q * q)));
  // Beckmann: exp(-25 (sx^2 + sy^2)) / (pi 0.02 hz^4), s = h.xy / hz.
  const double s2 = (h.x * h.x + h.y * h.y) / (h.z * h.z);
  EXPECT_TRUE(near_rel(beckmann_ndf_matrix(h, a, tau), std::exp(-25.0 * s2) / (kPi * 0.02 * std::pow(h.z, 4.0))));
  // With det >= tau the clamp is inactive: the matrix form equals the axis form.
  EXPECT_TRUE(near_rel(ggx_ndf_matrix(h, a, 1e-6), ggx_ndf_axis(h, Vec2{0.01, 0.01})));
  // At h = z: D(z) = 1 / (pi sqrt(max(det, tau))): 1 / (0.02 pi) clamped vs 1 / (0.01 pi).
  EXPECT_TRUE(near_rel(ggx_ndf_matrix(Vec3{0, 0, 1}, a, tau), 1.0 / (0.02 * kPi)));
  EXPECT_TRUE(near_rel(ggx_ndf_matrix(Vec3{0, 0, 1}, a, 0.0), 1.0 / (0.01 * kPi)));
}

TEST(Ggx, LambdaAndG2) {
  const Sym2 a = rotated_matrix(0.05, 0.4, 0.5);
  // Normal incidence: -0.5 + sqrt(0 + 1) / (2 * 1) = 0 exactly.
  EXPECT_EQ(ggx_lambda_matrix(Vec3{0, 0, 1}, a), 0.0);
  EXPECT_EQ(ggx_lambda_axis(Vec3{0, 0, 1}, Vec2{0.3, 0.7}), 0.0);
  EXPECT_EQ(beckmann_lambda_matrix(Vec3{0, 0, 1}, a), 0.0);  // projected roughness 0 guard
  EXPECT_EQ(ggx_g2_matrix(Vec3{0, 0, 1}, Vec3{0, 0, 1}, Vec3{0, 0, 1}, a), 1.0);
  // A hand value: isotropic alpha^2 = 0.25, w at 60 deg: w = (sqrt(3)/2, 0, 1/2):
  // Lambda = -0.5 + sqrt(0.25 * 0.75 + 0.25) / 1 = -0.5 + sqrt(0.4375) = 0.161437...
  const Vec3 w60{std::sqrt(3.0) / 2.0, 0.0, 0.5};
  EXPECT_TRUE(near_rel(ggx_lambda_matrix(w60, Sym2{0.25, 0, 0.25}), -0.5 + std::sqrt(0.4375)));
  std::mt19937_64 rng(29);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 i = random_unit_upper(rng, 0.01), o = random_unit_upper(rng, 0.01);
    const Vec3 h = normalize(i + o);
    const double g2 = ggx_g2_matrix(i, o, h, a);
    // Lambda >= 0 because w.xy^T A w.xy >= 0 makes the sqrt >= |wz|: G2 in (0, 1].
    EXPECT_GT(g2, 0.0);
    EXPECT_LE(g2, 1.0);
    EXPECT_GE(ggx_lambda_matrix(i, a), 0.0);
  }
  // chi+: a half vector facing away from i gives 0.
  EXPECT_EQ(ggx_g2_matrix(Vec3{0, 0, 1}, Vec3{0, 0, 1}, Vec3{0, 0, -1}, a), 0.0);
}

TEST(Beckmann, WalterFitErrorOnG1) {
  // G1 = 1 / (1 + Lambda). Compare Walter et al.'s fit with the exact erf form over
  // a in [1e-4, 10] (tan theta / alpha from 1e4 to 0.1), 2e5 log-spaced points.
  // Sanity of the exact form: Lambda(a) -> 1 / (2 a sqrt(pi)) for small a, -> 0 for large a.
  EXPECT_TRUE(near_rel(beckmann_lambda_exact(1e-6), 1.0 / (2e-6 * std::sqrt(kPi)), 1e-5));
  // At a = 1: (erf(1) - 1) / 2 + e^-1 / (2 sqrt(pi)) with erf(1) = 0.8427007929497149 and
  // e^-1 = 0.36787944117144233: -0.0786496035251426 + 0.1037768743551487 = 0.0251272708300061.
  EXPECT_NEAR(beckmann_lambda_exact(1.0), 0.0251272708300061, 1e-15);
  double worst = 0.0, worst_a = 0.0, most_negative = 0.0;
  const int n = 200000;
  for (int k = 0; k <= n; ++k) {
    const double a = std::pow(10.0, -4.0 + 5.0 * k / n);
    const double g_fit = 1.0 / (1.0 + beckmann_lambda_from_a(a));
    const double g_exact = 1.0 / (1.0 + beckmann_lambda_exact(a));
    const double err = std::fabs(g_fit - g_exact) / g_exact;
    if (err > worst) {
      worst = err;
      worst_a = a;
    }
    most_negative = std::min(most_negative, beckmann_lambda_from_a(a));
  }
  std::printf(
      "[ info ] Walter fit: max relative error of G1 = %.4e at a = %.4f; "
      "most negative fitted Lambda = %.3e\n",
      worst, worst_a, most_negative);
  // Measured 3.13e-3 at a ~ 1.336 (the grid step is 5.8e-5 relative in a and the error is
  // smooth there, so the true maximum is within ~1e-7 of the grid's). Bound: 3.2e-3, i.e. the
  // fit is good to a third of a percent in G1, well inside the "~1e-2" usually quoted.
  EXPECT_LT(worst, 3.2e-3);
  EXPECT_GT(worst, 3.0e-3);  // and the measurement is what we say it is
  // The fit's numerator 1 - 1.259 a + 0.396 a^2 has roots a = (1.259 +- sqrt(1.259^2 -
  // 4 * 0.396)) / 0.792 = 1.548 and 1.631: just below the 1.6 cut-off the fitted Lambda is
  // slightly negative (G1 slightly above 1, by < 1e-4).
  EXPECT_LT(beckmann_lambda_from_a(1.58), 0.0);
  EXPECT_GT(most_negative, -1e-4);
  EXPECT_EQ(beckmann_lambda_from_a(1.6), 0.0);
}

TEST(Beckmann, MatrixNdfIntegratesToOneInProjectedArea) {
  // Slope-space Gaussian exp(-s^T A^-1 s) / (pi sqrt(det A)) integrates to 1 over R^2; in the
  // disk parameterisation the integrand is smooth and vanishes to all orders at r = 1. Same
  // quadrature and tolerance reasoning as for GGX.
  const Sym2 cases[] = {Sym2{0.25, 0, 0.25}, Sym2{0.05, 0, 0.3}, rotated_matrix(0.05, 0.3, kPi / 6.0), rotated_matrix(0.1, 0.5, 2.0)};
  for (const Sym2& a : cases) {
    auto ndf = [&](Vec3 h) { return beckmann_ndf_matrix(h, a, 0.0); };
    const double fine = integrate_projected_area(ndf, 64, 16, 512);
    const double coarse = integrate_projected_area(ndf, 32, 16, 256);
    EXPECT_NEAR(fine, coarse, 1e-12);
    EXPECT_NEAR(fine, 1.0, 1e-12);
  }
}

// =============================================================================================
// Quad derivatives.

TEST(QuadDerivatives, LinearFieldGivesExactCoefficients) {
  // f(x, y) = a + b x + c y on pixels (0,0), (1,0), (0,1), (1,1) with dyadic a, b, c: every
  // value and difference is exact. Coarse and fine: b along x, c along y, at every pixel.
  const double a = 0.75, b = -0.375, c = 2.5;
  auto f = [&](double x, double y) { return a + b * x + c * y; };
  const Quad<double> q{f(0, 0), f(1, 0), f(0, 1), f(1, 1)};
  EXPECT_EQ(ddx_coarse(q), b);
  EXPECT_EQ(ddy_coarse(q), c);
  for (int px = 0; px < 4; ++px) {
    EXPECT_EQ(ddx_fine(q, px), b);
    EXPECT_EQ(ddy_fine(q, px), c);
    EXPECT_EQ(ddx(q, px, Derivative::coarse), b);
    EXPECT_EQ(ddy(q, px, Derivative::fine), c);
  }
  EXPECT_THROW(ddx_fine(q, 4), std::out_of_range);
}

TEST(QuadDerivatives, FineDdxOfProductFieldDiffersBetweenRows) {
  // f = x y: values 0, 0, 0, 1. df/dx = y: fine ddx is 0 on the top row (y = 0) and 1 on the
  // bottom row (y = 1); coarse ddx takes the top row everywhere (0). Symmetrically for ddy:
  // fine 0 in the left column, 1 in the right one; coarse 0.
  const Quad<double> q{0.0, 0.0, 0.0, 1.0};
  EXPECT_EQ(ddx_fine(q, kTopLeft), 0.0);
  EXPECT_EQ(ddx_fine(q, kTopRight), 0.0);
  EXPECT_EQ(ddx_fine(q, kBottomLeft), 1.0);
  EXPECT_EQ(ddx_fine(q, kBottomRight), 1.0);
  EXPECT_EQ(ddy_fine(q, kTopLeft), 0.0);
  EXPECT_EQ(ddy_fine(q, kBottomLeft), 0.0);
  EXPECT_EQ(ddy_fine(q, kTopRight), 1.0);
  EXPECT_EQ(ddy_fine(q, kBottomRight), 1.0);
  EXPECT_EQ(ddx(q, kBottomRight, Derivative::coarse), 0.0);
  EXPECT_EQ(ddy(q, kBottomRight, Derivative::coarse), 0.0);
}

TEST(QuadDerivatives, ListingThreeNeighbourNormalIsTheMeanOfTheEdgeNeighbours) {
  // Dyadic vectors keep every sum exact. w = 0.5 - 2 frac(floor(p) / 2) = +0.5 at even,
  // -0.5 at odd coordinates. Top-left: n_tl + 0.5 (n_tr - n_tl) + 0.5 (n_bl - n_tl)
  // = 0.5 (n_tr + n_bl); top-right: n_tr - 0.5 (n_tr - n_tl) + 0.5 (n_br - n_tr)
  // = 0.5 (n_tl + n_br); likewise bottom-left 0.5 (n_tl + n_br), bottom-right 0.5 (n_tr + n_bl).
  const Quad<Vec3> n{Vec3{0.25, 0.5, 1}, Vec3{0.5, 0.5, 1}, Vec3{0.25, 0.75, 1}, Vec3{0.625, 0.875, 1}};
  const Quad<Vec2> fc = frag_coords(10, 20);
  const Vec3 diag_a = 0.5 * (n.top_right + n.bottom_left);
  const Vec3 diag_b = 0.5 * (n.top_left + n.bottom_right);
  EXPECT_EQ(quad_average_normal_quad(n, fc, kTopLeft), diag_a);
  EXPECT_EQ(quad_average_normal_quad(n, fc, kBottomRight), diag_a);
  EXPECT_EQ(quad_average_normal_quad(n, fc, kTopRight), diag_b);
  EXPECT_EQ(quad_average_normal_quad(n, fc, kBottomLeft), diag_b);
}

// =============================================================================================
// Fragment wrappers on quads.

TEST(QuadWrappers, DeferredIsotropicWrappersUseTheQuadDifferences) {
  const Params p;
  const Quad<Vec3> n = sphere_normals(8, 12);
  const Vec3 cx = ddx_coarse(n), cy = ddy_coarse(n);
  for (int px = 0; px < 4; ++px) {
    EXPECT_EQ(deferred_sum_fragment_quad(p, 0.1, n, px), deferred_sum(p, 0.1, cx, cy));
    EXPECT_EQ(deferred_avg_fragment_quad(p, 0.1, n, px), deferred_avg(p, 0.1, cx, cy));
    EXPECT_EQ(deferred_max_tangent_free_fragment_quad(p, 0.1, n, px), deferred_max_tangent_free(p, 0.1, cx, cy));
    EXPECT_EQ(deferred_projected_space_fragment_quad(p, 0.1, n, px), deferred_projected_space(p, 0.1, cx, cy));
    EXPECT_EQ(deferred_sum_fragment_quad(p, 0.1, n, px, Derivative::fine), deferred_sum(p, 0.1, ddx_fine(n, px), ddy_fine(n, px)));
  }
  // The field is curved, so the bottom-right pixel's fine differences differ from coarse.
  EXPECT_NE(deferred_sum_fragment_quad(p, 0.0, n, kBottomRight, Derivative::fine),
            deferred_sum_fragment_quad(p, 0.0, n, kBottomRight, Derivative::coarse));
  // Magnitude by hand: n = normalize(u, v, 1), u = (x - 16)/20 = -0.375, v = -0.175 at the
  // top-left centre (8.5, 12.5). |dn/du| = sqrt(1 + v^2) / (1 + u^2 + v^2) = 1.0152 / 1.1712
  // = 0.867, |dn/dv| = sqrt(1 + u^2) / 1.1712 = 0.912; du = dv = 1/20 per pixel, so
  // |ddx n| ~ 0.0433, |ddy n| ~ 0.0456 and the kernel 2 * 0.25 * (0.0433^2 + 0.0456^2)
  // ~ 1.98e-3 (first order; the one-pixel differences shift it by a few percent).
  const double k = deferred_sum_fragment_quad(p, 0.0, n, kTopLeft);
  EXPECT_GT(k, 1.5e-3);
  EXPECT_LT(k, 2.6e-3);
}

TEST(QuadWrappers, DeferredPreviousAndMaxSeeCurvatureThroughThePerPixelFrame) {
  const Params p;
  const Quad<Vec2> fc = frag_coords(8, 12);
  const Quad<Vec3> n = sphere_normals(8, 12);
  const Quad<Frame> frames = map(n, frame_from_normal);
  const Quad<Vec3> t = map(frames, [](const Frame& f) { return f.t; });
  const Quad<Vec3> b = map(frames, [](const Frame& f) { return f.b; });
  const double sum_kernel = deferred_sum_fragment_quad(p, 0.0, n, kTopLeft);
  for (int px = 0; px < 4; ++px) {
    const double prev = deferred_previous_fragment_quad(p, 0.0, n, t, b, fc, px);
    const double mx = deferred_max_fragment_quad(p, 0.0, n, t, b, fc, px);
    // Nonzero, and of the order of the normal-derivative kernel (Sec. 4.4: the derivative of
    // the average normal in the per-pixel frame has the length of the normal difference).
    EXPECT_GT(prev, 0.3 * sum_kernel) << px;
    EXPECT_LT(prev, 3.0 * sum_kernel) << px;
    EXPECT_GT(mx, 0.3 * sum_kernel) << px;
    EXPECT_LE(mx, sum_kernel * 1.01) << px;  // lambda_max <= trace, up to the frame's error
  }
  std::printf("[ info ] sphere field, top-left pixel: previous %.4e, max %.4e, sum %.4e\n",
              deferred_previous_fragment_quad(p, 0.0, n, t, b, fc, kTopLeft), deferred_max_fragment_quad(p, 0.0, n, t, b, fc, kTopLeft),
              sum_kernel);

  // The degenerate reading: the neighbour-weighted normal expressed in a *fixed* frame. For a
  // normal field linear in the pixel coordinates it is the same vector at all four pixels
  // (see the previous test: 0.5 (n_tr + n_bl) = 0.5 (n_tl + n_br) when n is linear), so its
  // derivative, and the kernel, vanish exactly. Dyadic, unnormalised field: exact arithmetic.
  auto lin = [](double x, double y) { return Vec3{0.25 + 0.125 * x, 0.5 + 0.0625 * y, 1.0}; };
  const Quad<Vec3> nl{lin(0, 0), lin(1, 0), lin(0, 1), lin(1, 1)};
  const Quad<Vec2> fc0 = frag_coords(0, 0);
  // The neighbour-weighted normal is the same vector at all four pixels (exact arithmetic)...
  const Vec3 m0 = quad_average_normal_quad(nl, fc0, kTopLeft);
  for (int px = 1; px < 4; ++px) EXPECT_EQ(quad_average_normal_quad(nl, fc0, px), m0);
  // ...so in the fixed frame (x, y, z) its slope has zero ddx/ddy: alpha^2 is unchanged.
  const Quad<Vec2> fixed_lin = map_indexed(nl, [&](Vec3, int q) {
    const Vec3 m = quad_average_normal_quad(nl, fc0, q);
    return m.xy() / std::fabs(m.z);
  });
  EXPECT_EQ(deferred_previous(p, 0.2, ddx_coarse(fixed_lin), ddy_coarse(fixed_lin)), 0.2);
  // Per-pixel frames of the (normalised) linear field: nonzero kernel.
  const Quad<Vec3> nl_unit = map(nl, [](Vec3 v) { return normalize(v); });
  const Quad<Frame> fl = map(nl_unit, frame_from_normal);
  const double per_pixel = deferred_previous_fragment_quad(p, 0.0, nl_unit, map(fl, [](const Frame& f) { return f.t; }),
                                                           map(fl, [](const Frame& f) { return f.b; }), fc0, kTopLeft);
  EXPECT_GT(per_pixel, 1e-3);
  // And on the sphere field, the fixed frame gives a kernel orders of magnitude smaller than
  // the per-pixel frame (only the field's nonlinearity survives).
  const Vec3 z{0, 0, 1};
  auto fixed_slope = [&](int q) {
    const Vec3 m = to_tangent_space(quad_average_normal_quad(n, fc, q), Vec3{1, 0, 0}, Vec3{0, 1, 0}, z);
    return m.xy() / std::fabs(m.z);
  };
  const Quad<Vec2> s{fixed_slope(0), fixed_slope(1), fixed_slope(2), fixed_slope(3)};
  const double fixed = deferred_previous(p, 0.0, ddx_coarse(s), ddy_coarse(s));
  const double moving = deferred_previous_fragment_quad(p, 0.0, n, t, b, fc, kTopLeft);
  std::printf("[ info ] sphere field: fixed-frame kernel %.3e vs per-pixel-frame %.3e\n", fixed, moving);
  EXPECT_LT(fixed, 1e-3 * moving);
}

TEST(QuadWrappers, FlatNormalFieldGivesZeroKernel) {
  const Params p;
  const Vec3 nflat = normalize(Vec3{0.2, -0.1, 1.0});
  const Quad<Vec3> n{nflat, nflat, nflat, nflat};
  const Frame f = frame_from_normal(nflat);
  const Quad<Vec3> t{f.t, f.t, f.t, f.t}, b{f.b, f.b, f.b, f.b};
  const Quad<Vec2> fc = frag_coords(4, 6);
  // Every difference is exactly 0 (identical values): the kernel is 0 and alpha^2 unchanged.
  for (int px = 0; px < 4; ++px) {
    for (const Derivative m : {Derivative::coarse, Derivative::fine}) {
      EXPECT_EQ(deferred_previous_fragment_quad(p, 0.3, n, t, b, fc, px, m), 0.3);
      EXPECT_EQ(deferred_max_fragment_quad(p, 0.3, n, t, b, fc, px, m), 0.3);
      EXPECT_EQ(deferred_sum_fragment_quad(p, 0.3, n, px, m), 0.3);
      EXPECT_EQ(deferred_avg_fragment_quad(p, 0.3, n, px, m), 0.3);
      EXPECT_EQ(deferred_max_tangent_free_fragment_quad(p, 0.3, n, px, m), 0.3);
      EXPECT_EQ(deferred_projected_space_fragment_quad(p, 0.3, n, px, m), 0.3);
    }
  }
}

TEST(QuadWrappers, ForwardWrappersDifferentiateTheHalfVectorCoordinates) {
  const Params p;
  // Half vectors of a quad: h(x, y) = normalize(0.3 + 0.02 x, -0.2 + 0.03 y, 0.5).
  auto hv = [](double x, double y) { return normalize(Vec3{0.3 + 0.02 * x, -0.2 + 0.03 * y, 0.5}); };
  const Quad<Vec3> h{hv(0, 0), hv(1, 0), hv(0, 1), hv(1, 1)};
  const Vec2 a2{0.01, 0.02};
  const Quad<Vec2> proj = map(h, half_vector_projected);
  const Quad<Vec2> slope = map(h, half_vector_slope);
  for (int px = 0; px < 4; ++px) {
    EXPECT_EQ(forward_aniso_projected_fragment_quad(p, a2, h, px), forward_aniso_projected(p, a2, ddx_coarse(proj), ddy_coarse(proj)));
    EXPECT_EQ(forward_aniso_slope_fragment_quad(p, a2, h, px), forward_aniso_slope(p, a2, ddx_coarse(slope), ddy_coarse(slope)));
    EXPECT_EQ(forward_axis_projected_fragment_quad(p, a2, h, px, Derivative::fine),
              forward_axis_projected(p, a2, ddx_fine(proj, px), ddy_fine(proj, px)));
    EXPECT_EQ(forward_axis_slope_fragment_quad(p, a2, h, px, Derivative::fine),
              forward_axis_slope(p, a2, ddx_fine(slope, px), ddy_fine(slope, px)));
  }
  // The slope kernel is the larger one: hz ~ 0.8 here, and the Jacobian scales by ~1/hz^3.
  const Sym2 ks = forward_aniso_slope_fragment_quad(p, Vec2{0, 0}, h, 0);
  const Sym2 kp = forward_aniso_projected_fragment_quad(p, Vec2{0, 0}, h, 0);
  EXPECT_GT(trace(ks), trace(kp));
}

TEST(QuadWrappers, FilteredBrdfWrappersUseTheFilteredMatrixAndTau) {
  const Params p;
  // A light and a view direction varying across the quad (unit vectors, tangent space).
  auto light = [](double x, double y) { return normalize(Vec3{0.4 + 0.03 * x, 0.1 - 0.02 * y, 0.9}); };
  auto view = [](double x, double y) { return normalize(Vec3{-0.2 + 0.01 * y, 0.05 * x, 1.0}); };
  const Quad<Vec3> i{light(0, 0), light(1, 0), light(0, 1), light(1, 1)};
  const Quad<Vec3> o{view(0, 0), view(1, 0), view(0, 1), view(1, 1)};
  const Vec2 a2{0.0004, 0.0009};  // alpha = 0.02, 0.03: small enough for filtering to matter
  const Quad<Vec3> h = map_indexed(i, [&](Vec3 l, int q) { return normalize(l + o[q]); });
  for (int px = 0; px < 4; ++px) {
    const Sym2 a = forward_aniso_projected_fragment_quad(p, a2, h, px);
    const double tau = a2.x * a2.y;
    EXPECT_EQ(ggx_brdf_filtered_fragment_quad(p, i, o, a2, px), ggx_brdf_matrix(i[px], o[px], a, tau));
    EXPECT_EQ(beckmann_brdf_filtered_fragment_quad(p, i, o, a2, px), beckmann_brdf_matrix(i[px], o[px], a, tau));
    // The kernel is positive semi-definite and nonzero here: tr(A) > ax^2 + ay^2.
    EXPECT_GT(trace(a), a2.x + a2.y);
  }
}

// The filtered GGX lobes of brdf.hpp against the exact convolution of GGX with a Gaussian kernel.
//
// The exact filtered slope density is recomputed here by quadrature of GGX's Gaussian scale
// mixture (filtered_ggx_slope_density; its accuracy is checked first against GGX's closed form
// and against a Gaussian's). Distances are taken in slope space, where D(h) cos(theta) d omega =
// P(s) ds: the L1 distance integral |P_model - P_exact| ds is the distance of the NDFs under the
// measure the energy integral uses. Grids: log-spaced slope radii from 1e-4 to 1e5 times the
// lobe's scale (the mass left outside is below alpha^2 / (1e10 alpha'^2) < 1e-9).
//
// Targets: L1 <= 0.03 and the mass beyond 4 sqrt(k) within 25 % of the exact one over alpha^2 in
// [1e-6, 0.5] and k in [0, kappa] (kappa = 0.18: k is the per-axis slope variance, the kernel
// added to alpha^2 is 2k), and energy within 1e-3 of 1.
#include "scale_mixture_quadrature.hpp"

#include "saagen/reference/reference.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

using namespace saagen::ref;

namespace {

constexpr double kKappa = 0.18;

// A slope-space density of (sx, sy), evaluated through an NDF of h = normalize(-sx, -sy, 1):
// P(s) = D(h) cos^4(theta).
using SlopeDensity = std::function<double(double sx, double sy)>;

SlopeDensity from_ndf(std::function<double(Vec3)> ndf) {
  return [ndf](double sx, double sy) {
    const double cos2 = 1.0 / (1.0 + sx * sx + sy * sy);
    const double c = std::sqrt(cos2);
    return ndf({-sx * c, -sy * c, c}) * cos2 * cos2;
  };
}

struct RadialGrid {
  std::vector<double> radius;
  std::vector<double> weight;  // 2 pi rho d rho (isotropic densities)
};

RadialGrid radial_grid(double scale, int count = 400) {
  RadialGrid g;
  const double low = std::log(1e-4 * scale), high = std::log(1e5 * scale);
  const double step = (high - low) / count;
  for (int i = 0; i < count; ++i) {
    const double rho = std::exp(low + (i + 0.5) * step);
    g.radius.push_back(rho);
    g.weight.push_back(2.0 * kPi * rho * rho * step);
  }
  return g;
}

struct LobeDistance {
  double l1 = 0.0;
  double energy = 0.0;
};

// L1 distance of an isotropic density to the exact filtered one, and its total mass.
LobeDistance isotropic_distance(const SlopeDensity& model, double alpha2, double k) {
  const RadialGrid g = radial_grid(std::sqrt(alpha2 + 2.0 * k));
  LobeDistance d;
  for (std::size_t i = 0; i < g.radius.size(); ++i) {
    const double p = model(g.radius[i], 0.0);
    d.l1 += g.weight[i] * std::fabs(p - filtered_ggx_slope_density(g.radius[i], alpha2, k));
    d.energy += g.weight[i] * p;
  }
  return d;
}

// Mass of an isotropic density beyond radius R.
double mass_beyond(const SlopeDensity& model, double radius, double scale) {
  const RadialGrid g = radial_grid(scale, 800);
  double mass = 0.0;
  for (std::size_t i = 0; i < g.radius.size(); ++i)
    if (g.radius[i] > radius) mass += g.weight[i] * model(g.radius[i], 0.0);
  return mass;
}

SlopeDensity tail_preserving(double alpha2, double k) {
  return from_ndf([=](Vec3 h) { return ggx_ndf_filtered_axis(h, {alpha2 + 2.0 * k, alpha2 + 2.0 * k}, {alpha2, alpha2}); });
}

SlopeDensity papers_lobe(double alpha2, double k) {
  return from_ndf([=](Vec3 h) { return ggx_ndf_axis(h, {alpha2 + 2.0 * k, alpha2 + 2.0 * k}); });
}

const std::vector<double> kAlpha2s{1e-6, 1e-5, 6.25e-6, 4e-5, 1e-4, 1e-3, 2.5e-3, 0.01, 0.1, 0.5};
const std::vector<double> kKernels{0.0, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.05, kKappa};

}  // namespace

// The quadrature: k = 0 gives GGX's closed form 1 / (pi alpha^2 (1 + rho^2 / alpha^2)^2), and
// alpha^2 -> 0 a Gaussian of variance k, to 1e-9 relative (trapezoid rule in ln w, step 0.02).
TEST(FilteredGgx, ExactConvolutionQuadrature) {
  for (double alpha2 : {1e-6, 1e-2, 0.5})
    for (double t : {0.0, 0.3, 1.0, 3.0, 100.0}) {
      const double rho = t * std::sqrt(alpha2);
      const double q = 1.0 + rho * rho / alpha2;
      EXPECT_NEAR(filtered_ggx_slope_density(rho, alpha2, 0.0), 1.0 / (kPi * alpha2 * q * q), 1e-9 / (kPi * alpha2 * q * q));
      EXPECT_NEAR(filtered_ggx_mass_beyond(rho, alpha2, 0.0), alpha2 / (alpha2 + rho * rho), 1e-9);
    }
  const double k = 1e-3;
  for (double t : {0.0, 1.0, 3.0}) {
    const double rho = t * std::sqrt(k);
    EXPECT_NEAR(filtered_ggx_slope_density(rho, 1e-30, k), std::exp(-t * t / 2.0) / (2.0 * kPi * k), 1e-9 / k);
  }
}

// The (alpha^2, k) table: L1 and tail mass of the tail-preserving lobe, next to the papers'
// GGX(alpha^2 + 2k). Printed for the documentation (docs/FILTERED_GGX.md).
TEST(FilteredGgx, IsotropicDistanceTailAndEnergy) {
  std::printf("%9s %9s | %8s %8s | %10s %10s %10s | %8s\n", "alpha^2", "k", "L1 saagen", "L1 paper", "tail exact", "saagen", "paper",
              "energy");
  double worst_l1 = 0.0, worst_tail = 0.0, worst_energy = 0.0;
  for (double alpha2 : kAlpha2s)
    for (double k : kKernels) {
      const SlopeDensity model = tail_preserving(alpha2, k);
      const LobeDistance d = isotropic_distance(model, alpha2, k);
      const LobeDistance paper = isotropic_distance(papers_lobe(alpha2, k), alpha2, k);
      const double scale = std::sqrt(alpha2 + 2.0 * k);
      const double radius = 4.0 * std::sqrt(k);
      const double exact_tail = filtered_ggx_mass_beyond(radius, alpha2, k);
      const double model_tail = mass_beyond(model, radius, scale);
      const double paper_tail = (alpha2 + 2.0 * k) / (alpha2 + 2.0 * k + radius * radius);
      std::printf("%9.3g %9.3g | %8.4f %8.4f | %10.4g %10.4g %10.4g | %8.6f\n", alpha2, k, d.l1, paper.l1, exact_tail, model_tail,
                  paper_tail, d.energy);
      EXPECT_LE(d.l1, 0.03) << "alpha^2 " << alpha2 << " k " << k;
      EXPECT_NEAR(model_tail / exact_tail, 1.0, 0.25) << "alpha^2 " << alpha2 << " k " << k;
      EXPECT_NEAR(d.energy, 1.0, 1e-3) << "alpha^2 " << alpha2 << " k " << k;
      worst_l1 = std::max(worst_l1, d.l1);
      worst_tail = std::max(worst_tail, std::fabs(std::log(model_tail / exact_tail)));
      worst_energy = std::max(worst_energy, std::fabs(d.energy - 1.0));
    }
  std::printf("worst: L1 %.4f, tail ratio within %.1f %%, energy within %.2e\n", worst_l1, 100.0 * (std::exp(worst_tail) - 1.0),
              worst_energy);
}

// The papers' lobe fails the same targets (the reason for the mixture): L1 0.2 - 0.4 once the
// kernel dominates alpha^2.
TEST(FilteredGgx, PapersLobeMissesTheTargets) {
  const double alpha2 = 1e-4, k = 1e-3;
  EXPECT_GT(isotropic_distance(papers_lobe(alpha2, k), alpha2, k).l1, 0.3);
  const double radius = 4.0 * std::sqrt(k);
  EXPECT_GT((alpha2 + 2.0 * k) / (alpha2 + 2.0 * k + radius * radius), 5.0 * filtered_ggx_mass_beyond(radius, alpha2, k));
}

// Unfiltered input (A = diag(alpha2)): the lobe is GGX(alpha2) itself.
TEST(FilteredGgx, NoKernelIsGgx) {
  for (double alpha2 : {1e-4, 0.1})
    for (double t : {0.0, 0.5, 2.0}) {
      const Vec3 h = normalize(Vec3{t * std::sqrt(alpha2), 0.3 * t * std::sqrt(alpha2), 1.0});
      EXPECT_NEAR(ggx_ndf_filtered_axis(h, {alpha2, alpha2}, {alpha2, alpha2}), ggx_ndf_axis(h, {alpha2, alpha2}),
                  1e-12 * ggx_ndf_axis(h, {alpha2, alpha2}));
    }
}

// The per-pixel / per-light split of the isotropic form is the axis form of (filtered, filtered):
// the same lobe with its light-independent terms computed once (rounding only: 1e-12 relative).
TEST(FilteredGgx, SplitIsotropicLobeIsTheAxisForm) {
  for (double alpha2 : {1e-6, 2.5e-3, 0.1, 0.6})
    for (double kernel : {0.0, 1e-4, 0.02, 0.36})
      for (double tilt : {0.0, 0.05, 0.3, 1.2}) {
        const double filtered = alpha2 + kernel;
        const IsotropicLobe lobe = ggx_filtered_lobe_isotropic(filtered, alpha2);
        const Vec3 i = normalize(Vec3{0.4 + tilt, -0.2, 1.0}), o = normalize(Vec3{-0.3, 0.1 - tilt, 1.0});
        const double axis = ggx_brdf_filtered_axis(i, o, {filtered, filtered}, {alpha2, alpha2});
        EXPECT_NEAR(ggx_brdf_filtered_lobe(i, o, filtered, alpha2, lobe), axis, 1e-12 * axis + 1e-300)
            << "alpha2 " << alpha2 << " kernel " << kernel << " tilt " << tilt;
      }
  // A filtered alpha^2 below the material's (rounding in a G-buffer) is no kernel, as in the axis form.
  const IsotropicLobe none = ggx_filtered_lobe_isotropic(0.009, 0.01);
  EXPECT_DOUBLE_EQ(none[0], 0.01);
  EXPECT_DOUBLE_EQ(none[1], 1.0);
}

// deferred-aniso's lobe split per pixel and per light is its one-pass BRDF: for kernels thin and
// round, turned, and with the frame built from tilted normals.
TEST(FilteredGgx, SplitMatrixLobeIsDeferredAnisosBrdf) {
  const Params p{};
  for (double alpha2 : {1e-6, 2.5e-3, 0.1, 0.6})
    for (const Sym2 tensor : {Sym2{0.0, 0.0, 0.0}, Sym2{1e-4, 0.0, 1e-4}, Sym2{0.18, 0.02, 0.001}, Sym2{0.02, -0.09, 0.18}})
      for (double tilt : {0.0, 0.05, 0.3, 1.2}) {
        const Vec3 n = normalize(Vec3{0.2 * tilt, -0.1, 1.0});
        const Vec3 light = normalize(Vec3{0.4 + tilt, -0.2, 1.0}), view = normalize(Vec3{-0.3, 0.1 - tilt, 1.0});
        const double one_pass = deferred_aniso_brdf(p, light, view, n, tensor, alpha2);
        const double split = deferred_aniso_brdf_lobe(p, light, view, n, tensor, alpha2, deferred_aniso_lobe(p, tensor, alpha2));
        EXPECT_NEAR(split, one_pass, 1e-12 * one_pass + 1e-300) << "alpha2 " << alpha2 << " tilt " << tilt;
      }
}

namespace {

// 2D L1 distance of the matrix lobe to the exact anisotropic convolution
// integral e^-w N(0, A0 / (2w) + Sigma) dw (A0 = diag(alpha2), Sigma = K / 2), on a polar grid.
double anisotropic_l1(const SlopeDensity& model, Vec2 alpha2, Sym2 sigma) {
  const double large = std::sqrt(std::max(alpha2.x + 2.0 * sigma.xx, alpha2.y + 2.0 * sigma.yy));
  const double small = std::sqrt(std::min(alpha2.x, alpha2.y));
  const int radii = 160, angles = 48;
  const double low = std::log(1e-3 * small), high = std::log(1e4 * large);
  const double dr = (high - low) / radii, dt = kPi / angles;
  double l1 = 0.0;
  for (int i = 0; i < radii; ++i) {
    const double rho = std::exp(low + (i + 0.5) * dr);
    for (int j = 0; j < angles; ++j) {
      const double t = (j + 0.5) * dt, x = rho * std::cos(t), y = rho * std::sin(t);
      l1 += 2.0 * rho * rho * dr * dt * std::fabs(model(x, y) - saagen::test::anisotropic_slope_density(alpha2, sigma, x, y));
    }
  }
  return l1;
}

}  // namespace

// The matrix form on the kernels the forward variants produce: anisotropic and correlated, and
// alpha anisotropic across the kernel (outside the fit's grid, whose A0 is isotropic once
// whitened): the lobe must beat the papers' GGX(A0 + K) on every one. Printed for the documentation.
TEST(FilteredGgx, MatrixFormBeatsThePapersLobe) {
  struct Case {
    Vec2 alpha2;
    Sym2 sigma;
  };
  const Case cases[] = {
      {{1e-4, 1e-4}, {1e-3, 0.0, 1e-3}}, {{1e-4, 1e-4}, {1e-3, 0.0, 1e-4}},     {{1e-4, 1e-4}, {1e-3, 8e-4, 1e-3}},
      {{1e-2, 1e-4}, {1e-3, 0.0, 1e-3}}, {{0.01, 0.01}, {0.003, 0.002, 0.006}}, {{0.1, 0.1}, {0.02, -0.01, 0.01}},
  };
  for (const Case& c : cases) {
    const Sym2 a{c.alpha2.x + 2.0 * c.sigma.xx, 2.0 * c.sigma.xy, c.alpha2.y + 2.0 * c.sigma.yy};
    const double saagen = anisotropic_l1(from_ndf([&](Vec3 h) { return ggx_ndf_filtered_matrix(h, a, c.alpha2); }), c.alpha2, c.sigma);
    const double paper = anisotropic_l1(from_ndf([&](Vec3 h) { return ggx_ndf_matrix(h, a, ndf_clamp_tau(c.alpha2)); }), c.alpha2, c.sigma);
    std::printf("alpha2 (%g, %g) Sigma (%g, %g, %g): L1 saagen %.4f, paper %.4f\n", c.alpha2.x, c.alpha2.y, c.sigma.xx, c.sigma.xy,
                c.sigma.yy, saagen, paper);
    EXPECT_LT(saagen, paper);
  }
}

// The anisotropic grid (scripts/fit_filtered_ggx.py --check): kernels of slope variances r1,
// r2 = r1 (r2 / r1) in units of alpha^2 (mean r = (r1 + r2) / 2), here turned 30 degrees from the
// material's axes (the lobe and the exact density depend on the kernel only through its
// eigenvalues in A0's frame). The lobe is fitted to isotropic kernels and one r; where an
// anisotropic kernel dominates alpha^2 (the torus's highlight: r 9.2, r2 / r1 0.01) its core
// M = A0 + c K keeps A0's width along the axis the kernel leaves alone, and misses GGX's wings
// there (docs/FILTERED_GGX.md). `script`: the script's L1 on its coarser grid (60 x 12 cells against
// 160 x 48 here); the two agree within 5e-3, so the documented table is the committed lobe's.
TEST(FilteredGgx, AnisotropicKernelsMatchTheFitScriptsTable) {
  struct Cell {
    double r, anisotropy, script;
  };
  const Cell cells[] = {{1.0, 0.1, 0.0593},   {1.0, 0.01, 0.0880},  {1.0, 0.0, 0.0937},    {5.623, 0.1, 0.0796}, {5.623, 0.01, 0.1602},
                        {5.623, 0.0, 0.1841}, {31.62, 0.1, 0.0584}, {31.62, 0.01, 0.1774}, {31.62, 0.0, 0.2603}};
  const double alpha2 = 1e-4, angle = kPi / 6.0, c = std::cos(angle), s = std::sin(angle);
  for (const Cell& cell : cells) {
    const double r1 = 2.0 * cell.r / (1.0 + cell.anisotropy), r2 = cell.anisotropy * r1;
    const Sym2 sigma{alpha2 * (r1 * c * c + r2 * s * s), alpha2 * (r1 - r2) * c * s, alpha2 * (r1 * s * s + r2 * c * c)};
    const Sym2 a{alpha2 + 2.0 * sigma.xx, 2.0 * sigma.xy, alpha2 + 2.0 * sigma.yy};
    const double l1 = anisotropic_l1(from_ndf([&](Vec3 h) {
                                       return ggx_ndf_filtered_matrix(h, a, {alpha2, alpha2});
                                     }),
                                     {alpha2, alpha2}, sigma);
    std::printf("r %6.3g r2/r1 %4.2f: L1 %.4f (script %.4f)\n", cell.r, cell.anisotropy, l1, cell.script);
    EXPECT_NEAR(l1, cell.script, 5e-3) << "r " << cell.r << " r2/r1 " << cell.anisotropy;
  }
}

// The single-roughness mapping meets its criterion: the GGX lobe of alpha'^2 holds the exact
// filtered lobe's mass within 2 sqrt(k), to the fit's 3.2 % in alpha'^2 - alpha^2 terms
// (tolerance 4 %: the fit's worst case plus quadrature).
TEST(FilteredGgx, SingleRoughnessMatchesCoreMass) {
  for (double alpha2 : kAlpha2s)
    for (double k : kKernels) {
      if (k == 0.0) {
        EXPECT_EQ(ggx_filtered_alpha2(alpha2, 0.0), alpha2);
        continue;
      }
      const double radius2 = 4.0 * k;
      const double core = 1.0 - filtered_ggx_mass_beyond(std::sqrt(radius2), alpha2, k);
      const double criterion = radius2 * (1.0 - core) / core;  // GGX: mass within R = R^2 / (a^2 + R^2)
      EXPECT_NEAR(ggx_filtered_alpha2(alpha2, 2.0 * k) / criterion, 1.0, 0.04) << "alpha^2 " << alpha2 << " k " << k;
    }
  // Limits: the papers add 2k; the mapping adds 2.687 k for a small kernel, 0.646 k for a large one.
  EXPECT_NEAR(ggx_kernel_scale(1.0, 1e-9), 2.687 / 2.0, 1e-6);
  EXPECT_NEAR(ggx_kernel_scale(1e-9, 1.0), 0.391 / 1.210, 1e-6);
}

// Tests of the ground-truth renderer (measure/src): analytic scenes against
// hand-derived hits and normals, the pixel filter's moments, convergence of the ground truth,
// agreement of the 1-spp image with the ground truth where nothing aliases, the renderer's use
// of the reference quad functions, the flicker metric, thread-count independence and the cache.
//
// Runtime: the images are small (16 x 16 to 64 x 64) and sample counts are reduced where a
// test allows (each says why), so the whole binary runs in a few seconds on 2 cores; the
// renderer's throughput is in bench/bench_reference.cpp.
#include "saagen/measure/render.hpp"
#include "saagen/reference/brdf.hpp"
#include "saagen/reference/saa.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace saagen::measure;
namespace ref = saagen::ref;
using ref::Vec2;
using ref::Vec3;

namespace {

void expect_vec_near(Vec3 a, Vec3 b, double tol, const char* what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

// The frame of a hit must be orthonormal and right-handed with b = n x t.
void expect_orthonormal_frame(const SurfaceHit& h, double tol = 1e-12) {
  EXPECT_NEAR(ref::length(h.normal), 1.0, tol);
  EXPECT_NEAR(ref::length(h.tangent), 1.0, tol);
  EXPECT_NEAR(ref::dot(h.normal, h.tangent), 0.0, tol);
  expect_vec_near(h.bitangent, ref::cross(h.normal, h.tangent), tol, "b = n x t");
}

// RMSE of a against b over the pixels where mask(i) holds.
template <class Mask>
double masked_rmse(const Image& a, const Image& b, Mask&& mask, std::size_t* count = nullptr) {
  double s = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!mask(i)) continue;
    const double d = static_cast<double>(a.pixels[i]) - b.pixels[i];
    s += d * d;
    ++n;
  }
  if (count) *count = n;
  return n ? std::sqrt(s / n) : 0.0;
}

template <class Mask>
double masked_rms(const Image& a, Mask&& mask) {
  double s = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!mask(i)) continue;
    s += static_cast<double>(a.pixels[i]) * a.pixels[i];
    ++n;
  }
  return n ? std::sqrt(s / n) : 0.0;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Scenes

// Unit sphere, ray (0.3, 0.4, 5) + t (0, 0, -1): z^2 = 1 - 0.09 - 0.16 = 0.75, so the hit is
// (0.3, 0.4, sqrt(0.75)) at t = 5 - sqrt(0.75), and the normal is the hit point itself.
TEST(Scene, SphereHitAndNormal) {
  const Sphere sphere(1.0);
  SurfaceHit hit;
  ASSERT_TRUE(sphere.intersect({{0.3, 0.4, 5.0}, {0.0, 0.0, -1.0}}, 0.0, hit));
  const double z = std::sqrt(0.75);
  EXPECT_NEAR(hit.t, 5.0 - z, 1e-14);
  expect_vec_near(hit.position, {0.3, 0.4, z}, 1e-14, "position");
  expect_vec_near(hit.normal, {0.3, 0.4, z}, 1e-14, "normal");
  expect_orthonormal_frame(hit);

  // Oblique ray from (3, 0, 0) aimed at (0, 0.6, 0.8) on the far side: d = (-3, 0.6, 0.8) /
  // sqrt(10), o.d = -9 / sqrt(10), |o|^2 - 1 = 8, so t^2 - 2 (9 / sqrt 10) t + 8 = 0 and
  // t = 9 / sqrt(10) -+ sqrt(8.1 - 8). The far root is sqrt(10), the aimed point; the ray
  // enters at the near root 9 / sqrt(10) - sqrt(0.1).
  const Vec3 d = ref::normalize(Vec3{-3.0, 0.6, 0.8});
  ASSERT_TRUE(sphere.intersect({{3.0, 0.0, 0.0}, d}, 0.0, hit));
  EXPECT_NEAR(hit.t, 9.0 / std::sqrt(10.0) - std::sqrt(0.1), 1e-13);
  expect_vec_near(hit.normal, hit.position, 1e-14, "normal = position on the unit sphere");
  EXPECT_NEAR(ref::length(hit.position), 1.0, 1e-14);

  // Tangent field: at the front pole (0, 0, 1) the stereographic field is +x; it is tangent
  // everywhere except the back pole.
  expect_vec_near(Sphere::stereographic_tangent({0.0, 0.0, 1.0}), {1.0, 0.0, 0.0}, 1e-15, "front-pole tangent");
  // On the equator point (1, 0, 0): t ~ (1 + 0 - 1, 0, -2) -> (0, 0, -1).
  expect_vec_near(Sphere::stereographic_tangent({1.0, 0.0, 0.0}), {0.0, 0.0, -1.0}, 1e-15, "equator tangent");

  // A miss: the ray passes at distance 1.1 from the centre.
  EXPECT_FALSE(sphere.intersect({{1.1, 0.0, 5.0}, {0.0, 0.0, -1.0}}, 0.0, hit));

  // The standard scene: the central ray from the camera at (0, 0, 4) hits (0, 0, 1), n = +z.
  const Scene scene = make_scene(SceneId::sphere);
  ASSERT_TRUE(scene.intersect(scene.camera().generate(32.0, 32.0, 64, 64), hit));
  expect_vec_near(hit.position, {0.0, 0.0, 1.0}, 1e-14, "scene centre hit");
  expect_vec_near(hit.normal, {0.0, 0.0, 1.0}, 1e-14, "scene centre normal");
}

// Torus R = 1, r = 0.25 around y.
TEST(Scene, TorusHitAndNormal) {
  const Torus torus(1.0, 0.25);
  SurfaceHit hit;
  // Straight down onto the top of the tube at (1, 0.25, 0): t = 5 - 0.25, n = +y, and the
  // tangent is the major-circle direction normalize(-pz, 0, px) = +z.
  ASSERT_TRUE(torus.intersect({{1.0, 5.0, 0.0}, {0.0, -1.0, 0.0}}, 0.0, hit));
  EXPECT_NEAR(hit.t, 4.75, 1e-12);
  expect_vec_near(hit.position, {1.0, 0.25, 0.0}, 1e-12, "top");
  expect_vec_near(hit.normal, {0.0, 1.0, 0.0}, 1e-12, "top normal");
  expect_vec_near(hit.tangent, {0.0, 0.0, 1.0}, 1e-12, "top tangent");
  expect_orthonormal_frame(hit);

  // Along -z through the axis plane x = 0: the outer equator of the tube at z = 1.25, n = +z.
  ASSERT_TRUE(torus.intersect({{0.0, 0.0, 5.0}, {0.0, 0.0, -1.0}}, 0.0, hit));
  EXPECT_NEAR(hit.t, 3.75, 1e-12);
  expect_vec_near(hit.normal, {0.0, 0.0, 1.0}, 1e-12, "equator normal");

  // The tube point at major angle 0 and tube angle 60 degrees:
  // p = (1 + 0.25 cos 60, 0.25 sin 60, 0) = (1.125, 0.2165, 0), n = (cos 60, sin 60, 0).
  // A ray arriving along -n from p + 3 n meets p first (x stays >= 1.125 on the way).
  const Vec3 n{0.5, std::sqrt(3.0) / 2.0, 0.0};
  const Vec3 p{1.125, 0.25 * std::sqrt(3.0) / 2.0, 0.0};
  ASSERT_TRUE(torus.intersect({p + 3.0 * n, -1.0 * n}, 0.0, hit));
  EXPECT_NEAR(hit.t, 3.0, 1e-12);
  expect_vec_near(hit.position, p, 1e-12, "60-degree point");
  expect_vec_near(hit.normal, n, 1e-12, "60-degree normal");

  // Down the axis through the hole: a miss.
  EXPECT_FALSE(torus.intersect({{0.0, 3.0, 0.0}, {0.0, -1.0, 0.0}}, 0.0, hit));
}

// The quartic solver against a brute-force march of the implicit function on random rays: the
// first root must agree, and every hit must lie on the surface.
TEST(Scene, TorusMatchesBruteForceMarch) {
  const double big_r = 1.0, small_r = 0.35;
  const Torus torus(big_r, small_r);
  auto f = [&](Vec3 p) {
    const double g = ref::dot(p, p) + big_r * big_r - small_r * small_r;
    return g * g - 4.0 * big_r * big_r * (p.x * p.x + p.z * p.z);
  };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 origin = 4.0 * ref::normalize(Vec3{u(rng), u(rng), u(rng)});
    const Vec3 target{1.4 * u(rng), 0.5 * u(rng), 1.4 * u(rng)};
    const Ray ray{origin, ref::normalize(target - origin)};
    // March in steps of 1e-3 (thinner than any chord this test counts), then bisect.
    double t_march = -1.0;
    double previous = f(ray.origin);
    for (double t = 1e-3; t < 9.0; t += 1e-3) {
      const double value = f(ray.origin + t * ray.direction);
      if ((previous > 0.0) != (value > 0.0)) {
        double lo = t - 1e-3, hi = t;
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (lo + hi);
          if ((f(ray.origin + mid * ray.direction) > 0.0) == (previous > 0.0))
            lo = mid;
          else
            hi = mid;
        }
        t_march = 0.5 * (lo + hi);
        break;
      }
      previous = value;
    }
    SurfaceHit hit;
    const bool found = torus.intersect(ray, 0.0, hit);
    if (t_march < 0.0) {
      // The march can only miss chords shorter than its step (grazing rays); the solver
      // may find those. Nothing to compare.
      continue;
    }
    ASSERT_TRUE(found) << "trial " << trial << " march t " << t_march;
    EXPECT_NEAR(hit.t, t_march, 1e-9) << "trial " << trial;
    // |grad f| ~ 8 R^2 r at the surface, so |f| <= 1e-9 means a distance below ~1e-9.
    EXPECT_NEAR(f(hit.position), 0.0, 1e-9) << "trial " << trial;
    expect_orthonormal_frame(hit, 1e-12);
    ++hits;
  }
  EXPECT_GT(hits, 500);
}

// Three tubes of radius 0.1 at y = -0.5, 0, 0.5, axes along x, |x| <= 2.
TEST(Scene, TubeHitAndNormal) {
  const TubeRow tubes(3, 0.1, 0.5, 2.0);
  SurfaceHit hit;
  // Ray (0.3, 0.05, 5) + t (0, 0, -1) meets the middle tube where 0.05^2 + z^2 = 0.01:
  // z = sqrt(0.0075); normal (0, 0.05, z) / 0.1 = (0, 0.5, 0.866); tangent +x; object 1.
  ASSERT_TRUE(tubes.intersect({{0.3, 0.05, 5.0}, {0.0, 0.0, -1.0}}, 0.0, hit));
  const double z = std::sqrt(0.0075);
  EXPECT_NEAR(hit.t, 5.0 - z, 1e-13);
  EXPECT_EQ(hit.object, 1);
  expect_vec_near(hit.normal, {0.0, 0.5, z / 0.1}, 1e-12, "middle tube normal");
  expect_vec_near(hit.tangent, {1.0, 0.0, 0.0}, 0.0, "tube tangent");
  expect_orthonormal_frame(hit);
  // Straight at the top tube's axis: hit at z = 0.1, n = +z, object 2.
  ASSERT_TRUE(tubes.intersect({{-1.0, 0.5, 5.0}, {0.0, 0.0, -1.0}}, 0.0, hit));
  EXPECT_NEAR(hit.t, 4.9, 1e-13);
  EXPECT_EQ(hit.object, 2);
  expect_vec_near(hit.normal, {0.0, 0.0, 1.0}, 1e-13, "top tube normal");
  // Seen from above, the top tube hides the others: ray down x = 0, z = 0 hits y = 0.6.
  ASSERT_TRUE(tubes.intersect({{0.0, 3.0, 0.0}, {0.0, -1.0, 0.0}}, 0.0, hit));
  EXPECT_NEAR(hit.position.y, 0.6, 1e-13);
  EXPECT_EQ(hit.object, 2);
  // Beyond the end (x = 2.5) and between tubes (y = 0.25): misses.
  EXPECT_FALSE(tubes.intersect({{2.5, 0.0, 5.0}, {0.0, 0.0, -1.0}}, 0.0, hit));
  EXPECT_FALSE(tubes.intersect({{0.0, 0.25, 5.0}, {0.0, 0.0, -1.0}}, 0.0, hit));
}

// Bump plane: the shading normal is normalize(-dh/dx, -dh/dy, 1) of the height field.
TEST(Scene, BumpPlaneNormal) {
  // One wave h = a sin(kx x + ky y + phase): dh/dx = a kx cos(.), dh/dy = a ky cos(.).
  const double a = 0.01, kx = 30.0, ky = -12.0, phase = 0.4;
  const BumpPlane single(2.0, {SineWave{{kx, ky}, a, phase}});
  SurfaceHit hit;
  const Vec3 origin{0.37, -0.21, 3.0};
  ASSERT_TRUE(single.intersect({origin, {0.0, 0.0, -1.0}}, 0.0, hit));
  EXPECT_NEAR(hit.t, 3.0, 1e-15);  // the geometry is flat: only shading follows h
  const double c = std::cos(kx * 0.37 + ky * -0.21 + phase);
  const Vec3 expected = ref::normalize(Vec3{-a * kx * c, -a * ky * c, 1.0});
  expect_vec_near(hit.normal, expected, 1e-15, "single-wave normal");
  expect_orthonormal_frame(hit);
  // The tangent is the x axis made orthogonal to n: it lies in the plane of e_x and n.
  EXPECT_NEAR(ref::dot(hit.tangent, ref::cross(Vec3{1.0, 0.0, 0.0}, hit.normal)), 0.0, 1e-15);
  EXPECT_GT(hit.tangent.x, 0.0);

  // Several waves: the analytic gradient against central differences of h (step 1e-6:
  // truncation error ~ h''' step^2 / 6 <= a k^3 1e-12 ~ 1e-9, rounding ~ 1e-16 / 1e-6).
  const BumpPlane multi(2.0,
                        {SineWave{{40.0, 12.0}, 0.004, 0.3}, SineWave{{-20.0, 55.0}, 0.003, 1.7}, SineWave{{60.0, -52.0}, 0.0015, 4.1}});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.9, 1.9);
  for (int trial = 0; trial < 50; ++trial) {
    const double x = u(rng), y = u(rng);
    const double step = 1e-6;
    const double hx = (multi.height(x + step, y) - multi.height(x - step, y)) / (2 * step);
    const double hy = (multi.height(x, y + step) - multi.height(x, y - step)) / (2 * step);
    ASSERT_TRUE(multi.intersect({{x, y, 1.0}, {0.0, 0.0, -1.0}}, 0.0, hit));
    expect_vec_near(hit.normal, ref::normalize(Vec3{-hx, -hy, 1.0}), 1e-8, "multi-wave normal");
  }
  // Seen from below or outside the square: no hit.
  EXPECT_FALSE(multi.intersect({{0.0, 0.0, -1.0}, {0.0, 0.0, 1.0}}, 0.0, hit));
  EXPECT_FALSE(multi.intersect({{2.5, 0.0, 1.0}, {0.0, 0.0, -1.0}}, 0.0, hit));

  // The standard scene puts the plane's normal on world +y: every hit normal leans from +y
  // by at most the sum of the waves' slope amplitudes (0.65 -> 33 degrees).
  const Scene scene = make_scene(SceneId::bump_plane);
  int n_hits = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      if (!scene.intersect(scene.camera().generate(x + 0.5, y + 0.5, 32, 32), hit)) continue;
      ++n_hits;
      EXPECT_NEAR(hit.position.y, 0.0, 1e-12);
      EXPECT_GT(hit.normal.y, std::cos(std::atan(0.65)) - 1e-12);
      expect_orthonormal_frame(hit);
    }
  EXPECT_GT(n_hits, 32 * 32 / 2);
}

namespace {

// E[s] and E[s s^T] of the bump plane's slope s = grad h over x ~ N(centre, S) by the trapezoidal
// rule on z in [-10, 10]^2, x = centre + L z (L L^T = S, Cholesky). For an entire integrand times
// a Gaussian the rule converges geometrically: its aliasing error is of order exp(-(2 pi / step -
// w)^2 / 2) for an oscillation of frequency w = |L^T k| in z (below 30 here, against 2 pi / step =
// 126), and the cut at |z| = 10 drops exp(-50) of the weight; what remains is rounding, at most
// n eps max|s s^T| ~ 1.6e5 x 1.1e-16 x 0.1 ~ 2e-12 for the n weighted terms.
SlopeMoments quadrature_moments(const BumpPlane& plane, Vec2 centre, ref::Sym2 s) {
  const double l00 = std::sqrt(s.xx), l10 = l00 > 0.0 ? s.xy / l00 : 0.0, l11 = std::sqrt(std::max(s.yy - l10 * l10, 0.0));
  constexpr double kStep = 0.05, kCut = 10.0;
  SlopeMoments m;
  double total = 0.0;
  for (double z0 = -kCut; z0 <= kCut + 1e-9; z0 += kStep)
    for (double z1 = -kCut; z1 <= kCut + 1e-9; z1 += kStep) {
      const double w = std::exp(-0.5 * (z0 * z0 + z1 * z1));
      const Vec2 g = plane.gradient(centre.x + l00 * z0, centre.y + l10 * z0 + l11 * z1);
      m.mean = m.mean + w * g;
      m.second = m.second + w * ref::Sym2{g.x * g.x, g.x * g.y, g.y * g.y};
      total += w;
    }
  return {m.mean / total, (1.0 / total) * m.second};
}

void expect_moments_near(const SlopeMoments& a, const SlopeMoments& b, double tolerance, const std::string& what) {
  EXPECT_NEAR(a.mean.x, b.mean.x, tolerance) << what;
  EXPECT_NEAR(a.mean.y, b.mean.y, tolerance) << what;
  EXPECT_NEAR(a.second.xx, b.second.xx, tolerance) << what;
  EXPECT_NEAR(a.second.xy, b.second.xy, tolerance) << what;
  EXPECT_NEAR(a.second.yy, b.second.yy, tolerance) << what;
}

// The bump plane scene's waves' scale: 4 waves, wavelengths 0.083 - 0.23, slope amplitudes 0.12 - 0.2.
const BumpPlane& test_plane() {
  static const BumpPlane plane(2.5, {SineWave{{40.0, 12.0}, 0.2 / 41.8, 0.3}, SineWave{{-22.0, 55.0}, 0.15 / 59.2, 1.7},
                                     SineWave{{57.0, -50.0}, 0.12 / 75.8, 4.1}, SineWave{{5.5, 27.0}, 0.18 / 27.6, 2.6}});
  return plane;
}

}  // namespace

// The closed-form footprint moments of a sum of sines (scene.hpp, BumpPlane) against the
// quadrature of the same Gaussian expectation: an empty footprint gives the slope and its square,
// isotropic and sheared footprints (standard deviations about 1/25 to 1/2 of the shortest wavelength)
// the quadrature's values (tolerance: its rounding bound, quadrature_moments).
TEST(Scene, BumpPlaneFootprintMomentsMatchQuadrature) {
  const BumpPlane& plane = test_plane();
  for (const Vec2 centre : {Vec2{0.13, -0.41}, Vec2{-1.2, 0.77}}) {
    const Vec2 g = plane.gradient(centre.x, centre.y);
    expect_moments_near(plane.slope_moments(centre, {}), SlopeMoments{g, {g.x * g.x, g.x * g.y, g.y * g.y}}, 1e-15, "empty footprint");
    for (const ref::Sym2 s :
         {ref::Sym2{1e-5, 0.0, 1e-5}, ref::Sym2{4e-4, 0.0, 4e-4}, ref::Sym2{1e-3, 6e-4, 5e-4}, ref::Sym2{2e-4, -1e-4, 1e-3}})
      expect_moments_near(plane.slope_moments(centre, s), quadrature_moments(plane, centre, s), 2e-12,
                          "footprint " + std::to_string(s.xx) + " " + std::to_string(s.xy) + " " + std::to_string(s.yy));
  }
}

// A footprint much wider than every wave (and every difference of two waves' vectors): the mean
// slope vanishes and the second moment is each wave's own, sum a^2 k k^T / 2 (the mean of cos^2),
// exactly (exp underflows to 0). The scene's uv-footprint form is the plane's with x = size uv - half.
TEST(Scene, BumpPlaneWideFootprintKeepsEachWavesVariance) {
  const BumpPlane& plane = test_plane();
  const SlopeMoments m = plane.slope_moments({0.3, 0.2}, {100.0, 0.0, 100.0});
  ref::Sym2 expected{};
  for (const SineWave& w : plane.waves())
    expected =
        expected + (0.5 * w.amplitude * w.amplitude) *
                       ref::Sym2{w.wave_vector.x * w.wave_vector.x, w.wave_vector.x * w.wave_vector.y, w.wave_vector.y * w.wave_vector.y};
  expect_moments_near(m, SlopeMoments{{}, expected}, 1e-16, "wide footprint");
  // uv (0.56, 0.54) on the 5 x 5 plane is x = (0.3, 0.2); S_uv = S / 25.
  const auto via_uv = plane.footprint_slope_moments({0.56, 0.54}, {4e-5, 1e-5, 2e-5});
  ASSERT_TRUE(via_uv.has_value());
  expect_moments_near(*via_uv, plane.slope_moments({0.3, 0.2}, {1e-3, 2.5e-4, 5e-4}), 1e-14, "uv footprint");
  EXPECT_FALSE(Sphere(1.0).footprint_slope_moments({0.5, 0.5}, {1e-3, 0.0, 1e-3}).has_value());
}

// The rotation used for the flicker animation is rigid and about the vertical axis.
TEST(Scene, RotationAboutVerticalAxis) {
  for (SceneId id : all_scenes()) {
    const Scene a = make_scene(id, 0.0), b = make_scene(id, 0.3);
    const Rigid& ra = a.object_to_world();
    const Rigid& rb = b.object_to_world();
    // The vertical component of every object axis is unchanged by a rotation about y.
    EXPECT_NEAR(ra.col_x.y, rb.col_x.y, 1e-15) << scene_name(id);
    EXPECT_NEAR(ra.col_y.y, rb.col_y.y, 1e-15) << scene_name(id);
    EXPECT_NEAR(ra.col_z.y, rb.col_z.y, 1e-15) << scene_name(id);
    EXPECT_NE(a.describe(), b.describe());
  }
}

// ---------------------------------------------------------------------------------------------
// Pixel filter

// The truncated Gaussian has variance exactly sigma^2 = 0.25 (by construction of s0): check by
// Simpson integration of x^2 pdf over the support (10^4 panels: error ~ 1e-14).
TEST(Sampler, TruncatedFilterHasVarianceSigma2) {
  const GaussianPixelFilter& filter = default_pixel_filter();
  EXPECT_NEAR(filter.radius(), 3.0 * filter.underlying_sigma(), 1e-15);
  // s0 = 0.5 / sqrt(1 - 6 phi(3) / (2 Phi(3) - 1)) = 0.50680...
  EXPECT_NEAR(filter.underlying_sigma(), 0.5068, 5e-5);
  const int panels = 10000;
  const double a = -filter.radius(), b = filter.radius(), h = (b - a) / panels;
  double mass = 0.0, mean = 0.0, second = 0.0;
  for (int i = 0; i <= panels; ++i) {
    const double x = a + i * h;
    const double w = (i == 0 || i == panels) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    const double p = filter.pdf(x);
    mass += w * p;
    mean += w * x * p;
    second += w * x * x * p;
  }
  mass *= h / 3.0;
  mean *= h / 3.0;
  second *= h / 3.0;
  EXPECT_NEAR(mass, 1.0, 1e-12);
  EXPECT_NEAR(mean, 0.0, 1e-14);
  EXPECT_NEAR(second, 0.25, 1e-12);
  // The tabulated inverse CDF used for sampling against the exact one (bound: sampling.hpp).
  double worst = 0.0;
  for (int i = 0; i <= 100000; ++i) {
    const double u = i / 100000.0;
    worst = std::max(worst, std::fabs(filter.sample(u) - filter.inverse_cdf_exact(u)));
  }
  EXPECT_LT(worst, 3e-6);
}

// The stratified samples of the renderer (32 x 32 jittered points through the inverse CDF)
// have mean 0 and variance 0.25 on both axes.
//
// Tolerance, derived rather than tuned: in stratum column i the x coordinate of each of the 32
// samples lies in [g(i/32), g((i+1)/32)] (g the inverse CDF) independently of the others, so its
// variance is at most w_i^2 / 4 (w_i the interval's width; any distribution on an interval of
// width w has variance <= w^2 / 4). The sample mean of N = 1024 samples therefore has variance
// <= sum_i 32 w_i^2 / 4 / N^2, and over P independent pixels a P-th of that; the estimator is
// unbiased (the average of g over each stratum is its share of the mean). The same holds for
// x^2 with the widths of x^2 on the strata. Tolerance: 5 of these bounding standard deviations.
TEST(Sampler, StratifiedSamplesHaveMeanZeroAndVarianceSigma2) {
  const GaussianPixelFilter& filter = default_pixel_filter();
  const int strata = 32, pixels = 64;
  const double n = strata * strata;
  double var_mean_bound = 0.0, var_second_bound = 0.0;
  for (int i = 0; i < strata; ++i) {
    const double lo = filter.inverse_cdf_exact(static_cast<double>(i) / strata);
    const double hi = filter.inverse_cdf_exact(static_cast<double>(i + 1) / strata);
    const double w = hi - lo;
    const double sq_lo = (lo < 0.0 && hi > 0.0) ? 0.0 : std::min(lo * lo, hi * hi);
    const double w2 = std::max(lo * lo, hi * hi) - sq_lo;
    var_mean_bound += strata * w * w / 4.0 / (n * n);
    var_second_bound += strata * w2 * w2 / 4.0 / (n * n);
  }
  var_mean_bound /= pixels;
  var_second_bound /= pixels;
  const double tol_mean = 5.0 * std::sqrt(var_mean_bound);
  const double tol_second = 5.0 * std::sqrt(var_second_bound);

  double sx = 0, sy = 0, sxx = 0, syy = 0;
  std::vector<FilmOffset> offsets;
  for (int p = 0; p < pixels; ++p) {
    Rng rng(pixel_seed(12345, p, 0));
    stratified_filter_offsets(filter, strata, rng, offsets);
    ASSERT_EQ(offsets.size(), static_cast<std::size_t>(n));
    for (const FilmOffset& o : offsets) {
      sx += o.dx;
      sy += o.dy;
      sxx += o.dx * o.dx;
      syy += o.dy * o.dy;
      ASSERT_LE(std::fabs(o.dx), filter.radius());
      ASSERT_LE(std::fabs(o.dy), filter.radius());
    }
  }
  const double total = n * pixels;
  std::printf("stratified filter: mean (%.2e, %.2e) tol %.2e, E[x^2] (%.6f, %.6f) tol %.2e\n", sx / total, sy / total, tol_mean,
              sxx / total, syy / total, tol_second);
  EXPECT_NEAR(sx / total, 0.0, tol_mean);
  EXPECT_NEAR(sy / total, 0.0, tol_mean);
  // Variance = E[x^2] - mean^2; mean^2 <= tol_mean^2 ~ 1e-7 is far below tol_second.
  EXPECT_NEAR(sxx / total - (sx / total) * (sx / total), 0.25, tol_second + tol_mean * tol_mean);
  EXPECT_NEAR(syy / total - (sy / total) * (sy / total), 0.25, tol_second + tol_mean * tol_mean);
}

// ---------------------------------------------------------------------------------------------
// Ground truth

// Bit-identical images for 1, 2 and 3 threads (pixel seeds do not depend on the schedule).
// Torus, 40 x 40, 8 x 8 samples: the sample count does not matter for determinism.
TEST(GroundTruth, MultithreadedEqualsSingleThreaded) {
  const Scene scene = make_scene(SceneId::torus, 0.1);
  const std::vector<Material> materials{{0.01, false}, {0.1, true}};
  GroundTruthSettings settings;
  settings.width = 40;
  settings.height = 40;
  settings.strata = 8;
  settings.threads = 1;
  const GroundTruth one = render_ground_truth(scene, settings, materials);
  for (int threads : {2, 3}) {
    settings.threads = threads;
    const GroundTruth many = render_ground_truth(scene, settings, materials);
    for (std::size_t m = 0; m < materials.size(); ++m)
      EXPECT_EQ(0, std::memcmp(one.images[m].pixels.data(), many.images[m].pixels.data(), one.images[m].size() * sizeof(float)))
          << threads << " threads, material " << m;
    EXPECT_EQ(0, std::memcmp(one.coverage.pixels.data(), many.coverage.pixels.data(), one.coverage.size() * sizeof(float)));
  }
  // The 1-spp images as well.
  const GBuffer g1 = render_gbuffer(scene, 40, 40, 1), g2 = render_gbuffer(scene, 40, 40, 2);
  const Image v1 = render_variant(g1, Variant::deferred_previous, materials[0], {}, ref::Derivative::coarse, 1);
  const Image v2 = render_variant(g2, Variant::deferred_previous, materials[0], {}, ref::Derivative::coarse, 2);
  EXPECT_EQ(0, std::memcmp(v1.pixels.data(), v2.pixels.data(), v1.size() * sizeof(float)));
}

// 1024 spp against 4096 spp: the ground truth has converged. To keep the cost small but the
// pixel scale of the 256 x 256 table, the test renders the 48 x 48 centre crop of the 256 x 256
// view (Camera::cropped) of the sphere (one smooth highlight), the tubes and the bump plane
// (many sub-pixel glints per pixel at alpha = 0.01: the hard case). Measured when written,
// relative RMSE (RMSE / RMS of the 4096-spp image): alpha = 0.01: sphere 0.2 %, tubes 4.7 %,
// bump plane 4.7 %; alpha >= 0.05: <= 1 %. Bounds: 8 % at alpha = 0.01, 2 % above. The glints
// of alpha = 0.01 cover a small fraction of a pixel each and their edges make the integrand
// discontinuity-like (stratified error ~ N^-3/4 rather than N^-1 or better for smooth
// integrands); their RMSE is still an order of magnitude below the 1-spp variants' errors
// (trade table: relative errors of order 100 % for the same cases).
TEST(GroundTruth, ConvergesAt1024Samples) {
  const std::vector<Material> materials{{0.01, false}, {0.05, false}, {0.1, false}, {0.3, false}};
  for (SceneId id : {SceneId::sphere, SceneId::tubes, SceneId::bump_plane}) {
    const Scene full = make_scene(id);
    const Scene scene = full.with_camera(full.camera().cropped(48, 256));
    GroundTruthSettings settings;
    settings.width = 48;
    settings.height = 48;
    settings.strata = 32;
    const GroundTruth gt1024 = render_ground_truth(scene, settings, materials);
    settings.strata = 64;
    settings.seed += 1;  // an independent sample pattern
    const GroundTruth gt4096 = render_ground_truth(scene, settings, materials);
    for (std::size_t m = 0; m < materials.size(); ++m) {
      const ImageError e = compare_images(gt1024.images[m], gt4096.images[m]);
      const double scale = rms(gt4096.images[m]);
      ASSERT_GT(scale, 0.0) << scene_name(id) << ": the crop shows nothing";
      const double relative = e.rmse_linear / scale;
      std::printf("%-10s alpha %.2f: RMSE(1024 vs 4096) %.3e, RMS %.3e, relative %.4f\n", std::string(scene_name(id)).c_str(),
                  materials[m].alpha, e.rmse_linear, scale, relative);
      EXPECT_LT(relative, materials[m].alpha < 0.02 ? 0.08 : 0.02) << scene_name(id) << " alpha " << materials[m].alpha;
    }
  }
}

// Rough material on the smooth sphere: little aliasing, so the 1-spp image without SAA (shaded
// at the pixel centre) is close to the filtered ground truth. Compared where the pixel's whole
// filter footprint lies on the sphere (coverage 1): silhouette pixels are geometric aliasing,
// which SAA does not address. 64 x 64, 1024 spp. The remaining difference is the filter's
// smoothing of the radiance, sigma^2 / 2 * Laplacian(L): small for alpha = 0.3, whose lobe
// spans tens of pixels here. Bound: 2 % of the RMS radiance.
TEST(OneSpp, NoneMatchesGroundTruthOnRoughSphere) {
  const Scene scene = make_scene(SceneId::sphere);
  const Material material{0.3, false};
  GroundTruthSettings settings;
  settings.width = 64;
  settings.height = 64;
  const GroundTruth gt = render_ground_truth(scene, settings, std::span(&material, 1));
  const GBuffer gbuffer = render_gbuffer(scene, 64, 64);
  const Image none = render_variant(gbuffer, Variant::none, material);
  auto interior = [&](std::size_t i) { return gt.coverage.pixels[i] == 1.0f; };
  std::size_t count = 0;
  const double error = masked_rmse(none, gt.images[0], interior, &count);
  const double scale = masked_rms(gt.images[0], interior);
  std::printf("alpha 0.3 sphere, %zu interior pixels: RMSE %.3e, RMS %.3e, relative %.4f\n", count, error, scale, error / scale);
  EXPECT_GT(count, 1500u);
  EXPECT_LT(error / scale, 0.02);
}

// The renderer hands the quad functions the right inputs: its 1-spp image equals, pixel for
// pixel, the reference *_fragment_quad function fed the renderer's own per-pixel fields,
// with the quad assembled here independently (partners off the surface -> the pixel's own
// fields, gl_FragCoord always the partner's own). Torus and tubes at 32 x 32: quads straddle
// silhouettes and, for the tubes, two different tubes, so the substitution is exercised.
TEST(OneSpp, RendererUsesReferenceQuadFunctions) {
  const ref::Params params{};
  for (SceneId id : {SceneId::torus, SceneId::tubes}) {
    const Scene scene = make_scene(id);
    const int w = 32, h = 32;
    const GBuffer g = render_gbuffer(scene, w, h);
    for (ref::Derivative mode : {ref::Derivative::coarse, ref::Derivative::fine}) {
      for (const Material material : {Material{0.01, false}, Material{0.1, true}}) {
        const double a2 = material.alpha * material.alpha;
        const Vec2 alpha2{a2, a2};
        const std::vector<Variant> variants{Variant::forward_aniso_slope, Variant::forward_axis_projected, Variant::deferred_previous,
                                            Variant::deferred_avg};
        std::vector<Image> images;
        for (Variant v : variants) images.push_back(render_variant(g, v, material, params, mode));
        int substituted = 0, checked = 0;
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const PixelFields& self = g.at(x, y);
            if (!self.hit) {
              for (const Image& image : images) EXPECT_EQ(image.at(x, y), 0.0f);
              continue;
            }
            // Assemble the quad.
            std::array<PixelFields, 4> f;
            std::array<Vec2, 4> frag;
            for (int q = 0; q < 4; ++q) {
              const int qx = (x / 2) * 2 + q % 2, qy = (y / 2) * 2 + q / 2;
              frag[q] = {qx + 0.5, qy + 0.5};
              const PixelFields& partner = g.at(qx, qy);
              const bool same = partner.hit && partner.object == self.object;
              f[q] = same ? partner : self;
              substituted += same ? 0 : 1;
            }
            auto quad3 = [&](Vec3 PixelFields::*m) { return ref::Quad<Vec3>{f[0].*m, f[1].*m, f[2].*m, f[3].*m}; };
            const ref::Quad<Vec2> fc{frag[0], frag[1], frag[2], frag[3]};
            const int pixel = x % 2 + 2 * (y % 2);
            const Vec3 i = self.light_ts, o = self.view_ts;
            auto radiance = [&](double brdf) {
              double value = brdf * i.z * self.irradiance;
              if (material.fresnel) value *= 0.04 + 0.96 * std::pow(1.0 - ref::dot(i, ref::normalize(i + o)), 5.0);
              return static_cast<float>(value);
            };
            const ref::Sym2 aniso = ref::forward_aniso_slope_fragment_quad(params, alpha2, quad3(&PixelFields::half_ts), pixel, mode);
            const Vec2 axis = ref::forward_axis_projected_fragment_quad(params, alpha2, quad3(&PixelFields::half_ts), pixel, mode);
            const double previous = ref::deferred_previous_fragment_quad(
                params, a2, quad3(&PixelFields::normal), quad3(&PixelFields::tangent), quad3(&PixelFields::bitangent), fc, pixel, mode);
            const double avg = ref::deferred_avg_fragment_quad(params, a2, quad3(&PixelFields::normal), pixel, mode);
            const float expected[4] = {radiance(ref::ggx_brdf_matrix(i, o, aniso, ref::ndf_clamp_tau(alpha2))),
                                       radiance(ref::ggx_brdf_axis(i, o, axis)), radiance(ref::ggx_brdf_axis(i, o, {previous, previous})),
                                       radiance(ref::ggx_brdf_axis(i, o, {avg, avg}))};
            for (std::size_t v = 0; v < variants.size(); ++v) {
              // Fresnel: the renderer multiplies by Schlick with (1-c)^5 as
              // products, here std::pow: allow a few ulps in that case only.
              const float got = images[v].at(x, y);
              if (material.fresnel)
                EXPECT_NEAR(got, expected[v], 4e-7f * std::fabs(expected[v]) + 1e-30f)
                    << scene_name(id) << " " << variant_id(variants[v]) << " pixel " << x << "," << y;
              else
                EXPECT_EQ(got, expected[v]) << scene_name(id) << " " << variant_id(variants[v]) << " pixel " << x << "," << y;
            }
            ++checked;
          }
        EXPECT_GT(checked, 100) << scene_name(id);
        EXPECT_GT(substituted, 10) << scene_name(id) << ": no quad straddles an edge";
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Metrics

// A static animation (no rotation, no pan) has zero flicker and zero temporal difference error
// for every variant: identical frames have a temporal variance of exactly 0 (Welford's update)
// and frame differences of exactly 0, for the ground truth too. Tiny sizes: only the identity of
// the frames matters.
TEST(Metrics, StaticSceneHasZeroFlicker) {
  TradeConfig config;
  config.width = config.height = 16;
  config.strata = 4;
  config.flicker_width = config.flicker_height = 16;
  config.flicker_strata = 4;
  config.frames = 4;
  config.rotation_degrees_per_frame = 0.0;
  config.pan_pixels_per_frame = {0.0, 0.0};
  config.scenes = {SceneId::sphere, SceneId::bump_plane};
  config.alphas = {0.01};
  config.fresnel_modes = {false};
  const TradeTable table = compute_trade_table(config);
  // Per scene: every variant and engine, and each further lobe of the lobe variants; the bump
  // plane's normal detail adds the geometric feed of every variant but the baseline (lobes too),
  // and its procedural detail the LEAN row of every prefiltered variant (lobes too; no other
  // prefilter: scene_has_procedural_normals).
  const std::size_t lobe_rows = config.lobe_variants.size() * config.lobes.size();
  const std::size_t per_scene = all_variants().size() + all_engines().size() + lobe_rows;
  std::size_t lean_rows = 0;
  for (Variant v : config.prefiltered_variants) {
    const bool has_lobes = std::find(config.lobe_variants.begin(), config.lobe_variants.end(), v) != config.lobe_variants.end();
    lean_rows += 1 + (has_lobes ? config.lobes.size() : 0);
  }
  ASSERT_EQ(table.rows.size(), 2 * per_scene + (all_variants().size() - 1) + lobe_rows + lean_rows);
  std::size_t bump_lean = 0;
  for (const TradeRow& row : table.rows) {
    EXPECT_TRUE(row.prefilter == Prefilter::none || (row.prefilter == Prefilter::lean && row.scene == SceneId::bump_plane))
        << configuration_id(row) << " " << scene_name(row.scene);
    bump_lean += row.prefilter == Prefilter::lean;
  }
  EXPECT_EQ(bump_lean, lean_rows);
  for (const TradeRow& row : table.rows) {
    EXPECT_EQ(row.flicker, 0.0) << configuration_id(row) << " " << scene_name(row.scene);
    EXPECT_EQ(row.temporal_stddev, 0.0);
    EXPECT_EQ(row.reference_temporal_stddev, 0.0);
    EXPECT_EQ(row.temporal_stddev_display, 0.0);
    EXPECT_EQ(row.reference_temporal_stddev_display, 0.0);
    EXPECT_EQ(row.tde, 0.0);
    EXPECT_EQ(row.tde_excess_flicker, 0.0);
    EXPECT_EQ(row.tde_lost_motion, 0.0);
  }
  // And a moving one does change from frame to frame, for the variant and the ground truth.
  config.rotation_degrees_per_frame = 0.25;
  config.scenes = {SceneId::torus};
  config.variants = {Variant::none};
  const TradeTable moving = compute_trade_table(config);
  ASSERT_EQ(moving.rows.size(), 1u);
  EXPECT_GT(moving.rows[0].temporal_stddev, 0.0);
  EXPECT_GT(moving.rows[0].reference_temporal_stddev, 0.0);
  EXPECT_NE(moving.rows[0].flicker, 0.0);
  EXPECT_GT(moving.rows[0].temporal_stddev_display, 0.0);
  EXPECT_GT(moving.rows[0].flicker_display, 0.0);
  EXPECT_GT(moving.rows[0].tde, 0.0);
  // The pan alone moves the image too.
  config.rotation_degrees_per_frame = 0.0;
  config.pan_pixels_per_frame = {0.11, 0.37};
  const TradeTable panned = compute_trade_table(config);
  EXPECT_GT(panned.rows[0].tde, 0.0);
  EXPECT_GT(panned.rows[0].reference_temporal_stddev, 0.0);
}

// The metrics on hand-made images.
TEST(Metrics, RmseTonemapMaxError) {
  Image a(2, 1), b(2, 1);
  a.pixels = {1.0f, 3.0f};
  b.pixels = {1.0f, 1.0f};
  const ImageError e = compare_images(a, b);
  EXPECT_DOUBLE_EQ(e.rmse_linear, std::sqrt(4.0 / 2.0));
  // tonemap(3) - tonemap(1) = 0.75 - 0.5.
  EXPECT_DOUBLE_EQ(e.rmse_tonemapped, std::sqrt(0.25 * 0.25 / 2.0));
  EXPECT_DOUBLE_EQ(e.max_error, 2.0);
  EXPECT_DOUBLE_EQ(tonemap(1.0), 0.5);
  // Temporal statistics: frames 0 and 2 at one pixel -> population std 1.
  TemporalStats s(1, 1), r(1, 1);
  Image f0(1, 1, 0.0f), f2(1, 1, 2.0f), f1(1, 1, 1.0f);
  s.add(f0);
  s.add(f2);
  r.add(f1);
  r.add(f1);
  EXPECT_DOUBLE_EQ(s.stddev(0), 1.0);
  EXPECT_DOUBLE_EQ(flicker(s, r), 1.0);
}

// ---------------------------------------------------------------------------------------------
// Cache

TEST(Cache, RoundTripAndKey) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("saagen_gt_cache_test_" + std::to_string(std::random_device{}()));
  std::filesystem::remove_all(dir);
  const Scene scene = make_scene(SceneId::sphere);
  const std::vector<Material> materials{{0.05, false}, {0.05, true}};
  GroundTruthSettings settings;
  settings.width = settings.height = 16;
  settings.strata = 4;
  bool hit = true;
  const GroundTruth first = cached_ground_truth(scene, settings, materials, dir.string(), {}, &hit);
  EXPECT_FALSE(hit);
  const GroundTruth second = cached_ground_truth(scene, settings, materials, dir.string(), {}, &hit);
  EXPECT_TRUE(hit);
  for (std::size_t m = 0; m < materials.size(); ++m) EXPECT_EQ(first.images[m].pixels, second.images[m].pixels);
  EXPECT_EQ(first.coverage.pixels, second.coverage.pixels);
  // Every parameter is in the key: seed, samples, rotation, materials.
  const std::string key = ground_truth_cache_key(scene, settings, materials);
  GroundTruthSettings other = settings;
  other.seed += 1;
  EXPECT_NE(key, ground_truth_cache_key(scene, other, materials));
  other = settings;
  other.strata = 5;
  EXPECT_NE(key, ground_truth_cache_key(scene, other, materials));
  EXPECT_NE(key, ground_truth_cache_key(make_scene(SceneId::sphere, 0.01), settings, materials));
  const std::vector<Material> rougher{{0.06, false}, {0.05, true}};
  EXPECT_NE(key, ground_truth_cache_key(scene, settings, rougher));
  EXPECT_NE(ground_truth_cache_file(key), ground_truth_cache_file(ground_truth_cache_key(scene, settings, rougher)));
  std::filesystem::remove_all(dir);
}

// Pixels overwritten under an intact header (NaN, 1e30) are a miss that renders again, and the
// file is rewritten: the checksum over the payload no longer matches.
TEST(Cache, ACorruptedPayloadIsAMissThatRecomputes) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("saagen_gt_cache_corrupt_" + std::to_string(std::random_device{}()));
  std::filesystem::remove_all(dir);
  const Scene scene = make_scene(SceneId::sphere);
  const std::vector<Material> materials{{0.05, false}};
  GroundTruthSettings settings;
  settings.width = settings.height = 8;
  settings.strata = 2;
  const GroundTruth first = cached_ground_truth(scene, settings, materials, dir.string());
  const std::filesystem::path file = dir / ground_truth_cache_file(ground_truth_cache_key(scene, settings, materials));
  const auto size = std::filesystem::file_size(file);
  for (const float bad : {std::nanf(""), 1e30f}) {
    {
      std::fstream stream(file, std::ios::in | std::ios::out | std::ios::binary);
      stream.seekp(static_cast<std::streamoff>(size - 4 * 8 * 8 - 4 * 10));  // a pixel of the material's image
      stream.write(reinterpret_cast<const char*>(&bad), sizeof bad);
    }
    bool hit = true;
    const GroundTruth again = cached_ground_truth(scene, settings, materials, dir.string(), {}, &hit);
    EXPECT_FALSE(hit);
    EXPECT_EQ(again.images[0].pixels, first.images[0].pixels);
    cached_ground_truth(scene, settings, materials, dir.string(), {}, &hit);
    EXPECT_TRUE(hit);  // rewritten whole
  }
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// Throughput

// Throughput: bench/bench_reference.cpp (BM_GroundTruthSphere64).

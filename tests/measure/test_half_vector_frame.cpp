// The frame the forward filters difference their half vectors in (renderer.hpp, HalfVectorFrame).
// In each quad pixel's own tangent frame (the papers' listing), a frame that turns about the normal
// from pixel to pixel turns h.xy with it, and the difference reads that turn as curvature. Carried
// from the pixel's frame without the turn (transported), the quad's half vectors differ only as the
// surface and the directions do: a pure turn adds nothing, and a frame field that does not turn is
// left as it was.
#include "saagen/measure/renderer.hpp"
#include "saagen/reference/reference.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace {

namespace ref = saagen::ref;
namespace measure = saagen::measure;
using measure::HalfVectorFrame;
using ref::Sym2;
using ref::Vec2;
using ref::Vec3;

struct QuadSurface {
  std::array<Vec3, 4> normal;
  std::array<Vec3, 4> tangent;
};

// A 2x2 G-buffer of one object: each pixel's frame (t, n x t, n) and the one world-space half vector
// h expressed in it.
measure::GBuffer quad_gbuffer(const QuadSurface& surface, Vec3 half_ws) {
  measure::GBuffer g;
  g.width = 2;
  g.height = 2;
  g.pixels.resize(4);
  for (std::size_t q = 0; q < 4; ++q) {
    measure::PixelFields& f = g.pixels[q];
    const Vec3 n = surface.normal[q], t = surface.tangent[q], b = ref::cross(n, t);
    f.hit = true;
    f.normal = f.geometric_normal = n;
    f.tangent = f.geometric_tangent = t;
    f.bitangent = f.geometric_bitangent = b;
    f.half_ts = f.geometric_half_ts = {ref::dot(half_ws, t), ref::dot(half_ws, b), ref::dot(half_ws, n)};
  }
  return g;
}

// The kernel forward-aniso-projected adds at pixel (0, 0): A - diag(alpha^2).
Sym2 kernel_at_top_left(const measure::GBuffer& g, HalfVectorFrame frame) {
  const Vec2 alpha2{0.01, 0.01};
  const measure::QuadFields q = measure::gather_quad(g, 0, 0, frame);
  const Sym2 a = ref::forward_aniso_projected_fragment_quad(ref::Params{}, alpha2, q.half_ts, q.pixel);
  return {a.xx - alpha2.x, a.xy, a.yy - alpha2.y};
}

Vec3 turned_about_z(double angle) { return {std::cos(angle), std::sin(angle), 0.0}; }

// The tangent t0 carried onto normal n: its component along n removed.
Vec3 carried(Vec3 t0, Vec3 n) { return ref::normalize(t0 - n * ref::dot(n, t0)); }

const Vec3 kHalf = ref::normalize(Vec3{0.3, 0.2, 1.0});

TEST(HalfVectorFrame, AFrameTurningAboutAFlatNormalAddsAKernelOnlyInTheTangentFrames) {
  QuadSurface flat;
  for (std::size_t q = 0; q < 4; ++q) {
    flat.normal[q] = {0.0, 0.0, 1.0};
    flat.tangent[q] = turned_about_z(0.3 * static_cast<double>(q));
  }
  const measure::GBuffer g = quad_gbuffer(flat, kHalf);
  // h.xy turns by 0.3 rad from pixel 0 to pixel 1 (and 0.6 to pixel 2): |dh| = 2 |h.xy| sin(0.15),
  // and the kernel's trace is 2 sigma^2 (|dh_x|^2 + |dh_y|^2), sigma^2 = 0.25.
  const double h_xy = std::hypot(kHalf.x, kHalf.y);
  const double dx = 2.0 * h_xy * std::sin(0.15), dy = 2.0 * h_xy * std::sin(0.3);
  const Sym2 tangent = kernel_at_top_left(g, HalfVectorFrame::tangent);
  EXPECT_NEAR(tangent.xx + tangent.yy, 2.0 * 0.25 * (dx * dx + dy * dy), 1e-12);
  const Sym2 transported = kernel_at_top_left(g, HalfVectorFrame::transported);
  EXPECT_NEAR(transported.xx, 0.0, 1e-15);
  EXPECT_NEAR(transported.xy, 0.0, 1e-15);
  EXPECT_NEAR(transported.yy, 0.0, 1e-15);
}

TEST(HalfVectorFrame, TransportedFramesKeepTheTiltAndDropOnlyTheTurn) {
  // A curved patch: the normals tilt across the quad. Its tangents once carried from pixel 0's
  // without turning, once turned about each normal besides.
  const std::array<Vec3, 4> normals{ref::normalize(Vec3{0.0, 0.0, 1.0}), ref::normalize(Vec3{0.08, 0.01, 1.0}),
                                    ref::normalize(Vec3{-0.02, 0.07, 1.0}), ref::normalize(Vec3{0.06, 0.08, 1.0})};
  QuadSurface untwisted, twisted;
  for (std::size_t q = 0; q < 4; ++q) {
    untwisted.normal[q] = twisted.normal[q] = normals[q];
    untwisted.tangent[q] = carried({1.0, 0.0, 0.0}, normals[q]);
    const Vec3 t = untwisted.tangent[q], b = ref::cross(normals[q], t);
    const double turn = 0.25 * static_cast<double>(q);
    twisted.tangent[q] = t * std::cos(turn) + b * std::sin(turn);
  }
  const Sym2 reference = kernel_at_top_left(quad_gbuffer(untwisted, kHalf), HalfVectorFrame::tangent);
  EXPECT_GT(reference.xx + reference.yy, 1e-4);  // the tilt is measured
  for (const QuadSurface* surface : {&untwisted, &twisted}) {
    const Sym2 transported = kernel_at_top_left(quad_gbuffer(*surface, kHalf), HalfVectorFrame::transported);
    EXPECT_NEAR(transported.xx, reference.xx, 1e-15);
    EXPECT_NEAR(transported.xy, reference.xy, 1e-15);
    EXPECT_NEAR(transported.yy, reference.yy, 1e-15);
  }
  // The turn widens the kernel in the tangent frames: here by more than the tilt itself.
  const Sym2 turned = kernel_at_top_left(quad_gbuffer(twisted, kHalf), HalfVectorFrame::tangent);
  EXPECT_GT(turned.xx + turned.yy, 2.0 * (reference.xx + reference.yy));
}

}  // namespace

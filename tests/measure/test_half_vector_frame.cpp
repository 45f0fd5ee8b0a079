// The frame the projected forward filters difference their half vectors in (renderer.hpp,
// HalfVectorFrame), as the renderer shades a quad gathered for it. In each quad pixel's own tangent
// frame (the papers' listing), a frame that turns about the normal from pixel to pixel turns h.xy
// with it, and the difference reads that turn as curvature. The transported wrappers
// (*_transported_fragment) read the world-space derivatives in the pixel's frame with its change
// along the normal removed: a pure turn adds nothing, the partners' frames do not enter at all,
// and where the frames do not turn they give the tangent frames' kernel to first order.
#include "saagen/measure/renderer.hpp"
#include "saagen/reference/reference.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>

namespace {

namespace ref = saagen::ref;
namespace measure = saagen::measure;
using measure::HalfVectorFrame;
using ref::Sym2;
using ref::Vec2;
using ref::Vec3;

const Vec3 kHalf = ref::normalize(Vec3{0.3, 0.2, 1.0});

struct QuadSurface {
  std::array<Vec3, 4> normal;
  std::array<Vec3, 4> tangent;
};

// A 2x2 G-buffer of one object: each pixel's frame (t, n x t, n) and the one world-space half vector
// h expressed in it, its quads gathered for `frame`.
measure::GBuffer quad_gbuffer(const QuadSurface& surface, Vec3 half_ws, HalfVectorFrame frame) {
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
  measure::gather_quads(g, 1, frame);
  return g;
}

// The kernel forward-aniso-projected adds at pixel (0, 0), as the renderer shades it: A - diag(alpha^2).
Sym2 kernel_at_top_left(const QuadSurface& surface, HalfVectorFrame frame) {
  const measure::Material material{0.1, false};
  const double alpha2 = material.alpha * material.alpha;
  const measure::GBuffer g = quad_gbuffer(surface, kHalf, frame);
  const Sym2 a = measure::shade_pixel(g, 0, 0, measure::Variant::forward_aniso_projected, material).roughness;
  return {a.xx - alpha2, a.xy, a.yy - alpha2};
}

double largest_difference(const Sym2& a, const Sym2& b) {
  return std::max({std::fabs(a.xx - b.xx), std::fabs(a.xy - b.xy), std::fabs(a.yy - b.yy)});
}

Vec3 turned_about_z(double angle) { return {std::cos(angle), std::sin(angle), 0.0}; }

// The tangent t0 carried onto normal n: its component along n removed.
Vec3 carried(Vec3 t0, Vec3 n) { return ref::normalize(t0 - n * ref::dot(n, t0)); }

TEST(HalfVectorFrame, AFrameTurningAboutAFlatNormalAddsAKernelOnlyInTheTangentFrames) {
  QuadSurface flat;
  for (std::size_t q = 0; q < 4; ++q) {
    flat.normal[q] = {0.0, 0.0, 1.0};
    flat.tangent[q] = turned_about_z(0.3 * static_cast<double>(q));
  }
  // h.xy turns by 0.3 rad from pixel 0 to pixel 1 (and 0.6 to pixel 2): |dh| = 2 |h.xy| sin(0.15),
  // and the kernel's trace is 2 sigma^2 (|dh_x|^2 + |dh_y|^2), sigma^2 = 0.25.
  const double h_xy = std::hypot(kHalf.x, kHalf.y);
  const double dx = 2.0 * h_xy * std::sin(0.15), dy = 2.0 * h_xy * std::sin(0.3);
  const Sym2 tangent = kernel_at_top_left(flat, HalfVectorFrame::tangent);
  EXPECT_NEAR(tangent.xx + tangent.yy, 2.0 * 0.25 * (dx * dx + dy * dy), 1e-12);
  // Transported: the world half vector and the normal do not change across the quad.
  EXPECT_LT(largest_difference(kernel_at_top_left(flat, HalfVectorFrame::transported), Sym2{}), 1e-15);
}

// A curved patch whose normals tilt across the quad by `tilt` times a fixed pattern, its tangents
// carried from pixel 0's without turning, and turned about each normal by `turn` per pixel besides.
QuadSurface curved_patch(double tilt, double turn) {
  const std::array<Vec3, 4> pattern{Vec3{0.0, 0.0, 0.0}, Vec3{0.08, 0.01, 0.0}, Vec3{-0.02, 0.07, 0.0}, Vec3{0.06, 0.08, 0.0}};
  QuadSurface surface;
  for (std::size_t q = 0; q < 4; ++q) {
    const Vec3 n = ref::normalize(Vec3{0.0, 0.0, 1.0} + tilt * pattern[q]);
    const Vec3 t = carried({1.0, 0.0, 0.0}, n), b = ref::cross(n, t);
    const double angle = turn * static_cast<double>(q);
    surface.normal[q] = n;
    surface.tangent[q] = t * std::cos(angle) + b * std::sin(angle);
  }
  return surface;
}

TEST(HalfVectorFrame, TransportedFramesKeepTheTiltAndDropOnlyTheTurn) {
  // The turn does not enter the transported kernel: only the pixel's own frame is read, and
  // pixel 0 is not turned.
  const Sym2 untwisted = kernel_at_top_left(curved_patch(1.0, 0.0), HalfVectorFrame::transported);
  EXPECT_LT(largest_difference(kernel_at_top_left(curved_patch(1.0, 0.25), HalfVectorFrame::transported), untwisted), 1e-15);
  // The turn widens the kernel in the tangent frames: here by more than the tilt itself.
  const Sym2 reference = kernel_at_top_left(curved_patch(1.0, 0.0), HalfVectorFrame::tangent);
  EXPECT_GT(reference.xx + reference.yy, 1e-4);  // the tilt is measured
  const Sym2 turned = kernel_at_top_left(curved_patch(1.0, 0.25), HalfVectorFrame::tangent);
  EXPECT_GT(turned.xx + turned.yy, 2.0 * (reference.xx + reference.yy));
  // Where the frames do not turn, the transported derivative is the tangent frames' to first order
  // in the tilt (docs/FORWARD_DERIVATIVES.md): the kernel's relative difference is O(tilt), halving
  // with it.
  const auto relative_difference = [](double tilt) {
    const Sym2 transported = kernel_at_top_left(curved_patch(tilt, 0.0), HalfVectorFrame::transported);
    const Sym2 tangent = kernel_at_top_left(curved_patch(tilt, 0.0), HalfVectorFrame::tangent);
    return largest_difference(transported, tangent) / (tangent.xx + tangent.yy);
  };
  const double coarse = relative_difference(1.0), fine = relative_difference(0.5), finer = relative_difference(0.25);
  EXPECT_GT(coarse, 0.0);
  EXPECT_NEAR(coarse / fine, 2.0, 0.2);
  EXPECT_NEAR(fine / finer, 2.0, 0.1);
}

}  // namespace

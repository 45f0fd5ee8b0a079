// The frame the projected forward filters difference their half vectors in (renderer.hpp,
// HalfVectorFrame), as the renderer shades a quad gathered for it. In each quad pixel's own tangent
// frame (the papers' listing), a frame that turns about the normal from pixel to pixel turns h.xy
// with it, and the difference reads that turn as curvature. The transported wrappers
// (*_transported_fragment) take the frame's turn, ddx(t).b, out of those derivatives: what is left
// of a pure turn is of second order, and turning frames give the kernel of frames carried without
// turning, to first order.
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

// A flat quad whose frames turn about the normal by `turn` radians per pixel along x, twice that along y.
QuadSurface turning_flat_quad(double turn) {
  QuadSurface flat;
  for (std::size_t q = 0; q < 4; ++q) {
    flat.normal[q] = {0.0, 0.0, 1.0};
    flat.tangent[q] = turned_about_z(turn * static_cast<double>(q));
  }
  return flat;
}

TEST(HalfVectorFrame, AFrameTurningAboutAFlatNormalAddsAKernelOnlyInTheTangentFrames) {
  // h.xy turns by 0.3 rad from pixel 0 to pixel 1 (and 0.6 to pixel 2): |dh| = 2 |h.xy| sin(0.15),
  // and the kernel's trace is 2 sigma^2 (|dh_x|^2 + |dh_y|^2), sigma^2 = 0.25.
  const double h_xy = std::hypot(kHalf.x, kHalf.y);
  const double dx = 2.0 * h_xy * std::sin(0.15), dy = 2.0 * h_xy * std::sin(0.3);
  EXPECT_NEAR(trace(kernel_at_top_left(turning_flat_quad(0.3), HalfVectorFrame::tangent)), 2.0 * 0.25 * (dx * dx + dy * dy), 1e-12);
  // Without the turn (to first order) nothing is left but the second-order remainder of the
  // chord, h.xy (cos w - 1): the kernel is a fraction of the tangent frames' that falls as w^2.
  const auto fraction_left = [](double turn) {
    return trace(kernel_at_top_left(turning_flat_quad(turn), HalfVectorFrame::transported)) /
           trace(kernel_at_top_left(turning_flat_quad(turn), HalfVectorFrame::tangent));
  };
  EXPECT_LT(fraction_left(0.1), 0.01);
  EXPECT_NEAR(fraction_left(0.05) / fraction_left(0.1), 0.25, 0.02);
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
  const Sym2 reference = kernel_at_top_left(curved_patch(1.0, 0.0), HalfVectorFrame::tangent);
  EXPECT_GT(trace(reference), 1e-4);  // the tilt is measured
  // The turn widens the kernel in the tangent frames: here by more than the tilt itself.
  EXPECT_GT(trace(kernel_at_top_left(curved_patch(1.0, 0.25), HalfVectorFrame::tangent)), 2.0 * trace(reference));
  // Without the turn, the turning frames give the kernel of frames carried without turning, up to
  // terms of second order in the tilt and the turn: the relative difference is of first order,
  // halving with both (here 0.44 at a turn of 0.25 rad per pixel, 0.10 at 0.0625).
  const auto relative_difference = [](double scale) {
    const Sym2 transported = kernel_at_top_left(curved_patch(scale, 0.25 * scale), HalfVectorFrame::transported);
    const Sym2 carried_frames = kernel_at_top_left(curved_patch(scale, 0.0), HalfVectorFrame::tangent);
    return largest_difference(transported, carried_frames) / trace(carried_frames);
  };
  const double whole = relative_difference(1.0), half = relative_difference(0.5), quarter = relative_difference(0.25);
  EXPECT_NEAR(half / whole, 0.5, 0.1);
  EXPECT_NEAR(quarter / half, 0.5, 0.05);
}

}  // namespace

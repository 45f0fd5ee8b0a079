// saagen reference: the 2x2 pixel quad in which a GPU evaluates ddx/ddy.
//
// Pixel layout (framebuffer coordinates as gl_FragCoord with Vulkan's upper-left origin, or
// SV_Position in Direct3D: x grows to the right, y grows downwards). Quads start at even pixel
// coordinates, so the top-left pixel of a quad has even floor(x) and even floor(y):
//
//        x ->
//   y   +------------+-------------+
//   |   | 0 top_left | 1 top_right |
//   v   +------------+-------------+
//       | 2 bot_left | 3 bot_right |
//       +------------+-------------+
//
// The pixel index within the quad is (x & 1) + 2 (y & 1).
//
// Derivatives (SPIR-V OpDPdx/OpDPdy, HLSL ddx/ddy, GLSL dFdx/dFdy):
//   fine:   the difference inside the row (x) or column (y) that contains the pixel;
//   coarse: one difference for the whole quad. Vulkan allows any row/column; this reference
//           (like the common hardware) takes the top-left pixel's row and column:
//           ddx = top_right - top_left, ddy = bottom_left - top_left.
// Plain ddx/ddy may be either (implementation-defined), hence the Derivative argument of the
// fragment-wrapper references.
#pragma once

#include <stdexcept>

namespace saagen::ref {

// Index of a pixel in the quad.
enum QuadPixel : int { kTopLeft = 0, kTopRight = 1, kBottomLeft = 2, kBottomRight = 3 };

// How plain ddx/ddy (not the _fine/_coarse intrinsics) are evaluated.
enum class Derivative { coarse, fine };

// The values of one per-pixel quantity at the four pixels of a quad.
template <class T>
struct Quad {
  T top_left{};
  T top_right{};
  T bottom_left{};
  T bottom_right{};

  // Value at a pixel index 0..3 (see the layout above).
  const T& operator[](int pixel) const {
    switch (pixel) {
      case kTopLeft:
        return top_left;
      case kTopRight:
        return top_right;
      case kBottomLeft:
        return bottom_left;
      case kBottomRight:
        return bottom_right;
      default:
        throw std::out_of_range("quad pixel index must be 0..3");
    }
  }
};

// Apply a per-pixel function to the four pixels: the quad of f(value).
template <class T, class F>
auto map(const Quad<T>& q, F&& f) -> Quad<decltype(f(q.top_left))> {
  return {f(q.top_left), f(q.top_right), f(q.bottom_left), f(q.bottom_right)};
}

// Apply a per-pixel function that also receives the pixel index.
template <class T, class F>
auto map_indexed(const Quad<T>& q, F&& f) -> Quad<decltype(f(q.top_left, 0))> {
  return {f(q.top_left, 0), f(q.top_right, 1), f(q.bottom_left, 2), f(q.bottom_right, 3)};
}

inline void check_quad_pixel(int pixel) {
  if (pixel < 0 || pixel > 3) throw std::out_of_range("quad pixel index must be 0..3");
}

// Coarse screen-x derivative: top_right - top_left, the same at every pixel of the quad.
template <class T>
T ddx_coarse(const Quad<T>& q) {
  return q.top_right - q.top_left;
}

// Coarse screen-y derivative: bottom_left - top_left, the same at every pixel of the quad.
template <class T>
T ddy_coarse(const Quad<T>& q) {
  return q.bottom_left - q.top_left;
}

// Fine screen-x derivative at a pixel: right minus left in the pixel's own row.
template <class T>
T ddx_fine(const Quad<T>& q, int pixel) {
  check_quad_pixel(pixel);
  return pixel < 2 ? q.top_right - q.top_left : q.bottom_right - q.bottom_left;
}

// Fine screen-y derivative at a pixel: bottom minus top in the pixel's own column.
template <class T>
T ddy_fine(const Quad<T>& q, int pixel) {
  check_quad_pixel(pixel);
  return (pixel & 1) == 0 ? q.bottom_left - q.top_left : q.bottom_right - q.top_right;
}

// Plain ddx / ddy as the GPU may implement them.
template <class T>
T ddx(const Quad<T>& q, int pixel, Derivative mode) {
  check_quad_pixel(pixel);
  return mode == Derivative::coarse ? ddx_coarse(q) : ddx_fine(q, pixel);
}

template <class T>
T ddy(const Quad<T>& q, int pixel, Derivative mode) {
  check_quad_pixel(pixel);
  return mode == Derivative::coarse ? ddy_coarse(q) : ddy_fine(q, pixel);
}

}  // namespace saagen::ref

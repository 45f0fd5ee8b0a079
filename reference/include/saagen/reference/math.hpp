// saagen reference: small double-precision vector and matrix types.
//
// These mirror the types of the template dialect (templates/README.md):
//   real  -> double
//   real2 -> Vec2
//   real3 -> Vec3, or Sym2 where the template stores a symmetric 2x2 matrix (m00, m01, m11)
// Mat2 is not a dialect type (the dialect has no matrices); the reference uses it only for the
// analytic Jacobians of jacobian.hpp.
//
// Component-wise helpers use the HLSL intrinsic names the templates use (saturate, abs, min,
// max, normalize, ...) so that a reference function reads like its template body.
#pragma once

#include <cmath>

namespace saagen::ref {

// ---------------------------------------------------------------------------------------------
// Scalars

// HLSL saturate: clamp to [0, 1]. NaN inputs are out of scope for the reference (HLSL maps
// NaN to 0; GLSL leaves clamp(NaN) undefined).
constexpr double saturate(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

// Scalar min/max with the dialect's names (no std::min to keep call sites template-like).
constexpr double min(double a, double b) { return b < a ? b : a; }
constexpr double max(double a, double b) { return a < b ? b : a; }

// HLSL frac: x - floor(x), in [0, 1).
inline double frac(double v) { return v - std::floor(v); }

inline constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Vec2

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
constexpr Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
constexpr Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
constexpr Vec2 operator*(Vec2 a, Vec2 b) { return {a.x * b.x, a.y * b.y}; }
constexpr Vec2 operator/(Vec2 a, double s) { return {a.x / s, a.y / s}; }
constexpr bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }

constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double length(Vec2 a) { return std::sqrt(dot(a, a)); }
inline Vec2 abs(Vec2 a) { return {std::fabs(a.x), std::fabs(a.y)}; }
constexpr Vec2 min(Vec2 a, Vec2 b) { return {min(a.x, b.x), min(a.y, b.y)}; }
constexpr Vec2 max(Vec2 a, Vec2 b) { return {max(a.x, b.x), max(a.y, b.y)}; }
constexpr Vec2 saturate(Vec2 a) { return {saturate(a.x), saturate(a.y)}; }
inline Vec2 floor(Vec2 a) { return {std::floor(a.x), std::floor(a.y)}; }
inline Vec2 frac(Vec2 a) { return {frac(a.x), frac(a.y)}; }

// ---------------------------------------------------------------------------------------------
// Vec3

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  // The dialect's swizzle .xy.
  constexpr Vec2 xy() const { return {x, y}; }
};

constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
constexpr Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator/(Vec3 a, double s) { return {a.x / s, a.y / s, a.z / s}; }
constexpr bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { return a / length(a); }

// ---------------------------------------------------------------------------------------------
// Sym2: symmetric 2x2 matrix, stored as the dialect's real3 (m00, m01, m11).

struct Sym2 {
  double xx = 0.0;  // m00
  double xy = 0.0;  // m01 = m10
  double yy = 0.0;  // m11
};

constexpr Sym2 operator+(Sym2 a, Sym2 b) { return {a.xx + b.xx, a.xy + b.xy, a.yy + b.yy}; }
constexpr Sym2 operator-(Sym2 a, Sym2 b) { return {a.xx - b.xx, a.xy - b.xy, a.yy - b.yy}; }
constexpr Sym2 operator*(double s, Sym2 a) { return {s * a.xx, s * a.xy, s * a.yy}; }
constexpr bool operator==(Sym2 a, Sym2 b) { return a.xx == b.xx && a.xy == b.xy && a.yy == b.yy; }

constexpr double trace(Sym2 m) { return m.xx + m.yy; }

// ---------------------------------------------------------------------------------------------
// Mat2: general 2x2 matrix, row-major m[row][col]. Only for the analytic Jacobians.

struct Mat2 {
  double m00 = 0.0, m01 = 0.0;
  double m10 = 0.0, m11 = 0.0;
};

constexpr Vec2 operator*(const Mat2& a, Vec2 v) { return {a.m00 * v.x + a.m01 * v.y, a.m10 * v.x + a.m11 * v.y}; }
constexpr Mat2 operator*(const Mat2& a, const Mat2& b) {
  return {a.m00 * b.m00 + a.m01 * b.m10, a.m00 * b.m01 + a.m01 * b.m11, a.m10 * b.m00 + a.m11 * b.m10, a.m10 * b.m01 + a.m11 * b.m11};
}
constexpr Mat2 operator*(double s, const Mat2& a) { return {s * a.m00, s * a.m01, s * a.m10, s * a.m11}; }
constexpr double determinant(const Mat2& a) { return a.m00 * a.m11 - a.m01 * a.m10; }
constexpr Mat2 transpose(const Mat2& a) { return {a.m00, a.m10, a.m01, a.m11}; }

// J S J^T for a symmetric S: how a covariance (or Delta^T Delta) transforms when every row
// vector of Delta is mapped by d -> J d.
constexpr Sym2 congruence(const Mat2& j, Sym2 s) {
  const Mat2 full{s.xx, s.xy, s.xy, s.yy};
  const Mat2 r = j * full * transpose(j);
  return {r.m00, 0.5 * (r.m01 + r.m10), r.m11};
}

}  // namespace saagen::ref

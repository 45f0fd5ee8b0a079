// FLIP and HDR-FLIP (see flip.hpp for the equations each step implements).
//
// Layout: the YCxCz channels of both images are planar double images. Every filter is
// separable: a horizontal pass per kernel into full intermediate planes (rows padded by edge
// replication, i.e. clamp-to-edge borders), then, row by row, the vertical passes, the colour
// difference and the feature difference of that row. Inner loops run over x with no reduction
// across iterations, so they vectorise without reassociation. HDR-FLIP reuses one workspace for
// all exposures; the kernels are built once per call.
#include "saagen/measure/flip.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace saagen::measure {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- Colour spaces -------------------------------------------------------------------------

// Linear sRGB -> CIE XYZ: the matrix of the sRGB primaries (0.64, 0.33), (0.30, 0.60),
// (0.15, 0.06) and the D65 white (0.3127, 0.3290), in exact rational form.
constexpr double kRgbToXyz[3][3] = {{10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
                                    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
                                    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};

struct Colour {
  double c[3];
};

struct ColourConstants {
  double xyz_to_rgb[3][3];
  double white[3];  // D65 (Xn, Yn, Zn) = the matrix applied to RGB (1, 1, 1)
  double inv_white[3];
  double cmax;     // (HyAB of Hunt-adjusted green and blue)^qc
  double pc_cmax;  // pc * cmax
};

Colour mul(const double m[3][3], const Colour& v) {
  Colour r;
  for (int i = 0; i < 3; ++i) r.c[i] = m[i][0] * v.c[0] + m[i][1] * v.c[1] + m[i][2] * v.c[2];
  return r;
}

constexpr double kQc = 0.7;   // colour-difference exponent
constexpr double kPc = 0.4;   // remapping breakpoint, as a fraction of cmax
constexpr double kPt = 0.95;  // remapped value at the breakpoint
constexpr double kW = 0.082;  // feature width in degrees
constexpr double kQf = 0.5;   // feature-difference exponent
constexpr double kT = 0.85;   // HDR-FLIP: tone-mapped value that defines x_max

// CIELAB's companding f(t) (CIE 15): t^(1/3) above (6/29)^3, linear below.
double lab_f(double t) {
  constexpr double d = 6.0 / 29.0;
  if (t > d * d * d) return std::cbrt(t);
  return t / (3.0 * d * d) + 4.0 / 29.0;
}

// XYZ -> L*a*b* (reference white `inv_white` = 1 / white), then the Hunt adjustment
// a' = 0.01 L a, b' = 0.01 L b.
Colour xyz_to_lab_hunt(const Colour& xyz, const double inv_white[3]) {
  const double fx = lab_f(xyz.c[0] * inv_white[0]);
  const double fy = lab_f(xyz.c[1] * inv_white[1]);
  const double fz = lab_f(xyz.c[2] * inv_white[2]);
  const double L = 116.0 * fy - 16.0;
  const double a = 500.0 * (fx - fy);
  const double b = 200.0 * (fy - fz);
  return {{L, 0.01 * L * a, 0.01 * L * b}};
}

// HyAB: city-block distance in L, Euclidean in (a, b).
double hyab(const Colour& p, const Colour& q) {
  const double da = p.c[1] - q.c[1], db = p.c[2] - q.c[2];
  return std::fabs(p.c[0] - q.c[0]) + std::sqrt(da * da + db * db);
}

ColourConstants make_colour_constants() {
  ColourConstants k{};
  // Inverse of kRgbToXyz (adjugate / determinant).
  const auto& m = kRgbToXyz;
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  k.xyz_to_rgb[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
  k.xyz_to_rgb[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  k.xyz_to_rgb[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  k.xyz_to_rgb[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
  k.xyz_to_rgb[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  k.xyz_to_rgb[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  k.xyz_to_rgb[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
  k.xyz_to_rgb[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  k.xyz_to_rgb[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  for (int i = 0; i < 3; ++i) {
    k.white[i] = m[i][0] + m[i][1] + m[i][2];
    k.inv_white[i] = 1.0 / k.white[i];
  }
  const Colour green = xyz_to_lab_hunt(mul(kRgbToXyz, {{0.0, 1.0, 0.0}}), k.inv_white);
  const Colour blue = xyz_to_lab_hunt(mul(kRgbToXyz, {{0.0, 0.0, 1.0}}), k.inv_white);
  k.cmax = std::pow(hyab(green, blue), kQc);
  k.pc_cmax = kPc * k.cmax;
  return k;
}

const ColourConstants& colour_constants() {
  static const ColourConstants k = make_colour_constants();
  return k;
}

double srgb_eotf(double v) {  // sRGB-encoded -> linear (IEC 61966-2-1)
  if (v <= 0.04045) return v / 12.92;
  return std::pow((v + 0.055) / 1.055, 2.4);
}

double clamp01(double v) {  // NaN -> 0
  if (!(v > 0.0)) return 0.0;
  return v < 1.0 ? v : 1.0;
}

// ---- HDR-FLIP tone mapper ------------------------------------------------------------------

// ACES fit (Narkowicz 2015) on 0.6 x: ((0.6x)(2.51 (0.6x) + 0.03)) / ((0.6x)(2.43 (0.6x) + 0.59)
// + 0.14), written as a ratio of quadratics in x.
constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};

double aces(double x) {
  if (std::isinf(x)) return kAces[0] / kAces[3];
  return (kAces[0] * x * x + kAces[1] * x + kAces[2]) / (kAces[3] * x * x + kAces[4] * x + kAces[5]);
}

double aces_x_max() {
  // t(x) = T  <=>  (k0 - T k3) x^2 + (k1 - T k4) x + (k2 - T k5) = 0; the larger root.
  const double a = kAces[0] - kT * kAces[3];
  const double b = kAces[1] - kT * kAces[4];
  const double c = kAces[2] - kT * kAces[5];
  const double mid = -0.5 * b / a;
  return mid + std::sqrt(mid * mid - c / a);
}

// ---- Kernels -------------------------------------------------------------------------------

struct Kernels {
  int csf_radius = 0;
  std::vector<double> y, cx, cz1, cz2;  // 1-D CSF factors (see flip.hpp, step 2)
  int feature_radius = 0;
  std::vector<double> g, dg, ddg;  // Gaussian and its 1st/2nd derivatives (step 7)
};

Kernels make_kernels(double ppd) {
  if (!(ppd > 0.0) || !std::isfinite(ppd)) throw std::invalid_argument("FLIP: pixels_per_degree must be positive and finite");
  Kernels k;
  // CSF parameters (a_k, b_k) of the achromatic, red-green and blue-yellow channels.
  constexpr double aY = 1.0, bY = 0.0047;
  constexpr double aCx = 1.0, bCx = 0.0053;
  constexpr double aCz1 = 34.1, bCz1 = 0.04, aCz2 = 13.5, bCz2 = 0.025;
  const double b_max = std::max({bY, bCx, bCz1, bCz2});
  // exp(-pi^2 x^2 / b) has standard deviation sqrt(b / (2 pi^2)) degrees; 3 of them.
  k.csf_radius = static_cast<int>(std::ceil(3.0 * std::sqrt(b_max / (2.0 * kPi * kPi)) * ppd));
  const int n = 2 * k.csf_radius + 1;
  k.y.resize(n);
  k.cx.resize(n);
  k.cz1.resize(n);
  k.cz2.resize(n);
  // One factor of a separable 2-D term a sqrt(pi/b) exp(-pi^2 (x^2 + y^2) / b).
  auto factor = [](double x2, double a, double b) { return std::sqrt(a * std::sqrt(kPi / b)) * std::exp(-kPi * kPi * x2 / b); };
  double sy = 0, scx = 0, scz1 = 0, scz2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = (i - k.csf_radius) / ppd;
    const double x2 = x * x;
    sy += k.y[i] = factor(x2, aY, bY);
    scx += k.cx[i] = factor(x2, aCx, bCx);
    scz1 += k.cz1[i] = factor(x2, aCz1, bCz1);
    scz2 += k.cz2[i] = factor(x2, aCz2, bCz2);
  }
  // Unit sum in 2-D: a single separable term is normalised per axis; the blue-yellow filter's
  // 2-D sum is scz1^2 + scz2^2, so each factor is divided by its square root.
  const double ncz = 1.0 / std::sqrt(scz1 * scz1 + scz2 * scz2);
  for (int i = 0; i < n; ++i) {
    k.y[i] /= sy;
    k.cx[i] /= scx;
    k.cz1[i] *= ncz;
    k.cz2[i] *= ncz;
  }

  const double sigma = 0.5 * kW * ppd;  // pixels
  k.feature_radius = static_cast<int>(std::ceil(3.0 * sigma));
  const int m = 2 * k.feature_radius + 1;
  k.g.resize(m);
  k.dg.resize(m);
  k.ddg.resize(m);
  double sg = 0, sdg = 0, sddg_pos = 0, sddg_neg = 0;
  for (int i = 0; i < m; ++i) {
    const double x = i - k.feature_radius;
    const double g = std::exp(-x * x / (2.0 * sigma * sigma));
    const double dg = -x * g;
    const double ddg = (x * x / (sigma * sigma) - 1.0) * g;
    k.g[i] = g;
    k.dg[i] = dg;
    k.ddg[i] = ddg;
    sg += g;
    if (dg > 0) sdg += dg;  // the negative weights mirror these: same sum
    (ddg > 0 ? sddg_pos : sddg_neg) += std::fabs(ddg);
  }
  for (int i = 0; i < m; ++i) {
    k.g[i] /= sg;
    k.dg[i] /= sdg;
    k.ddg[i] /= (k.ddg[i] > 0 ? sddg_pos : sddg_neg);
  }
  // conv_fused relies on exact (anti)symmetry.
  auto symmetric = [](const std::vector<double>& v, double sign) {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (v[i] != sign * v[v.size() - 1 - i]) return false;
    return true;
  };
  if (!symmetric(k.y, 1) || !symmetric(k.cx, 1) || !symmetric(k.cz1, 1) || !symmetric(k.cz2, 1) || !symmetric(k.g, 1) ||
      !symmetric(k.ddg, 1) || !symmetric(k.dg, -1) || k.dg[0] == 0.0)
    throw std::logic_error("FLIP: kernel symmetry violated");
  return k;
}

// ---- Workspace and the LDR-FLIP core ------------------------------------------------------

// Per-image planes: the YCxCz inputs, the feature input (Y + 16) / 116, and the horizontal-pass
// outputs.
enum Plane { kY, kCx, kCz, kYn, kHY, kHCx, kHCz1, kHCz2, kHDx, kHDdx, kHG, kPlanes };

struct Workspace {
  int w = 0, h = 0;
  std::size_t n = 0;
  bool achromatic = false;  // both images grey: Cx = Cz = 0, the chroma planes are not used
  std::vector<double> planes[2][kPlanes];
  std::vector<double> pad;   // one row padded by edge replication
  std::vector<double> rows;  // row buffers of the vertical passes (8 rows per image)
  std::vector<const double*> taps;
  std::vector<double> colour_row;

  Workspace(int width, int height, const Kernels& k, bool grey) : w(width), h(height), achromatic(grey) {
    n = static_cast<std::size_t>(w) * h;
    for (auto& image : planes)
      for (int p = 0; p < kPlanes; ++p)
        if (!grey || !(p == kCx || p == kCz || p == kHCx || p == kHCz1 || p == kHCz2)) image[p].resize(n);
    const int r = std::max(k.csf_radius, k.feature_radius);
    pad.resize(static_cast<std::size_t>(w) + 2 * r);
    rows.resize(static_cast<std::size_t>(w) * 16);
    taps.resize(2 * r + 1);
    colour_row.resize(w);
  }
  double* plane(int image, int p) { return planes[image][p].data(); }
};

// Convolution of one input with a set of kernels of radius r: out_j[x] = sum_t k_j[t] src[t][x],
// t in [0, 2r], where src[t] points at the input row of tap t (shifted rows of a padded row for
// the horizontal pass, clamped rows of a plane for the vertical one). Every FLIP kernel is exactly
// symmetric (k[2r - t] == k[t]: the Gaussians, the CSF factors, the 2nd derivative) or
// antisymmetric (k[2r - t] == -k[t]: the 1st derivative), being a function of x^2 (times x), so
// mirrored taps are added (subtracted) before the multiplication; the first NS kernels are
// symmetric, the next NA antisymmetric. Kernels sharing an input share its loads. Blocks of B
// outputs are accumulated in registers; the taps are summed centre first, then t = 0, 1, ...
template <int NS, int NA, int B>
inline void conv_block(const double* const* src, int r, const double* const* k, double* const* out, int x) {
  constexpr int N = NS + NA;
  double s[N][B];
  const double* c = src[r] + x;
  for (int j = 0; j < N; ++j)
    for (int b = 0; b < B; ++b) s[j][b] = j < NS ? k[j][r] * c[b] : 0.0;
  for (int t = 0; t < r; ++t) {
    const double* p = src[t] + x;
    const double* q = src[2 * r - t] + x;
    double sum[B], diff[B];
    for (int b = 0; b < B; ++b) {
      sum[b] = p[b] + q[b];
      diff[b] = p[b] - q[b];
    }
    for (int j = 0; j < N; ++j) {
      const double wt = k[j][t];
      for (int b = 0; b < B; ++b) s[j][b] += wt * (j < NS ? sum[b] : diff[b]);
    }
  }
  for (int j = 0; j < N; ++j)
    for (int b = 0; b < B; ++b) out[j][x + b] = s[j][b];
}

template <int NS, int NA>
void conv_fused(const double* const* src, int r, const double* const* k, double* const* out, int w) {
  int x = 0;
  for (; x + 8 <= w; x += 8) conv_block<NS, NA, 8>(src, r, k, out, x);
  for (; x < w; ++x) conv_block<NS, NA, 1>(src, r, k, out, x);
}

template <int NS, int NA>
using KernelRefs = std::array<const std::vector<double>*, NS + NA>;
template <int NS, int NA>
using PlaneRefs = std::array<double*, NS + NA>;

// Horizontal pass of plane `in` into the planes `outs`; borders clamp to the edge pixel (each row
// padded by replication).
template <int NS, int NA>
void horizontal(Workspace& ws, const double* in, const KernelRefs<NS, NA>& kernels, const PlaneRefs<NS, NA>& outs) {
  const int w = ws.w;
  const int r = static_cast<int>(kernels[0]->size()) / 2;
  double* pad = ws.pad.data();
  for (int t = 0; t <= 2 * r; ++t) ws.taps[t] = pad + t;
  const double* k[NS + NA];
  double* o[NS + NA];
  for (int j = 0; j < NS + NA; ++j) k[j] = kernels[j]->data();
  for (int y = 0; y < ws.h; ++y) {
    const double* row = in + static_cast<std::size_t>(y) * w;
    for (int i = 0; i < r; ++i) pad[i] = row[0];
    std::copy(row, row + w, pad + r);
    for (int i = 0; i < r; ++i) pad[r + w + i] = row[w - 1];
    for (int j = 0; j < NS + NA; ++j) o[j] = outs[j] + static_cast<std::size_t>(y) * w;
    conv_fused<NS, NA>(ws.taps.data(), r, k, o, w);
  }
}

// Vertical pass at row y: out_j[x] = sum_t k_j[t] plane[clamp(y + t - r)][x].
template <int NS, int NA>
void vertical(Workspace& ws, const double* plane, int y, const KernelRefs<NS, NA>& kernels, const std::array<double*, NS + NA>& outs) {
  const int r = static_cast<int>(kernels[0]->size()) / 2;
  for (int t = 0; t <= 2 * r; ++t) ws.taps[t] = plane + static_cast<std::size_t>(std::clamp(y + t - r, 0, ws.h - 1)) * ws.w;
  const double* k[NS + NA];
  for (int j = 0; j < NS + NA; ++j) k[j] = kernels[j]->data();
  conv_fused<NS, NA>(ws.taps.data(), r, k, outs.data(), ws.w);
}

double remap_colour(const ColourConstants& k, double hyab_distance) {
  const double d = std::pow(hyab_distance, kQc);
  if (d < k.pc_cmax) return d * (kPt / k.pc_cmax);
  return kPt + ((d - k.pc_cmax) / (k.cmax - k.pc_cmax)) * (1.0 - kPt);
}

// The remapped colour error of two filtered YCxCz colours (steps 3-6).
double colour_error(const ColourConstants& k, double y_r, double cx_r, double cz_r, double y_t, double cx_t, double cz_t) {
  auto to_lab = [&k](double Y, double Cx, double Cz) {
    const double yr = (Y + 16.0) / 116.0;  // Y / Yn
    const Colour xyz{{(yr + Cx / 500.0) * k.white[0], yr * k.white[1], (yr - Cz / 200.0) * k.white[2]}};
    Colour rgb = mul(k.xyz_to_rgb, xyz);
    for (double& v : rgb.c) v = clamp01(v);
    return xyz_to_lab_hunt(mul(kRgbToXyz, rgb), k.inv_white);
  };
  return remap_colour(k, hyab(to_lab(y_r, cx_r, cz_r), to_lab(y_t, cx_t, cz_t)));
}

// The same for grey colours (Cx = Cz = 0): linear RGB = (Y / Yn) (1, 1, 1), clamped; a = b = 0,
// so HyAB reduces to |L_r - L_t| (identical to colour_error in exact arithmetic).
double grey_colour_error(const ColourConstants& k, double y_r, double y_t) {
  if (y_r == y_t) return 0.0;
  auto lightness = [](double Y) { return 116.0 * lab_f(clamp01((Y + 16.0) / 116.0)) - 16.0; };
  return remap_colour(k, std::fabs(lightness(y_r) - lightness(y_t)));
}

// The filtered rows of one image at one row y: the CSF-filtered YCxCz (the two blue-yellow terms
// summed; steps 2-3) and the four feature responses edge x = dG(x) G(y), point x = ddG(x) G(y),
// edge y = G(x) dG(y), point y = G(x) ddG(y) (step 7).
struct FilteredRow {
  const double *y = nullptr, *cx = nullptr, *cz = nullptr;
  const double *dx = nullptr, *ddx = nullptr, *dy = nullptr, *ddy = nullptr;
};

// Writable row buffers of one image (FilteredRow's rows and a scratch row for the second
// blue-yellow term).
struct RowBuffers {
  double *y, *cx, *cz, *cz2, *dx, *ddx, *dy, *ddy;
  FilteredRow row() const { return {y, cx, cz, dx, ddx, dy, ddy}; }
};

RowBuffers row_buffers(double* base, int w) {
  double* r[8];
  for (int i = 0; i < 8; ++i) r[i] = base + static_cast<std::size_t>(i) * w;
  return {r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7]};
}

// Horizontal passes of image `img`'s planes kY (kCx, kCz) and the feature input (Y + 16) / 116.
void horizontal_passes(Workspace& ws, const Kernels& k, int img) {
  horizontal<1, 0>(ws, ws.plane(img, kY), {&k.y}, {ws.plane(img, kHY)});
  if (!ws.achromatic) {
    horizontal<1, 0>(ws, ws.plane(img, kCx), {&k.cx}, {ws.plane(img, kHCx)});
    horizontal<2, 0>(ws, ws.plane(img, kCz), {&k.cz1, &k.cz2}, {ws.plane(img, kHCz1), ws.plane(img, kHCz2)});
  }
  // Features on the achromatic channel normalised to [0,1].
  const double* Y = ws.plane(img, kY);
  double* yn = ws.plane(img, kYn);
  for (std::size_t i = 0; i < ws.n; ++i) yn[i] = (Y[i] + 16.0) / 116.0;
  horizontal<2, 1>(ws, yn, {&k.g, &k.ddg, &k.dg}, {ws.plane(img, kHG), ws.plane(img, kHDdx), ws.plane(img, kHDx)});
}

// Vertical passes of image `img` at row y into `out` (after horizontal_passes).
void vertical_passes(Workspace& ws, const Kernels& k, int img, int y, const RowBuffers& out) {
  vertical<1, 0>(ws, ws.plane(img, kHY), y, {&k.y}, {out.y});
  if (!ws.achromatic) {
    vertical<1, 0>(ws, ws.plane(img, kHCx), y, {&k.cx}, {out.cx});
    vertical<1, 0>(ws, ws.plane(img, kHCz1), y, {&k.cz1}, {out.cz});
    vertical<1, 0>(ws, ws.plane(img, kHCz2), y, {&k.cz2}, {out.cz2});
    for (int x = 0; x < ws.w; ++x) out.cz[x] += out.cz2[x];
  }
  vertical<1, 0>(ws, ws.plane(img, kHDx), y, {&k.g}, {out.dx});
  vertical<1, 0>(ws, ws.plane(img, kHDdx), y, {&k.g}, {out.ddx});
  vertical<1, 1>(ws, ws.plane(img, kHG), y, {&k.ddg, &k.dg}, {out.ddy, out.dy});
}

// Steps 3-8 of one row from both images' filtered rows; writes (or, with take_max, maxes) the
// error into orow.
void combine_row(Workspace& ws, const FilteredRow& r, const FilteredRow& t, float* orow, bool take_max) {
  const ColourConstants& cc = colour_constants();
  const int w = ws.w;
  if (ws.achromatic) {
    for (int x = 0; x < w; ++x) ws.colour_row[x] = grey_colour_error(cc, r.y[x], t.y[x]);
  } else {
    for (int x = 0; x < w; ++x) ws.colour_row[x] = colour_error(cc, r.y[x], r.cx[x], r.cz[x], t.y[x], t.cx[x], t.cz[x]);
  }
  const double inv_sqrt2 = 1.0 / std::sqrt(2.0);
  for (int x = 0; x < w; ++x) {
    if (ws.colour_row[x] == 0.0) {  // Ec = 0: e = 0 (see flip.hpp, step 8)
      if (!take_max) orow[x] = 0.0f;
      continue;
    }
    const double edge = std::fabs(std::sqrt(r.dx[x] * r.dx[x] + r.dy[x] * r.dy[x]) - std::sqrt(t.dx[x] * t.dx[x] + t.dy[x] * t.dy[x]));
    const double point =
        std::fabs(std::sqrt(r.ddx[x] * r.ddx[x] + r.ddy[x] * r.ddy[x]) - std::sqrt(t.ddx[x] * t.ddx[x] + t.ddy[x] * t.ddy[x]));
    static_assert(kQf == 0.5, "the feature exponent is applied as a square root");
    const double ef = std::sqrt(inv_sqrt2 * std::max(edge, point));
    const float e = static_cast<float>(std::pow(ws.colour_row[x], 1.0 - ef));
    if (!take_max || e > orow[x]) orow[x] = e;
  }
}

// One image's filtered rows for every row y, kept whole: the reference's side of flip_core,
// computed once for many test images (GreyFlipReference).
struct FilteredImage {
  int w = 0;
  std::vector<double> y, cx, cz, cz2, dx, ddx, dy, ddy;  // cz2: scratch of the blue-yellow sum
  RowBuffers rows(int row) {
    const std::size_t o = static_cast<std::size_t>(row) * w;
    auto at = [o](std::vector<double>& plane) { return plane.empty() ? nullptr : plane.data() + o; };
    return {at(y), at(cx), at(cz), at(cz2), at(dx), at(ddx), at(dy), at(ddy)};
  }
  FilteredRow row(int row) const {
    const std::size_t o = static_cast<std::size_t>(row) * w;
    auto at = [o](const std::vector<double>& plane) { return plane.empty() ? nullptr : plane.data() + o; };
    return {at(y), at(cx), at(cz), at(dx), at(ddx), at(dy), at(ddy)};
  }
};

// The filtered rows of image `img` of the workspace (its YCxCz planes loaded).
FilteredImage filter_image(Workspace& ws, const Kernels& k, int img) {
  horizontal_passes(ws, k, img);
  FilteredImage f;
  f.w = ws.w;
  for (std::vector<double>* plane : {&f.y, &f.dx, &f.ddx, &f.dy, &f.ddy}) plane->resize(ws.n);
  if (!ws.achromatic)
    for (std::vector<double>* plane : {&f.cx, &f.cz, &f.cz2}) plane->resize(ws.n);
  for (int y = 0; y < ws.h; ++y) vertical_passes(ws, k, img, y, f.rows(y));
  return f;
}

// LDR-FLIP of the YCxCz planes kY, kCx, kCz of both images; writes (or, with take_max, maxes)
// the error into out. With `reference`, image 0's filtered rows are read from it instead.
void flip_core(Workspace& ws, const Kernels& k, float* out, bool take_max, const FilteredImage* reference = nullptr) {
  const int w = ws.w;
  if (!reference) horizontal_passes(ws, k, 0);
  horizontal_passes(ws, k, 1);
  const RowBuffers reference_rows = row_buffers(ws.rows.data(), w);
  const RowBuffers test_rows = row_buffers(ws.rows.data() + static_cast<std::size_t>(8) * w, w);
  for (int y = 0; y < ws.h; ++y) {
    if (!reference) vertical_passes(ws, k, 0, y, reference_rows);
    vertical_passes(ws, k, 1, y, test_rows);
    combine_row(ws, reference ? reference->row(y) : reference_rows.row(), test_rows.row(), out + static_cast<std::size_t>(y) * w, take_max);
  }
}

// Linear RGB (3 values) -> YCxCz.
void linear_to_ycxcz(const ColourConstants& k, double r, double g, double b, double& Y, double& Cx, double& Cz) {
  const Colour xyz = mul(kRgbToXyz, {{r, g, b}});
  const double xr = xyz.c[0] * k.inv_white[0], yr = xyz.c[1] * k.inv_white[1], zr = xyz.c[2] * k.inv_white[2];
  Y = 116.0 * yr - 16.0;
  Cx = 500.0 * (xr - yr);
  Cz = 200.0 * (yr - zr);
}

void check_pair(const RgbImage& a, const RgbImage& b, const char* who) {
  auto ok = [](const RgbImage& i) {
    return i.width >= 0 && i.height >= 0 && i.rgb.size() == 3 * static_cast<std::size_t>(i.width) * static_cast<std::size_t>(i.height);
  };
  if (!ok(a) || !ok(b)) throw std::invalid_argument(std::string(who) + ": malformed image");
  if (a.width != b.width || a.height != b.height) throw std::invalid_argument(std::string(who) + ": size mismatch");
}

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// Element of rank floor(n/2) (the reference implementation's median).
double upper_median(std::vector<double>& v) {
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

RgbImage grey_to_rgb(const Image& img, bool encode) {
  if (img.width < 0 || img.height < 0 || img.pixels.size() != static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height))
    throw std::invalid_argument("FLIP: malformed grey image");
  RgbImage out;
  out.width = img.width;
  out.height = img.height;
  out.rgb.resize(3 * img.pixels.size());
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    float v = img.pixels[i];
    if (encode) v = static_cast<float>(srgb_encode(v));  // image.hpp
    out.rgb[3 * i] = out.rgb[3 * i + 1] = out.rgb[3 * i + 2] = v;
  }
  return out;
}

bool is_grey(const RgbImage& img) {
  for (std::size_t i = 0; i < img.rgb.size(); i += 3)
    if (!(img.rgb[i] == img.rgb[i + 1] && img.rgb[i] == img.rgb[i + 2])) return false;
  return true;
}

}  // namespace

double flip_aces_tonemap(double x) { return aces(x); }
double flip_aces_x_max() { return aces_x_max(); }

// An image into the workspace's YCxCz planes of image `img`, each channel value first mapped to
// linear display RGB in [0, 1] by `to_linear` (LDR: the sRGB EOTF; HDR: exposure and tone
// mapping). Grey images fill Y alone (L* = 116 Y - 16 with the white point's Y = 1).
template <class ToLinear>
void load_plane(Workspace& ws, int img, const RgbImage& image, bool grey, ToLinear to_linear) {
  const ColourConstants& cc = colour_constants();
  const float* p = image.rgb.data();
  double* Y = ws.plane(img, kY);
  if (grey) {
    for (std::size_t i = 0; i < ws.n; ++i) Y[i] = 116.0 * to_linear(p[3 * i]) - 16.0;
    return;
  }
  double* Cx = ws.plane(img, kCx);
  double* Cz = ws.plane(img, kCz);
  for (std::size_t i = 0; i < ws.n; ++i)
    linear_to_ycxcz(cc, to_linear(p[3 * i]), to_linear(p[3 * i + 1]), to_linear(p[3 * i + 2]), Y[i], Cx[i], Cz[i]);
}

template <class ToLinear>
void load_planes(Workspace& ws, const RgbImage& reference, const RgbImage& test, bool grey, ToLinear to_linear) {
  load_plane(ws, 0, reference, grey, to_linear);
  load_plane(ws, 1, test, grey, to_linear);
}

// LDR-FLIP's first step: the sRGB-encoded signal decoded to linear display values.
double decoded(float v) { return srgb_eotf(clamp01(v)); }

// HDR-FLIP's exposure i of e (its scale 2^c) and what it does to a value: expose, tone map,
// clamp (NaN -> 0).
double exposure_scale(const HdrExposures& e, int i) {
  const double c = e.count == 1 ? e.start : e.start + i * (e.stop - e.start) / (e.count - 1);
  return std::exp2(c);
}
auto exposed(double scale) {
  return [scale](float v) {
    if (std::isnan(v)) return 0.0;
    return clamp01(aces(scale * static_cast<double>(v)));
  };
}

std::vector<float> ldr_flip_map(const RgbImage& reference, const RgbImage& test, const FlipSettings& settings) {
  check_pair(reference, test, "ldr_flip_map");
  const Kernels k = make_kernels(settings.pixels_per_degree);
  std::vector<float> out(static_cast<std::size_t>(reference.width) * reference.height, 0.0f);
  if (out.empty()) return out;
  const bool grey = is_grey(reference) && is_grey(test);
  Workspace ws(reference.width, reference.height, k, grey);
  load_planes(ws, reference, test, grey, decoded);
  flip_core(ws, k, out.data(), false);
  return out;
}

HdrExposures hdr_flip_exposures(const RgbImage& reference, const HdrFlipSettings& settings) {
  check_pair(reference, reference, "hdr_flip_exposures");
  HdrExposures e;
  if (!settings.start_exposure || !settings.stop_exposure) {
    const std::size_t n = reference.rgb.size() / 3;
    std::vector<double> lum;
    lum.reserve(n);
    double y_max = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double y = luminance(&reference.rgb[3 * i]);
      if (!std::isfinite(y)) continue;  // NaN / inf radiance carries no exposure information
      lum.push_back(y);
      y_max = std::max(y_max, y);
    }
    double start = 0.0, stop = 0.0;
    if (y_max > 0.0) {
      const double x_max = aces_x_max();
      double y_median = lum.empty() ? 0.0 : upper_median(lum);
      if (!(y_median > 0.0)) {  // extension: median of the positive luminances
        std::vector<double> pos;
        for (double y : lum)
          if (y > 0.0) pos.push_back(y);
        y_median = upper_median(pos);
      }
      start = std::log2(x_max / y_max);
      stop = std::log2(x_max / y_median);
    }
    e.start = settings.start_exposure.value_or(start);
    e.stop = settings.stop_exposure.value_or(stop);
  } else {
    e.start = *settings.start_exposure;
    e.stop = *settings.stop_exposure;
  }
  if (!std::isfinite(e.start) || !std::isfinite(e.stop) || e.start > e.stop)
    throw std::invalid_argument("hdr_flip: need finite start_exposure <= stop_exposure");
  if (settings.num_exposures < 0) throw std::invalid_argument("hdr_flip: num_exposures < 0");
  e.count = settings.num_exposures > 0 ? settings.num_exposures : static_cast<int>(std::max(2.0, std::ceil(e.stop - e.start)));
  return e;
}

std::vector<float> hdr_flip_map(const RgbImage& reference, const RgbImage& test, const HdrFlipSettings& settings) {
  check_pair(reference, test, "hdr_flip_map");
  const HdrExposures ex = hdr_flip_exposures(reference, settings);
  const Kernels k = make_kernels(settings.base.pixels_per_degree);
  std::vector<float> out(static_cast<std::size_t>(reference.width) * reference.height, 0.0f);
  if (out.empty()) return out;
  const bool grey = is_grey(reference) && is_grey(test);
  Workspace ws(reference.width, reference.height, k, grey);
  for (int i = 0; i < ex.count; ++i) {
    load_planes(ws, reference, test, grey, exposed(exposure_scale(ex, i)));
    flip_core(ws, k, out.data(), i > 0);
  }
  return out;
}

double mean(const std::vector<float>& map) {
  if (map.empty()) return 0.0;
  double s = 0.0;
  for (float v : map) s += v;
  return s / static_cast<double>(map.size());
}

double ldr_flip_mean_grey(const Image& reference_display, const Image& test_display) {
  return mean(ldr_flip_map(grey_to_rgb(reference_display, true), grey_to_rgb(test_display, true)));
}

double hdr_flip_mean_grey(const Image& reference_linear, const Image& test_linear) {
  return mean(hdr_flip_map(grey_to_rgb(reference_linear, false), grey_to_rgb(test_linear, false)));
}

// ---- One reference, many tests ---------------------------------------------------------------

struct GreyFlipReference::State {
  Range range = Range::ldr;
  FlipSettings settings;
  Kernels kernels;
  RgbImage reference;
  HdrExposures exposures;               // HDR: from the reference; LDR: one pass
  bool grey = true;                     // false when the reference has NaN pixels: every comparison uncached
  std::vector<FilteredImage> filtered;  // the reference's filtered rows, one per exposure
};

GreyFlipReference::GreyFlipReference(const Image& reference, Range range, const FlipSettings& settings) {
  auto state = std::make_shared<State>();
  state->range = range;
  state->settings = settings;
  state->kernels = make_kernels(settings.pixels_per_degree);
  state->reference = grey_to_rgb(reference, range == Range::ldr);
  state->grey = is_grey(state->reference);
  HdrFlipSettings hdr;
  hdr.base = settings;
  state->exposures = range == Range::hdr ? hdr_flip_exposures(state->reference, hdr) : HdrExposures{0.0, 0.0, 1};
  if (state->grey && !state->reference.rgb.empty()) {
    Workspace ws(reference.width, reference.height, state->kernels, true);
    for (int i = 0; i < state->exposures.count; ++i) {
      if (range == Range::ldr)
        load_plane(ws, 0, state->reference, true, decoded);
      else
        load_plane(ws, 0, state->reference, true, exposed(exposure_scale(state->exposures, i)));
      state->filtered.push_back(filter_image(ws, state->kernels, 0));
    }
  }
  state_ = std::move(state);
}

double GreyFlipReference::mean_error(const Image& test) const {
  const State& s = *state_;
  const RgbImage rgb = grey_to_rgb(test, s.range == Range::ldr);
  if (!s.grey || !is_grey(rgb)) {  // NaN pixels: the colour path, as the uncached functions take
    HdrFlipSettings hdr;
    hdr.base = s.settings;
    return mean(s.range == Range::ldr ? ldr_flip_map(s.reference, rgb, s.settings) : hdr_flip_map(s.reference, rgb, hdr));
  }
  check_pair(s.reference, rgb, "GreyFlipReference");
  std::vector<float> out(static_cast<std::size_t>(rgb.width) * rgb.height, 0.0f);
  if (out.empty()) return mean(out);
  Workspace ws(rgb.width, rgb.height, s.kernels, true);
  for (int i = 0; i < s.exposures.count; ++i) {
    if (s.range == Range::ldr)
      load_plane(ws, 1, rgb, true, decoded);
    else
      load_plane(ws, 1, rgb, true, exposed(exposure_scale(s.exposures, i)));
    flip_core(ws, s.kernels, out.data(), i > 0, &s.filtered[static_cast<std::size_t>(i)]);
  }
  return mean(out);
}

}  // namespace saagen::measure

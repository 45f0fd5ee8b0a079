// saagen ground-truth renderer: NVIDIA's FLIP image-difference metric.
//
// LDR-FLIP: P. Andersson, J. Nilsson, T. Akenine-Moller, M. Oskarsson, K. Astrom, M. D. Fairchild,
//   "FLIP: A Difference Evaluator for Alternating Images", Proc. ACM Comput. Graph. Interact. Tech.
//   3(2) (HPG 2020).
// HDR-FLIP: P. Andersson, J. Nilsson, P. Shirley, T. Akenine-Moller, "Visualizing Errors in
//   Rendered High Dynamic Range Images", Eurographics 2021 short papers.
// Written from the papers; constants, filter radii, border handling and the exposure computation
// were checked against the public reference implementation (github.com/NVlabs/flip, v1.2-v1.6,
// whose LDR results are unchanged between those versions).
//
// LDR-FLIP, step by step. Each step names the part of the HPG 2020 paper it implements and
// writes the paper's equation out (the equations are quoted by content, not by number):
//  1. Colour pipeline, input transform. Inputs are sRGB-encoded in [0,1] (clamped). sRGB EOTF
//     (IEC 61966-2-1) to linear RGB; linear RGB -> CIE XYZ with the exact sRGB-primaries/D65
//     matrix; XYZ -> YCxCz (the opponent space of Zhang & Wandell's S-CIELAB):
//         Y = 116 Y/Yn - 16,   Cx = 500 (X/Xn - Y/Yn),   Cz = 200 (Y/Yn - Z/Zn),
//     reference white (Xn, Yn, Zn) = D65 = the matrix's row sums.
//  2. Colour pipeline, spatial filtering with the contrast sensitivity functions (CSFs): each
//     YCxCz channel is convolved with the spatial-domain CSF filter
//         s(x) = sum_k a_k sqrt(pi / b_k) exp(-pi^2 |x|^2 / b_k),   |x| in degrees,
//     Y (achromatic):  a1 = 1,    b1 = 0.0047
//     Cx (red-green):  a1 = 1,    b1 = 0.0053
//     Cz (blue-yellow):a1 = 34.1, b1 = 0.04,  a2 = 13.5, b2 = 0.025
//     sampled at pixel centres |x| = (i, j) / ppd over a square of radius
//     r = ceil(3 sqrt(max_k b_k / (2 pi^2)) ppd) (three standard deviations of the widest
//     Gaussian, one radius for all channels), and normalised to unit sum. Every term is
//     separable, g_k(x) g_k(y) with g_k(t) = sqrt(a_k sqrt(pi / b_k)) exp(-pi^2 t^2 / b_k), so
//     the filter runs as two 1-D passes per Gaussian term. Borders clamp to the edge pixel.
//  3. The filtered YCxCz is taken back to linear RGB and clamped to [0,1] (keeps the filtered
//     colours inside the gamut), then to CIELAB (L*a*b*, D65 white above).
//  4. Hunt adjustment (colour pipeline): a' = 0.01 L a, b' = 0.01 L b.
//  5. HyAB distance (Abasi et al. 2020): dE = |L1 - L2| + sqrt((a'1 - a'2)^2 + (b'1 - b'2)^2).
//  6. Colour-error remapping: dE' = dE^qc with qc = 0.7;
//     cmax = HyAB(Hunt(Lab(green)), Hunt(Lab(blue)))^qc (green (0,1,0), blue (0,0,1): the largest
//     distance in the gamut); pc = 0.4, pt = 0.95:
//         Ec = pt dE' / (pc cmax)                                    if dE' <  pc cmax,
//         Ec = pt + (dE' - pc cmax) / (cmax - pc cmax) (1 - pt)      otherwise.
//  7. Feature pipeline (edges and points), on the unfiltered achromatic channel normalised to
//     [0,1], (Y + 16) / 116 (= relative luminance; the paper's erratum: 116, not 100). Gaussian
//     of standard deviation sigma = 0.5 w ppd pixels with the feature width w = 0.082 degrees,
//     radius ceil(3 sigma);
//     edge filter = first derivative of the Gaussian (-x G), point filter = second derivative
//     ((x^2/sigma^2 - 1) G); the Gaussian is normalised to unit sum, each derivative filter so
//     that its positive weights sum to 1 and its negative weights to -1. In 2-D the x-edge
//     filter is dG(x) G(y), the x-point filter ddG(x) G(y), likewise in y (separable).
//     |edge| = sqrt(ex^2 + ey^2), |point| = sqrt(px^2 + py^2), and
//         Ef = ( max(| |edge_r| - |edge_t| |, | |point_r| - |point_t| |) / sqrt(2) )^qf,  qf = 0.5.
//  8. Final FLIP error, combining the two pipelines: e = Ec^(1 - Ef), per pixel, in [0,1]
//     (Ec = 0 gives e = 0 even in the degenerate case Ef = 1, where std::pow's 0^0 would be 1).
//
// HDR-FLIP (Eurographics 2021):
//  - Tone mapper: ACES filmic fit (Narkowicz 2015) with the 0.6 pre-exposure cancelled, as in the
//    paper and the reference code: t(x) = (0.6^2 2.51 x^2 + 0.6 0.03 x) / (0.6^2 2.43 x^2 +
//    0.6 0.59 x + 0.14), per linear RGB channel, then clamped to [0,1].
//  - Automatic exposure range: x_max solves t(x_max) = 0.85; with Y the luminance
//    (0.2126 R + 0.7152 G + 0.0722 B) of the *reference*,
//        c_start = log2(x_max / Y_max),   c_stop = log2(x_max / Y_median),
//    Y_median being the element of rank floor(n/2) of the n sorted luminances (as the reference
//    implementation). Number of exposures N = max(2, ceil(c_stop - c_start)), exposures
//    c_i = c_start + i (c_stop - c_start) / (N - 1).
//  - For every exposure: both images scaled by 2^c_i, tone mapped, clamped, LDR-FLIP from step 1's
//    linear RGB (no sRGB coding: the tone-mapped values are already linear display values);
//    HDR-FLIP is the per-pixel maximum over the exposures.
//  Extensions where the paper's formulas are undefined (documented, not in the reference):
//    Y_max <= 0 (black reference): c_start = c_stop = 0; Y_median <= 0 (e.g. more than half of
//    the pixels black, common for saagen's specular images): Y_median is replaced by the median
//    (same rank rule) of the positive luminances; num_exposures == 1: one exposure at c_start.
//
// Implementation notes: double precision throughout (the reference is float32; see
// tests/measure/test_flip.cpp for the comparison with its published outputs, matched to its 6 printed
// decimals and on >= 99.9% of the pixels of its 8-bit map). Single-threaded; separable filters
// with precomputed kernels; NaN inputs count as 0. When both images are grey (R = G = B in every
// pixel, e.g. saagen's specular images) the chroma channels are identically 0 and are neither
// filtered nor converted: the colour difference is then |L*_r - L*_t| (HyAB with a* = b* = 0), the
// same value in exact arithmetic. Cost at 256 x 256 grey: about 10 ms of one core per exposure.
#pragma once

#include "saagen/measure/image.hpp"

#include <memory>
#include <optional>
#include <vector>

namespace saagen::measure {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major, 3 floats per pixel, row 0 top
};

// FLIP's viewing setup: 0.7 m from a 0.7 m wide, 3840 px wide monitor gives
// 0.7 * (3840 / 0.7) * pi / 180 = 67.0206... pixels per degree, the NVlabs tool's default (it
// prints it rounded, "67"). FlipSettings defaults to 67.0 exactly, as saagen specified and as the
// nv-flip Rust bindings do (their published outputs, used in tests/measure/test_flip.cpp, are for 67.0);
// pass kFlipToolPixelsPerDegree to reproduce the NVlabs tool's default run (the mean FLIP moves by
// about 1e-5).
inline constexpr double kFlipToolPixelsPerDegree = 0.7 * (3840.0 / 0.7) * (3.14159265358979323846 / 180.0);

struct FlipSettings {
  double pixels_per_degree = 67.0;
};

// LDR-FLIP on two sRGB-encoded images with values in [0,1] (the paper's input; values outside
// are clamped). Returns the per-pixel error map in [0,1], row-major, width * height floats.
// Throws std::invalid_argument on a size mismatch or a malformed image.
std::vector<float> ldr_flip_map(const RgbImage& reference, const RgbImage& test, const FlipSettings& = {});

// HDR-FLIP on linear-radiance images (see the header comment for the exposure range).
struct HdrFlipSettings {
  FlipSettings base;
  std::optional<double> start_exposure, stop_exposure;  // unset: computed from the reference
  int num_exposures = 0;                                // 0: automatic
};

std::vector<float> hdr_flip_map(const RgbImage& reference, const RgbImage& test, const HdrFlipSettings& = {});

// The exposure range HDR-FLIP uses for `reference` under `settings` (automatic values where unset).
struct HdrExposures {
  double start = 0.0, stop = 0.0;
  int count = 0;
};
HdrExposures hdr_flip_exposures(const RgbImage& reference, const HdrFlipSettings& = {});

// The HDR-FLIP tone mapper (ACES fit, see above) of one linear channel value, not clamped.
double flip_aces_tonemap(double x);
// x_max with flip_aces_tonemap(x_max) = 0.85 (the larger root of the quadratic).
double flip_aces_x_max();

// Arithmetic mean of an error map (double accumulation); 0 for an empty map.
double mean(const std::vector<float>& map);

// Convenience for saagen's single-channel (grey) images, R = G = B = the pixel value.
// ldr_flip_mean_grey: the inputs are display-referred linear values in [0,1] (e.g. tonemap()ped,
// NOT yet sRGB-encoded; clamped to [0,1]). FLIP's input is the sRGB-encoded signal, so each value
// is first encoded with the sRGB OETF (srgb_encode(), image.hpp: 12.92 v for v <= 0.0031308, else
// 1.055 v^(1/2.4) - 0.055) and then passed to ldr_flip_map (whose first step decodes it again).
double ldr_flip_mean_grey(const Image& reference_display, const Image& test_display);
// hdr_flip_mean_grey: linear radiance, automatic exposures; mean(hdr_flip_map(...)).
double hdr_flip_mean_grey(const Image& reference_linear, const Image& test_linear);

// ldr_flip_mean_grey / hdr_flip_mean_grey of many test images against one reference (the trade
// compares every configuration with one ground truth). The reference's half of the work, its
// CSF and feature filtering (for HDR-FLIP at each of its exposures), is done once here, so each
// comparison filters only its test image. The results are those functions' exactly: the same
// operations in the same order (a test or reference with NaN pixels takes their path).
// mean_error may be called from several threads at once.
class GreyFlipReference {
 public:
  enum class Range { ldr, hdr };  // ldr: display values in [0, 1]; hdr: linear radiance
  GreyFlipReference(const Image& reference, Range range, const FlipSettings& settings = {});
  double mean_error(const Image& test) const;

 private:
  struct State;
  std::shared_ptr<const State> state_;
};

}  // namespace saagen::measure

// saagen ground-truth renderer: the ColorVideoVDP video difference metric, in JOD.
//
// R. K. Mantiuk, P. Hanji, M. Ashraf, Y. Asano, A. Chapiro, "ColorVideoVDP: A visual difference
// predictor for image, video and display distortions", ACM Trans. Graph. 43(4), 2024 (the paper).
// Written from the paper and the model's published data: the calibrated parameters
// (cvvdp_parameters.json, version 0.5.6), the castleCSF lookup table of the parameter file's `csf`
// variant (csf_lut_weber_fixed_size.json), the display model standard_fhd (display_models.json) and
// its colour space (color_spaces.json), all of ColorVideoVDP 0.5.4 (github.com/gfxdisp/ColorVideoVDP,
// MIT, commit 7ca201accf78), embedded as numbers by scripts/video_vdp_tables.py. Where the paper
// leaves a numerical detail open (border handling, offsets and clamps), the behaviour is that of
// that release, which the parameters were calibrated with; each such detail says so below. The
// match with the reference implementation (pycvvdp) is in docs/COLORVIDEOVDP.md and
// tests/measure/test_video_vdp.cpp.
//
// The model, step by step (keys of cvvdp_parameters.json in brackets):
//  1. Display model (paper: photometric display model). A display-encoded value V in [0, 1]
//     (clamped) is emitted as luminance
//         L = (L_peak - L_black) EOTF(V) + L_black + L_refl,
//     EOTF = the sRGB decoding, L_black = L_peak / contrast, L_refl = k_refl E_ambient / pi
//     (ambient light reflected by a matte screen). standard_fhd: L_peak 200 cd/m^2, contrast
//     1000, E_ambient 250 lux, k_refl 0.005.
//  2. Colour (paper: colour space). Linear RGB (grey input: R = G = B = L) -> CIE XYZ
//     (color_spaces.json) -> LMS cone responses (CIE 2006) -> DKL opponent channels with a D65
//     white: achromatic L + M, red-green L - 2.3111 M, yellow-violet -L - M + 50.9776 S.
//  3. Temporal channels (paper: temporal channels). Four channels: sustained achromatic,
//     red-green and yellow-violet, transient achromatic. Each is a filter of N = 2 ceil(fps / 8)
//     + 1 taps (250 ms; 9 at 30 fps) whose frequency response at omega = 0 .. fps/2 Hz
//     ((N + 1) / 2 samples) is
//         sustained c:  R_c(omega) = exp(-omega^beta_c / sigma_c)                [beta_tf, sigma_tf]
//         transient:    R_3(omega) = exp(-(omega^beta_3 - 5^beta_3)^2 / sigma_3)
//     and whose taps are the real inverse DFT of that response, centred (tap k holds lag
//     k - (N - 1) / 2). Frame t of a channel is sum_k F[k] X[t - k] over the past N frames
//     (the achromatic channel X feeds both achromatic channels), frames before the first
//     repeating the first (the reference's default padding), so a clip shorter than the filter
//     is handled. A single frame is an image: three sustained channels and no filtering.
//  4. Multi-scale decomposition (paper: Laplacian pyramid). A decimated Gaussian pyramid with
//     the 5-tap kernel [0.25 - a/2, 0.25, a, 0.25, 0.25 - a/2], a = 0.4, symmetric borders
//     (the edge sample repeated), of n = height + 1 levels; band b < n - 1 is level b minus
//     level b + 1 expanded (zeros interleaved, the kernel times 2), the last band (the base
//     band) is the last Gaussian level. Band frequencies from the display's pixels per degree:
//     rho_0 = ppd / 2, rho_b = 0.3228 2^-(b-1) ppd / 2 (b >= 1), the base band's 0.1 cpd;
//     height = min(first b with rho_b <= 0.2, floor(log2 min(W, H)) - 1), at least 0: a small
//     image has fewer bands (one, the base band alone, below 4 pixels).
//  5. Contrast (paper: local adaptation, contrast `weber_g1`). Band b < n - 1 of every channel
//     is divided by its own image's local adaptation luminance, the achromatic sustained
//     channel's level b + 1 expanded (at least 0.01 cd/m^2); the base band by the mean of the
//     clamped last level. Contrast is at most 1000; the bands between the first and the base
//     band are doubled (the reference's band scaling).
//  6. Sensitivity (paper: castleCSF). S = 10^(log S(rho_b, L_a)) 10^(sensitivity_correction / 20)
//     with L_a the reference clip's adaptation luminance of step 5 and log S interpolated
//     linearly in log10 rho (extrapolated beyond the table) and log10 L_a (clamped to the
//     table) from the table's channel (omega 0 Hz for the sustained channels, 5 Hz for the
//     transient). [csf, sensitivity_correction]
//  7. Masking (paper: cross-channel contrast masking, `mult-mutual`). Per band below the base
//     band, with channel gains g = (1, 1.45, 1, 1):
//         T' = g S T,  R' = g S R,
//         M_c = 10^mask_c PU(min(|T'_c|, |R'_c|))                               [mask_c]
//         M'_c = sum_k 2^xcm[4k + c] pow(M_k, q_k)                              [xcm_weights, mask_q]
//         D_c = clamp(pow(|T'_c - R'_c|, p) / (1 + M'_c))                       [mask_p]
//     PU: a Gaussian blur of standard deviation pu_dilate = 3 pixels (13 taps, mirrored borders)
//     where the band is larger than 6 x 6, none on smaller bands [pu_dilate]; clamp(D) =
//     D_max D / (D_max + D), D_max = 10^d_max [dclamp_type soft, d_max]. The base band is not
//     masked: D_c = S_c |T_c - R_c|.
//  8. Pooling (paper: pooling). Per frame, band and channel the p-mean over the pixels
//     (beta = 2); then the p-norm over the bands (beta_sch = 4) of those values times the
//     channel weights (1, ch_chrom_w, ch_chrom_w, ch_trans_w) and, on the base band, the
//     baseband_weight; the p-norm over the channels (beta_tch = 4); the p-mean over the
//     frames (beta_t = 2), or for an image the value times image_int.
//     Every power here and in step 7 is the reference's offset power
//         pow(x, e) = (x + 1e-5)^e - 1e-5^e,
//     whose offset the parameters were calibrated with (without it the JODs of the bench's
//     clips move by up to 0.007).
//  9. JOD (paper: JOD regression): Q_JOD = 10 - jod_a Q^jod_exp for Q > 0.1, and below it the
//     straight line from 10 at Q = 0 to that curve at Q = 0.1, 10 - jod_a 0.1^(jod_exp - 1) Q
//     (the reference's form, differentiable at 0).  [jod_a, jod_exp]
//
// Implementation notes: double precision, but for the powers with a fractional exponent of
// step 7 (in single precision, as the reference computes everything: they move a JOD by < 1e-7
// and take half the time); one thread per comparison; the reference clip's half of the work (its
// channels, pyramid, adaptation luminance and sensitivities) is done once by VideoVdpReference.
// The reference implementation's pyramid reduction borders the last column by the parity of the
// rows, not of the columns (a difference only where they differ: never on a square clip); that is
// reproduced (reduce() in video_vdp.cpp), so that non-square clips match too.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace saagen::measure {

// A grey clip: `frames` frames of width x height display-encoded values in [0, 1] (the same
// value in R, G and B), frame-major then row-major, row 0 at the top:
// pixels[(t * height + y) * width + x].
struct GreyClip {
  int width = 0, height = 0, frames = 0;
  std::vector<float> pixels;
};

// A display (display_models.json's fields). EOTF sRGB, sRGB primaries.
struct VideoVdpDisplay {
  std::string name;
  int resolution_width = 0, resolution_height = 0;  // pixels
  double viewing_distance_m = 0.0;
  double diagonal_inches = 0.0;
  double peak_luminance = 0.0;       // cd/m^2
  double contrast = 0.0;             // peak / black
  double ambient_illuminance = 0.0;  // lux
  double reflectivity = 0.0;         // k_refl
};

// display_models.json's standard_fhd: a 24-inch 1920 x 1080 monitor, 200 cd/m^2, contrast 1000,
// seen from 0.6 m under 250 lux (37.84 pixels per degree).
VideoVdpDisplay video_vdp_standard_fhd();

// Pixels per visual degree at the centre of the display: 1 / (2 atan(w / (2 n d))) in degrees,
// w the display's width from its diagonal and aspect ratio, n its horizontal resolution, d the
// viewing distance.
double video_vdp_pixels_per_degree(const VideoVdpDisplay& display);

struct VideoVdpResult {
  double jod = 10.0;     // 10: no visible difference; lower is worse (may go below 0)
  double quality = 0.0;  // the pooled difference Q (step 8) the JOD maps
  // Per frame: the JOD of a clip whose every frame differed as this one (step 9 of the frame's
  // pooled Q, before the p-mean over the frames): how the difference varies over the clip.
  std::vector<double> frame_jod;
};

// The reference clip's half of ColorVideoVDP, computed once; compare() any number of test clips
// of its size with it (from several threads at once). Throws std::invalid_argument on an empty
// or malformed clip, a display without a positive size, distance or luminance, or fps <= 0 for a
// clip of more than one frame.
class VideoVdpReference {
 public:
  VideoVdpReference(const GreyClip& reference, const VideoVdpDisplay& display, double frames_per_second);
  // Throws std::invalid_argument when `test` is not the reference's size and frame count.
  VideoVdpResult compare(const GreyClip& test) const;
  int bands() const;  // spatial bands, the base band included

 private:
  struct State;
  std::shared_ptr<const State> state_;
};

// One comparison: VideoVdpReference(reference, display, fps).compare(test).
VideoVdpResult video_vdp(const GreyClip& test, const GreyClip& reference, const VideoVdpDisplay& display, double frames_per_second);

}  // namespace saagen::measure

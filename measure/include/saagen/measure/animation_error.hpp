// The trade's verdict metrics on an animation, and their uncertainty.
//
// Two criteria, both measured on the display values of the animation (display_image(): tonemap,
// then the sRGB encoding), frame by frame, so that two configurations can be compared frame by
// frame (paired) and every mean gets an interval:
//
//   image error     LDR-FLIP (Andersson et al. 2020) of frame t against the ground truth's frame t,
//                   one value per frame. Unlike frame 0 alone, it sees a result that lags the
//                   motion (a delayed image) or stops following it (a frozen one).
//   flicker error   for each pair of consecutive frames, the mean over pixels of
//                     | G * |I_t - I_{t-1}|  -  G * |R_t - R_{t-1}| |,
//                   G a normalised Gaussian of standard deviation kFlickerPoolingSigma pixels: the
//                   magnitude of change of the result against the ground truth's, pooled over a
//                   neighbourhood before they are compared. TDE (image.hpp) compares the signed
//                   change pixel by pixel, so a highlight that moves through other pixels than the
//                   ground truth's is counted twice (where it is, where it should be) and a
//                   frozen or missing one once: TDE ranked a frozen image above the converged
//                   animation rendered with another seed. Pooling the magnitude of change first
//                   (flicker energy compared over a neighbourhood, as the spatial pooling of
//                   video quality metrics does; Mantiuk et al. 2021, FovVideoVDP, and 2024,
//                   ColorVideoVDP) counts a displaced highlight once and a frozen one as all the
//                   motion it misses. Its parts:
//                     excess   mean max(0, G*|dI| - G*|dR|): change the ground truth does not make
//                              (aliasing: a highlight popping from pixel to pixel);
//                     missing  mean max(0, G*|dR| - G*|dI|): motion the result does not show.
//                   error = excess + missing.
//   lag             for each frame t after the first, the mean over pixels of
//                     (I_t - R_t)^2 - (I_t - R_{t-1})^2:
//                   whether frame t of the result is closer to the ground truth's frame t or to
//                   its previous frame. With independent noise in I and R its expectation is
//                   |E I_t - E R_t|^2 - |E I_t - E R_{t-1}|^2 (the noise cancels): about -|motion|^2
//                   for a result that follows the motion, +|motion|^2 for one a frame late. The
//                   video metric hardly sees a one-frame delay (a converged image shown a frame
//                   late is a good-looking clip); a result that lags more than no SAA is late,
//                   and the decision never takes it (saagen/decision.hpp).
//
// Neither criterion ranks anything before it passed the sanity suite (sanity.hpp): results whose
// ranking is known (the ground truth with another seed, with a quarter of its samples, delayed by
// a frame, blurred, frozen, without its highlight) must rank as expected on every scene.
#pragma once

#include "saagen/measure/image.hpp"

#include <array>
#include <span>
#include <vector>

namespace saagen::measure {

// The pooling footprint of the flicker error, in pixels of the animation: a highlight displaced
// by up to about a pixel (the step of 1-spp aliasing) stays inside one neighbourhood.
inline constexpr double kFlickerPoolingSigma = 1.5;

// `image` convolved with a normalised Gaussian of standard deviation `sigma` pixels (separable,
// truncated at 3 sigma; at the border the weights inside the image are renormalised).
Image gaussian_pooled(const Image& image, double sigma);

// G * |current - previous|: the pooled magnitude of change between two frames of one size.
Image pooled_change(const Image& previous, const Image& current, double sigma = kFlickerPoolingSigma);

struct FlickerError {
  double error = 0.0;
  double excess = 0.0;
  double missing = 0.0;
};

// The flicker error of one frame pair from the two pooled changes (pooled_change()).
FlickerError flicker_error(const Image& pooled_change_result, const Image& pooled_change_reference);

// The lag of one frame (see the top of this file): mean over pixels of (I - R)^2 - (I - P)^2 for
// the result's frame I, the ground truth's frame R and its previous frame P (display values,
// display_image()). All three of one size.
double lag_error(const Image& result, const Image& reference, const Image& previous_reference);

// A mean and its 95 % interval.
struct Interval {
  double mean = 0.0;
  double low = 0.0;
  double high = 0.0;
  double half_width() const { return 0.5 * (high - low); }
};

// Student's t quantile t_{0.975, dof} (two-sided 95 %), dof >= 1.
double student_t_975(int dof);

// Frames of one animation are correlated (the surface moves slowly under a fixed sample pattern),
// so a series of per-frame values is reduced to the means of consecutive blocks of this many
// frames, which are treated as independent (the batch-means method; e.g. Law and Kelton,
// "Simulation Modeling and Analysis", sec. 9.5.3).
inline constexpr int kFramesPerBlock = 4;

// The block means of a series (blocks of kFramesPerBlock; the last block takes the remainder; a
// series shorter than two blocks gives one block per value).
std::vector<double> block_means(std::span<const double> series);

// A mean over units (block means, over every cell) with its t interval, widened by the ground
// truth's Monte-Carlo error: `ground_truth_sd` is the standard deviation of the mean due to the
// ground truth alone (estimated from two seeds; ground_truth_spread()), added in quadrature with
// the normal quantile. One unit: the interval is the ground truth's alone.
Interval mean_interval(std::span<const double> units, double ground_truth_sd);

// The standard deviation, due to the ground truth, of a mean over cells of the average of two
// estimates, each against its own ground-truth seed: per cell, (estimate_a - estimate_b) / 2 is
// a one-sample estimate of the standard deviation of their average; over independent cells their
// squares add, divided by the number of cells squared.
double ground_truth_spread(std::span<const double> estimate_a, std::span<const double> estimate_b);

// A per-frame series measured against each ground-truth seed: [0] against the first, [1] against
// the second (empty when only one was rendered).
using SeedSeries = std::array<std::vector<double>, 2>;

// The mean over cells (e.g. a scene's alphas) of the seed-averaged series, with its 95 %
// interval: the units are every cell's block means (the variation over frames, pixels and
// cells), widened by the ground truth's spread between the seeds' cell means. For a difference
// between two configurations, pass the frame-by-frame differences (paired_difference()).
Interval series_interval(std::span<const SeedSeries> cells);

// The frame-by-frame difference a - b of two series of one clip (the same frames and seeds).
SeedSeries paired_difference(const SeedSeries& a, const SeedSeries& b);

// A difference and the ground truth's part of its uncertainty, for the verdict: the standard
// deviation of the mean due to the ground truth alone (ground_truth_spread() over the cells).
double series_ground_truth_sd(std::span<const SeedSeries> cells);

}  // namespace saagen::measure

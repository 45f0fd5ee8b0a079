// saagen ground-truth renderer: a temporal anti-aliasing (TAA) resolve of the 1-spp frames.
//
// Written from the public descriptions: B. Karis, "High-Quality Temporal Supersampling",
// SIGGRAPH 2014 course Advances in Real-Time Rendering (Unreal Engine 4's TAA), and M. Salvi,
// "An Excursion in Temporal Supersampling", GDC 2016 (variance clipping). Per frame:
//
//   jitter      the camera is offset by a sub-pixel amount (Camera::jitter) from the Halton
//               (2, 3) low-discrepancy sequence, `sequence_length` positions in [-0.5, 0.5)^2,
//               then repeating (Karis 2014; UE4 ships 8). The whole 1-spp frame is rendered with
//               it: the G-buffer rays, hence the quad derivatives every SAA filter reads, come
//               from the jittered quad, as on a GPU (the jitter is in the projection matrix).
//   current     the jittered samples resolved at the pixel centre: a Gaussian of variance
//               `current_filter_variance` (px^2) over the 3 x 3 neighbourhood's samples at their
//               jittered positions, truncated at 1.5 px per axis (Karis 2014 fits a Gaussian to
//               Blackman-Harris; 0.25 px^2 truncated at 3 sigma is the ground truth's pixel filter,
//               sampling.hpp, so the converged static resolve integrates that filter); 0: the
//               pixel's own sample.
//   reproject   the history is fetched where the current pixel's surface point was in the
//               previous frame: the point seen through the jittered sample, taken back through
//               the scene's exact rigid motion (Scene::object_to_world of both frames) and
//               projected with the previous, unjittered camera (Camera::project), minus the
//               current jitter (the jitter is not motion). Pixels that see the background keep
//               their position (it lies at infinity: the camera only translates).
//   history     sampled there with a 4 x 4 Catmull-Rom filter (Karis 2014: less blur than
//               bilinear over many reprojections) or bilinearly, clamped to the image's edge;
//               a point that projects outside the previous image has no history.
//   clip        variance clipping (Salvi 2016): the history is clipped to mu +- gamma sigma of
//               the 3 x 3 neighbourhood's current samples (gamma = clip_gamma, 1 by default).
//               Salvi clips in YCoCg; the renderer's images hold one grey value (the specular
//               radiance of a white light), whose chroma Co = Cg = 0, so the YCoCg box reduces
//               to its Y extent and the clip to a clamp of Y.
//   blend       out = history + blend (current - history), an exponential moving average; blend
//               0.1 (Salvi 2016: "typically we blend 10% of the current frame"). With
//               luma_weighting, every step from the current filter to the blend runs on
//               Reinhard's x / (1 + x) and the result is mapped back (Karis 2014's inverse
//               luminance weighting: a rare bright sample cannot dominate the history). The
//               mean of x / (1 + x) mapped back is exactly the 1 / (1 + x)-weighted mean of x,
//               so a sub-pixel highlight converges below its pixel's mean radiance: the
//               weighting trades highlight energy for stability (test_taa measures the
//               unweighted resolve's convergence).
//
// The first frame (no history) outputs the current resolve. TaaResolve keeps the history of
// one image stream; reproject_history gives its per-pixel history positions.
#pragma once

#include "saagen/measure/image.hpp"
#include "saagen/measure/renderer.hpp"
#include "saagen/measure/scene.hpp"

#include <string_view>
#include <vector>

namespace saagen::measure {

enum class HistoryFilter { catmull_rom, bilinear };
std::string_view history_filter_name(HistoryFilter filter);  // "catmull-rom", "bilinear"

struct TaaOptions {
  int sequence_length = 8;                // Halton (2, 3) positions per cycle (Karis 2014: 8)
  double blend = 0.1;                     // the current frame's weight (Salvi 2016)
  double clip_gamma = 1.0;                // variance box half-width in standard deviations (Salvi 2016)
  double current_filter_variance = 0.25;  // px^2; 0: the pixel's own sample
  HistoryFilter history_filter = HistoryFilter::catmull_rom;
  bool luma_weighting = true;  // resolve in x / (1 + x) (Karis 2014)
};

// Throws std::invalid_argument naming the option when one is out of range (sequence_length in
// [1, 256], blend in (0, 1], clip_gamma > 0 (infinity: no clip), current_filter_variance >= 0).
void check_taa_options(const TaaOptions& options);

// The radical inverse of index in base (Halton 1964): the digits of index mirrored about the
// radix point.
double radical_inverse(int index, int base);

// The jitter of frame `frame` (>= 0), in pixels (x right, y down): Halton (2, 3) of index
// (frame mod sequence_length) + 1 minus (0.5, 0.5) (index 0 would be the corner (0, 0) of every
// cycle).
Vec2 taa_jitter(int frame, int sequence_length);

// Where each pixel's history lies in the previous frame (film positions, pixels; pixel (x, y)'s
// centre is (x + 0.5, y + 0.5)); NaN where it has none (the point projects outside the
// previous image or behind its camera). gbuffer: the current frame rendered from `current`
// (whose camera carries the jitter); previous: the previous frame's scene (its jitter ignored).
std::vector<Vec2> reproject_history(const GBuffer& gbuffer, const Scene& current, const Scene& previous);

// The history of one image stream.
class TaaResolve {
 public:
  TaaResolve(int width, int height, const TaaOptions& options);

  // Resolves one frame: `samples` the 1-spp radiance rendered with camera jitter `jitter`,
  // `history_positions` from reproject_history (ignored on the first frame). Returns the
  // resolved radiance (linear), which becomes the history.
  const Image& resolve(const Image& samples, Vec2 jitter, const std::vector<Vec2>& history_positions);

  const Image& output() const { return output_; }
  bool has_history() const { return has_history_; }

 private:
  double to_space(double radiance) const;
  double from_space(double value) const;
  double current_at(const Image& space, Vec2 jitter, int x, int y) const;
  double history_at(Vec2 position) const;

  TaaOptions options_;
  int width_, height_;
  Image history_;  // in the resolve's space (x / (1 + x) with luma weighting)
  Image output_;   // linear
  bool has_history_ = false;
};

}  // namespace saagen::measure

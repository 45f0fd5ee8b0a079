// saagen ground-truth renderer: the quality trade table of the SAA variants.
//
// For every scene, GGX alpha, Fresnel switch and variant, the 1-spp image of the variant is
// compared with the ground truth of the same view (renderer.hpp):
//   rmse_linear      RMSE of linear specular radiance over all pixels;
//   rmse_tonemapped  RMSE after Reinhard's x / (1 + x) on both images (image.hpp);
//   max_error        the largest absolute linear error of a pixel;
//   flip_ldr         mean LDR-FLIP (Andersson et al. 2020) of the tonemapped images;
//   flip_hdr         mean HDR-FLIP (Andersson et al. 2021) of the linear images;
//   tde              temporal difference error (image.hpp, TemporalDifference): the animation
//                    below, in display values (display_image(): tonemap(), then the sRGB
//                    encoding LDR-FLIP takes); mean over pixels and consecutive frame pairs of
//                    |(I_t - I_{t-1}) - (R_t - R_{t-1})| of the 1-spp frames I against the
//                    ground-truth frames R (the pixel-level tLP of Chu et al. 2020, TecoGAN).
//                    0: the frames change as the converged animation does. Its parts:
//   tde_excess_flicker  mean max(0, |dI| - |dR|): change the ground truth does not make
//                    (aliasing: sub-pixel highlights popping from pixel to pixel);
//   tde_lost_motion  mean max(0, |dR| - |dI|): change the ground truth makes that is missing
//                    (a highlight blurred or clamped away, which a std ratio rewards);
//   flicker          per pixel, the temporal standard deviation of the variant's 1-spp frames
//                    minus that of the ground-truth frames, averaged over the pixels (linear
//                    values; image.hpp, flicker());
//   flicker_display  (secondary) the mean per-pixel temporal std of the tonemapped 1-spp frames
//                    divided by that of the tonemapped ground truth. A method that loses the
//                    moving highlight scores below 1 and looks "stable": the verdicts use tde.
//
// The animation (trade_animation_frame). Frame k of `frames`: the scene rotated about the
// vertical axis through its pivot by k times rotation_degrees_per_frame (make_scene), seen
// through the camera translated parallel to its film by (k - (frames - 1) / 2) times
// pan_pixels_per_frame (right, up), in pixels of the flicker resolution measured at the look-at
// distance (Camera::panned). The rotation alone moves little on screen (the torus turns under a
// highlight that stays nearly fixed, the sphere slides slowly about its off-centre pivot); the pan slides every sub-pixel highlight across
// the pixel grid by a fraction of a pixel per frame (0.11, 0.37 by default: the sub-pixel phase does not repeat within 32 frames), the
// motion at which 1-spp specular aliasing shimmers. It is mostly vertical, across the sideways slide of the sphere's off-centre rotation
// rather than against it, and centred on the unpanned view so that the shapes stay in frame.
//
// Flicker ground truth. 32 converged frames at the full resolution and 1024 spp would cost 32
// times the main ground truth, so the animation is rendered at flicker_width x flicker_height
// (default 128 x 128, half the main resolution) with flicker_strata^2 samples per pixel (default
// 16^2 = 256), and the 1-spp frames of the variants at that same resolution. Every frame uses
// the same per-pixel sample pattern (the pixel seeds do not depend on the frame), so the
// ground truth's residual Monte-Carlo error is correlated from frame to frame and changes only
// as the surface moves under the pattern: its temporal standard deviation measures mostly the
// motion of the converged image, not sampler noise. Measured at 128 x 128 over 8 frames of the
// rotation alone (before the pan), the mean temporal standard deviation of the ground truth at
// 256 spp is within 2 % of the 1024-spp value for every scene and alpha except the bump plane
// at alpha = 0.01 (0.84 at 256 spp, 0.69 at 1024, 1.19 at 64: its sub-pixel glints are not
// converged), so that case's flicker is biased low by ~0.15-0.25 (against 1-spp standard
// deviations of 0.5 - 2.3). Set flicker_strata = 32 for 1024 spp (4 x the cost).
//
// Ground-truth images can be cached on disk (cache_dir): one file per (scene, rotation, camera
// (hence the pan), size, samples, seed, filter, material list), named by a 64-bit FNV-1a hash of a text key holding
// every one of those numbers (and a format version); the key is stored in the file and
// compared on load, so a hash collision or a stale file only costs a re-render; so does a file
// whose pixels do not match the FNV-1a checksum stored with them (a corrupted file).
//
// A ground truth is checked before it is measured against: one holding a non-finite pixel, or
// black in every material (nothing of the scene lit in view: a camera scaled to nothing, an
// asset at one point), is a TradeError naming the scene, not a measurement in which every
// configuration errs by 0.
//
// Under TAA (TradeConfig::taa; taa.hpp). Each configuration (no SAA, every variant with its
// feeds, prefilters and lobes, every engine form) is also run through the TAA resolve as a row
// "CONFIGURATION+taa" ("forward-aniso-projected+taa/tail"): the animation at the flicker
// resolution, each 1-spp frame rendered with the Halton jitter (so the filters' derivatives come
// from the jittered quads), resolved with the history reprojected by the exact motion. A
// warm-up of taa_warmup_frames (default: one jitter cycle) before the animation's frame 0 fills
// the history; then, over the `frames` measured frames, the row's image metrics are means over
// the frames against each frame's ground truth (rmse_*, flip_ldr = flip_ldr_animation;
// max_error the largest; flip_hdr of the last frame) and its temporal ones are those of the
// resolved frames (tde and its parts, flicker), directly comparable with the rows without TAA.
// Every row without TAA gets the same flip_ldr_animation (mean LDR-FLIP of its 1-spp frames
// against the frames' ground truths), the figure to compare with a +taa row's flip_ldr (its own
// flip_ldr is frame 0's at the main resolution). The ground truths do not depend on the lobe.
#pragma once

#include "saagen/measure/animation_error.hpp"
#include "saagen/measure/image.hpp"
#include "saagen/measure/renderer.hpp"
#include "saagen/measure/scene.hpp"
#include "saagen/measure/taa.hpp"
#include "saagen/measure/trade_table.hpp"
#include "saagen/reference/quad.hpp"
#include "saagen/reference/saa.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace saagen::measure {

// A measurement that cannot be made (a degenerate ground truth): one line naming the scene.
class TradeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TradeProgress {
  std::string stage;       // e.g. "ground truth sphere", "flicker torus frame 3/32"
  std::uint64_t done = 0;  // work units: ground-truth samples + 1-spp pixel shadings
  std::uint64_t total = 0;
};

// Called on the calling thread, at most about every 100 ms and at each stage change.
using TradeProgressFn = std::function<void(const TradeProgress&)>;

TradeTable compute_trade_table(const TradeConfig& config, const TradeProgressFn& progress = {}, const AnimationFrameFn& frames = {});
// The config with a scene's own sizes (TradeConfig::scene_sizes) in width ... flicker_strata.
TradeConfig sized_for_scene(const TradeConfig& config, SceneId id);
// The ground truth a sized config (sized_for_scene) renders: its main image's settings, or with
// `animation` its animation frames' (flicker_width, flicker_height, flicker_strata).
GroundTruthSettings ground_truth_settings(const TradeConfig& sized, bool animation = false);

// The materials of a configuration in table order: for each alpha, for each Fresnel mode.
std::vector<Material> trade_materials(const TradeConfig& config);

// Ground truth through the disk cache (render_ground_truth when cache_dir is empty or the
// entry is missing or stale). *cache_hit (when given) tells which happened.
GroundTruth cached_ground_truth(const Scene& scene, const GroundTruthSettings& settings, std::span<const Material> materials,
                                const std::string& cache_dir, const SampleProgress& progress = {}, bool* cache_hit = nullptr);

// How a ground-truth cache file is written: (path, bytes), failures ignored (the cache is an
// optimisation). By default a temporary beside the path, renamed over it; a program with an
// output layer passes its own (the CLI's removes the temporary on a signal that ends the
// process). An empty writer restores the default.
using CacheFileWriter = std::function<void(const std::filesystem::path& path, const std::string& bytes)>;
void set_ground_truth_cache_writer(CacheFileWriter writer);

// The cache key text and its file name ("gt-<16 hex digits>.bin").
std::string ground_truth_cache_key(const Scene& scene, const GroundTruthSettings& settings, std::span<const Material> materials);
std::string ground_truth_cache_file(const std::string& key);

// Whether a scene has normal detail beyond its geometry (normal map or bump shading), i.e.
// whether the geometric and the shading normal differ.
bool scene_has_normal_detail(SceneId id);
// Whether that detail comes from a normal map texture (which prefiltering needs).
bool scene_has_normal_map(SceneId id);
// Whether that detail is procedural with closed-form footprint moments (Shape::
// footprint_slope_moments: the bump plane's sum of sines). Such a scene gets the prefiltered rows
// of config.prefiltered_variants with LEAN only (renderer.hpp, Prefilter), if config.prefilters
// lists it: the procedural shader band-limited to its footprint, LEAN's moments in closed form.
bool scene_has_procedural_normals(SceneId id);

// Fixed-width text table and CSV of the rows.
std::string format_trade_table(const TradeTable& table);
std::string trade_table_csv(const TradeTable& table);

}  // namespace saagen::measure

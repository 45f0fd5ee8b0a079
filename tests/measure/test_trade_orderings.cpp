// The quality orderings that Tokuyoshi & Kaplanyan 2019 (T&K19) report, checked on saagen's
// analytic scenes with the ground-truth renderer (measure/src). Every
// assertion prints the figures it compares.
//
// Configuration: 128 x 128 pixels, ground truth with 32 x 32 = 1024 stratified samples per
// pixel (as the paper's references), GGX alpha in {0.01, 0.05, 0.1, 0.3}, no Fresnel, coarse
// derivatives, sigma^2 = 0.25, kappa = 0.18. Why 128 and not 256 pixels: the binary must stay
// well under a minute on 2 cores (the ground truths of the four scenes take ~7 s here). The
// scenes are fixed in world units, so at 128 px every pixel covers twice the surface of the
// 256-px table: aliasing is stronger, and every ordering asserted below was checked to hold at
// both sizes unless its comment says otherwise. Relative ground-truth error at 128 px and 1024
// spp: <= 1 % at alpha >= 0.05, ~10 % at alpha = 0.01 on the tubes and the bump plane (many
// sub-pixel glints); a ground-truth error uncorrelated with the variants' own errors adds about
// the same term to every variant's squared RMSE, so it narrows the gaps rather than reordering.
//
// What holds and what does not (figures at 128 x 128; the report has 256 x 256):
//   * Deferred, T&K19 Sec. 5 / slides "avg best, previous worst": holds on the normal-mapped
//     bump plane and on the thin tubes (high curvature) at every alpha, in linear RMSE per case
//     and in tonemapped RMSE aggregated over the set. It does NOT hold in linear RMSE on the
//     smooth sphere at alpha = 0.05 and 0.1 (nor on the torus at 0.05 and 0.1), where the
//     conservative sum wins: see SmoothSphereFavoursSumInLinearRmse for the analysis.
//   * Forward, T&K19 Sec. 3 / Fig. 1: the projected kernel beats the slope kernel where half
//     vectors are grazing, for the non-axis-aligned and the axis-aligned form.
//   * The slope-space non-axis-aligned form blows up where h_z is small: > 10x the projected
//     form's RMSE over the pixels with h_z < 0.4 (measured: tubes 13x, torus 1200x, sphere
//     5600x; at 256 px 91x, 2400x, 28000x). Over the whole image at alpha = 0.01 the factor is
//     only 1.6x - 2.6x (7.7x on the sphere at 256 px), because the whole-image error at
//     alpha = 0.01 is dominated by the aliased highlight itself (h_z ~ 1), where both forms
//     coincide. The paper's 13124 (Fig. 1a) also contains, per its Sec. 3.1, the precision
//     error of evaluating the filtered BRDF with an inordinately elongated kernel (fp32 on the
//     GPU); this reference evaluates in double, so what remains here is the "rim" of spurious
//     highlights of Fig. 1a, not an overflow.
#include "saagen/measure/render.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

using namespace saagen::measure;
namespace ref = saagen::ref;
using ref::Vec3;

namespace {

constexpr int kSize = 128;
constexpr int kStrata = 32;
const std::vector<double> kAlphas{0.01, 0.05, 0.1, 0.3};

// The trade table of one scene (all alphas and variants, frame 0 only: the orderings are about
// image error; flicker is not asserted here), computed on first use. ctest runs every TEST in
// its own process, so each TEST renders only the scenes it reads (~1.5 - 3 s per scene).
struct Data {
  std::map<SceneId, TradeTable> tables;
  std::map<SceneId, GBuffer> gbuffers;

  const TradeTable& table(SceneId scene) {
    auto it = tables.find(scene);
    if (it != tables.end()) return it->second;
    TradeConfig config;
    config.width = config.height = kSize;
    config.strata = kStrata;
    config.frames = 0;
    config.scenes = {scene};
    config.alphas = kAlphas;
    config.fresnel_modes = {false};
    config.keep_images = true;
    TradeTable t = compute_trade_table(config);
    std::printf("%s", format_trade_table(t).c_str());
    gbuffers.emplace(scene, render_gbuffer(make_scene(scene), kSize, kSize));
    return tables.emplace(scene, std::move(t)).first->second;
  }
  const GBuffer& gbuffer(SceneId scene) {
    table(scene);
    return gbuffers.at(scene);
  }
  const TradeRow& row(SceneId scene, double alpha, Variant v) {
    const TradeRow* r = table(scene).find(v, scene, alpha, false);
    if (!r) throw std::runtime_error("missing row");
    return *r;
  }
  const ImageSet& images(SceneId scene, double alpha) {
    for (const ImageSet& set : table(scene).images)
      if (set.material.alpha == alpha) return set;
    throw std::runtime_error("missing images");
  }
  const Image& image(SceneId scene, double alpha, Variant v) {
    for (const auto& [variant, feed, prefilter, lobe, img] : images(scene, alpha).variants)
      if (variant == v && feed == NormalFeed::shading && prefilter == Prefilter::none && lobe == Lobe::papers) return img;
    throw std::runtime_error("missing image");
  }
  const Image& reference(SceneId scene, double alpha) { return images(scene, alpha).reference; }
};

Data& data() {
  static Data d;
  return d;
}

// RMSE of a variant's image over the hit pixels whose half vector (at the pixel centre) has
// h_z in [lo, hi).
double rmse_where_hz(Data& d, SceneId scene, double alpha, Variant v, double lo, double hi, int* count = nullptr) {
  const GBuffer& g = d.gbuffer(scene);
  const Image& image = d.image(scene, alpha, v);
  const Image& reference = d.reference(scene, alpha);
  double s = 0.0;
  int n = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const PixelFields& f = g.at(x, y);
      if (!f.hit || f.half_ts.z < lo || f.half_ts.z >= hi) continue;
      const double e = static_cast<double>(image.at(x, y)) - reference.at(x, y);
      s += e * e;
      ++n;
    }
  if (count) *count = n;
  return n ? std::sqrt(s / n) : 0.0;
}

std::string fmt_alpha(double alpha) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", alpha);
  return buffer;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Deferred (normal-based isotropic) filtering

// T&K19 Sec. 5: the less conservative Eq. 5 (avg) has less error than Eq. 4 (sum) and than
// Kaplanyan et al. 2016's rectangle (previous); their scenes are dominated by normal-mapped
// and finely curved geometry. The set here: the normal-mapped bump plane and the row of thin
// tubes (normals turn by 180 degrees across a few pixels), all four alphas. Per case in linear
// RMSE (the paper's metric); in tonemapped RMSE aggregated over the set (root mean square of
// the per-case values), because at alpha = 0.01 on the tubes, where every kernel hits the
// kappa clamp, the tonemapped ranking of these near-identical images flips (0.115 vs 0.108).
TEST(Deferred, AvgBeatsSumAndPreviousOnNormalMappedAndThinCurvedSurfaces) {
  Data& d = data();
  double agg_avg = 0.0, agg_sum = 0.0, agg_previous = 0.0;
  int cases = 0;
  for (SceneId scene : {SceneId::bump_plane, SceneId::tubes}) {
    for (double alpha : kAlphas) {
      const TradeRow& avg = d.row(scene, alpha, Variant::deferred_avg);
      const TradeRow& sum = d.row(scene, alpha, Variant::deferred_sum);
      const TradeRow& previous = d.row(scene, alpha, Variant::deferred_previous);
      const std::string where = std::string(scene_name(scene)) + " alpha " + fmt_alpha(alpha);
      EXPECT_LT(avg.rmse_linear, sum.rmse_linear) << where << ": RMSE avg " << avg.rmse_linear << " vs sum " << sum.rmse_linear;
      EXPECT_LT(avg.rmse_linear, previous.rmse_linear)
          << where << ": RMSE avg " << avg.rmse_linear << " vs previous " << previous.rmse_linear;
      agg_avg += avg.rmse_tonemapped * avg.rmse_tonemapped;
      agg_sum += sum.rmse_tonemapped * sum.rmse_tonemapped;
      agg_previous += previous.rmse_tonemapped * previous.rmse_tonemapped;
      ++cases;
    }
  }
  agg_avg = std::sqrt(agg_avg / cases);
  agg_sum = std::sqrt(agg_sum / cases);
  agg_previous = std::sqrt(agg_previous / cases);
  std::printf("tonemapped RMSE over bump_plane + tubes, 4 alphas: avg %.5f sum %.5f previous %.5f\n", agg_avg, agg_sum, agg_previous);
  EXPECT_LT(agg_avg, agg_sum) << "aggregated tonemapped RMSE avg vs sum";
  EXPECT_LT(agg_avg, agg_previous) << "aggregated tonemapped RMSE avg vs previous";

  // The slides' "previous worst": on the normal-mapped plane previous has the largest linear
  // RMSE of the deferred forms at every alpha (the tangent-space max, its tangent-free form,
  // sum, avg and projected-space all do better).
  for (double alpha : kAlphas) {
    const double previous = d.row(SceneId::bump_plane, alpha, Variant::deferred_previous).rmse_linear;
    for (Variant v : {Variant::deferred_max, Variant::deferred_max_tangent_free, Variant::deferred_sum, Variant::deferred_avg,
                      Variant::deferred_projected_space}) {
      const double other = d.row(SceneId::bump_plane, alpha, v).rmse_linear;
      EXPECT_LT(other, previous) << "bump_plane alpha " << alpha << ": " << variant_id(v) << " " << other << " vs previous " << previous;
    }
  }
}

// What is true on the smooth sphere (the ordering avg < sum does NOT hold there in linear
// RMSE at alpha = 0.05 and 0.1; at 256 px also not at 0.01). Analysis:
//  * The linear RMSE of the sphere is the error of a single compact highlight: a few peak
//    pixels dominate it. avg adds tr(Sigma_n) = sigma^2 (|dn_x|^2 + |dn_y|^2) to alpha^2: the
//    exact Beckmann width for an isotropic footprint of the *normal*. sum adds twice that.
//  * The deferred forms assume a distant eye and light (T&K19 Sec. 4.1), so they see only the
//    normal's variation. With the camera at 4 radii, the view vector also turns from pixel to
//    pixel, in the same sense as the half vector's motion in the tangent frame: at the
//    highlight, |d h_proj|^2 / |dn|^2 = 1.31 (measured below; 1.00 with the camera at 40
//    radii). avg therefore underfilters the highlight; sweeping sigma^2 at 256 px, deferred-avg
//    is best at ~1.5 x sigma^2, so sum's 2 x lands closer than avg's 1 x.
//  * With the eye far away (camera at 40 radii, same framing) the view term vanishes, and avg
//    beats sum clearly at alpha = 0.01 (0.33 vs 0.55 at 128 px); at 0.05 they tie.
//  * The tonemapped RMSE, which weighs the many near-highlight pixels rather than the peaks,
//    still ranks avg before sum on the sphere (and on the torus) at every alpha.
TEST(Deferred, SmoothSphereFavoursSumInLinearRmse) {
  Data& d = data();
  // The inversion, with a wide margin at alpha = 0.05 (0.0144 vs 0.0246).
  const TradeRow& avg = d.row(SceneId::sphere, 0.05, Variant::deferred_avg);
  const TradeRow& sum = d.row(SceneId::sphere, 0.05, Variant::deferred_sum);
  EXPECT_LT(sum.rmse_linear, avg.rmse_linear) << "sphere alpha 0.05 linear RMSE: sum " << sum.rmse_linear << " avg " << avg.rmse_linear;
  // Tonemapped: avg first on the curved surfaces at every alpha.
  for (SceneId scene : {SceneId::sphere, SceneId::torus})
    for (double alpha : kAlphas) {
      const double a = d.row(scene, alpha, Variant::deferred_avg).rmse_tonemapped;
      const double s = d.row(scene, alpha, Variant::deferred_sum).rmse_tonemapped;
      const double p = d.row(scene, alpha, Variant::deferred_previous).rmse_tonemapped;
      EXPECT_LT(a, s) << scene_name(scene) << " alpha " << alpha << " tonemapped avg " << a << " sum " << s;
      EXPECT_LT(a, p) << scene_name(scene) << " alpha " << alpha << " tonemapped avg " << a << " previous " << p;
    }

  // The mechanism: half-vector vs normal variation at the highlight (quads with h_z > 0.95).
  auto derivative_ratio = [](const GBuffer& g) {
    double sum_ratio = 0.0;
    int n = 0;
    for (int y = 0; y + 1 < g.height; y += 2)
      for (int x = 0; x + 1 < g.width; x += 2) {
        const PixelFields& a = g.at(x, y);
        const PixelFields& b = g.at(x + 1, y);
        const PixelFields& c = g.at(x, y + 1);
        if (!a.hit || !b.hit || !c.hit || a.half_ts.z < 0.95) continue;
        auto dh = [](Vec3 p, Vec3 q) { return (p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y); };
        auto dn = [](Vec3 p, Vec3 q) { return ref::dot(p - q, p - q); };
        sum_ratio += (dh(b.half_ts, a.half_ts) + dh(c.half_ts, a.half_ts)) / (dn(b.normal, a.normal) + dn(c.normal, a.normal));
        ++n;
      }
    return sum_ratio / n;
  };
  const Scene near = make_scene(SceneId::sphere);
  // Same sphere and light, camera at 40 radii with the field of view narrowed to keep the
  // framing (tan(fov/2) scaled by 4/40).
  const double fov = 2.0 * std::atan(std::tan(17.0 * ref::kPi / 180.0) * 0.1) * 180.0 / ref::kPi;
  const Scene far("sphere_far", std::make_shared<Sphere>(1.0), Rigid{}, Camera{{0.0, 0.0, 40.0}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, fov},
                  near.light(), {0.0, 0.0, -1.0}, 0.0);
  const GBuffer far_gbuffer = render_gbuffer(far, kSize, kSize);
  const double ratio_near = derivative_ratio(d.gbuffer(SceneId::sphere));
  const double ratio_far = derivative_ratio(far_gbuffer);
  std::printf("|dh_proj|^2 / |dn|^2 at the highlight: camera at 4 radii %.3f, at 40 radii %.3f\n", ratio_near, ratio_far);
  EXPECT_GT(ratio_near, 1.2);
  EXPECT_NEAR(ratio_far, 1.0, 0.05);

  // Far eye: avg beats sum at alpha = 0.01.
  const std::vector<Material> materials{{0.01, false}, {0.05, false}};
  GroundTruthSettings settings;
  settings.width = settings.height = kSize;
  settings.strata = kStrata;
  const GroundTruth gt = render_ground_truth(far, settings, materials);
  for (std::size_t m = 0; m < materials.size(); ++m) {
    const double a = compare_images(render_variant(far_gbuffer, Variant::deferred_avg, materials[m]), gt.images[m]).rmse_linear;
    const double s = compare_images(render_variant(far_gbuffer, Variant::deferred_sum, materials[m]), gt.images[m]).rmse_linear;
    std::printf("far sphere alpha %.2f: linear RMSE avg %.4g sum %.4g\n", materials[m].alpha, a, s);
    if (m == 0) {
      EXPECT_LT(a, s) << "far sphere alpha 0.01: avg " << a << " sum " << s;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Forward filtering: slope-space vs projected derivatives (T&K19 Sec. 3)

// The slope-space non-axis-aligned kernel blows up where h_z is small (T&K19 Sec. 3.1: the
// Jacobian of the slope projection has determinant 1/h_z^3, and the unclamped matrix kernel
// turns the derivative error into huge elongated roughness matrices, i.e. spurious rims). Over
// the pixels with h_z < 0.4 at alpha = 0.01 its RMSE exceeds the projected form's by > 10x.
// Over the whole image the factor is smaller at alpha = 0.01 (the shared highlight error
// dominates) and large at alpha >= 0.05 on the sphere.
namespace {
void slope_space_blow_up(Data& d) {
  for (SceneId scene : {SceneId::sphere, SceneId::torus, SceneId::tubes}) {
    int n = 0;
    const double e_slope = rmse_where_hz(d, scene, 0.01, Variant::forward_aniso_slope, 0.0, 0.4, &n);
    const double e_projected = rmse_where_hz(d, scene, 0.01, Variant::forward_aniso_projected, 0.0, 0.4);
    const double whole =
        d.row(scene, 0.01, Variant::forward_aniso_slope).rmse_linear / d.row(scene, 0.01, Variant::forward_aniso_projected).rmse_linear;
    std::printf(
        "%-7s alpha 0.01, h_z < 0.4 (%4d px): aniso slope %.4g, projected %.4g, "
        "ratio %.1f; whole image ratio %.2f\n",
        std::string(scene_name(scene)).c_str(), n, e_slope, e_projected, e_slope / e_projected, whole);
    EXPECT_GT(n, 300) << scene_name(scene);
    EXPECT_GT(e_slope, 10.0 * e_projected) << scene_name(scene) << " h_z < 0.4: slope " << e_slope << " projected " << e_projected;
    EXPECT_GT(whole, 1.3) << scene_name(scene) << " whole-image ratio at alpha 0.01";
  }
  for (double alpha : {0.05, 0.1, 0.3}) {
    const double ratio = d.row(SceneId::sphere, alpha, Variant::forward_aniso_slope).rmse_linear /
                         d.row(SceneId::sphere, alpha, Variant::forward_aniso_projected).rmse_linear;
    std::printf("sphere alpha %.2f whole image: aniso slope / projected RMSE %.1f\n", alpha, ratio);
    EXPECT_GT(ratio, 10.0) << "sphere alpha " << alpha;
  }
}
}  // namespace

// At alpha = 0.01, over the pixels whose half vector is grazing (h_z < 0.6: the sphere's and
// the torus's rims, the tubes' top and bottom edges), the projected kernel has less error than
// the slope kernel, for the non-axis-aligned and the axis-aligned form (Fig. 1a vs 1b, 1c vs
// 1d). Over the whole image the axis-aligned forms differ by only 0.3 % - 4.5 % in linear RMSE
// (the paper: 0.3016 vs 0.3000) since the highlight, where h_z ~ 1 and the forms coincide,
// dominates; the whole-image tonemapped RMSE separates them clearly and is asserted too.
// One TEST with slope_space_blow_up (above) so that the three scenes are rendered once.
TEST(Forward, ProjectedBeatsSlopeAtGrazingAndSlopeSpaceBlowsUpAtSmallHz) {
  Data& d = data();
  const double alpha = 0.01;
  for (SceneId scene : {SceneId::sphere, SceneId::torus, SceneId::tubes}) {
    for (auto [slope, projected] : {std::pair{Variant::forward_aniso_slope, Variant::forward_aniso_projected},
                                    std::pair{Variant::forward_axis_slope, Variant::forward_axis_projected}}) {
      int n = 0;
      const double e_slope = rmse_where_hz(d, scene, alpha, slope, 0.0, 0.6, &n);
      const double e_projected = rmse_where_hz(d, scene, alpha, projected, 0.0, 0.6);
      std::printf(
          "%-7s %-24s vs %-24s h_z < 0.6 (%5d px): %.4g vs %.4g; whole image "
          "linear %.4g vs %.4g, tonemapped %.4g vs %.4g\n",
          std::string(scene_name(scene)).c_str(), std::string(variant_id(slope)).c_str(), std::string(variant_id(projected)).c_str(), n,
          e_slope, e_projected, d.row(scene, alpha, slope).rmse_linear, d.row(scene, alpha, projected).rmse_linear,
          d.row(scene, alpha, slope).rmse_tonemapped, d.row(scene, alpha, projected).rmse_tonemapped);
      EXPECT_GT(n, 200) << scene_name(scene);
      EXPECT_LT(e_projected, e_slope) << scene_name(scene) << " h_z < 0.6: " << variant_id(projected) << " " << e_projected << " vs "
                                      << variant_id(slope) << " " << e_slope;
      EXPECT_LT(d.row(scene, alpha, projected).rmse_tonemapped, d.row(scene, alpha, slope).rmse_tonemapped)
          << scene_name(scene) << " whole image, tonemapped";
    }
    // Non-axis-aligned: also over the whole image in linear RMSE.
    EXPECT_LT(d.row(scene, alpha, Variant::forward_aniso_projected).rmse_linear,
              d.row(scene, alpha, Variant::forward_aniso_slope).rmse_linear)
        << scene_name(scene) << " whole image, linear";
  }

  // The same scenes: the slope-space blow-up where h_z is small (above).
  slope_space_blow_up(d);
}

// What the trade measures on real content (normal-mapped spheres with MIP-mapped normal maps, a
// torus-knot mesh) and against the engines' shipped forms, in display-referred metrics (LDR-FLIP
// of the tonemapped images, tonemapped RMSE). Each test pins an ordering that holds, or an
// inversion that is real, with the figures in its messages.
//
// Size: 128 x 128 pixels (the `medium` preset's view), 16 x 16 = 256 stratified samples per pixel,
// no flicker animation (frames = 0): each scene's ground truth takes a few seconds on 2 cores.
// The orderings asserted were checked at this size and in `saagen bench --preset medium`; margins
// are stated per test. The ground truth's own error at 256 spp is below 3 % of its RMS at alpha >= 0.05
// (test_ground_truth's convergence figures), far below the gaps asserted.
#include "saagen/measure/render.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

using namespace saagen::measure;

namespace {

constexpr int kSize = 128;
constexpr int kStrata = 16;

struct Key {
  SceneId scene;
  double alpha;
  double sigma2;
  bool operator<(const Key& o) const { return std::tie(scene, alpha, sigma2) < std::tie(o.scene, o.alpha, o.sigma2); }
};

const TradeTable& table(SceneId scene, double alpha, double sigma2 = 0.25) {
  static std::map<Key, TradeTable> tables;
  const Key key{scene, alpha, sigma2};
  if (auto it = tables.find(key); it != tables.end()) return it->second;
  TradeConfig config;
  config.width = config.height = kSize;
  config.strata = kStrata;
  config.frames = 0;
  config.scenes = {scene};
  config.alphas = {alpha};
  config.fresnel_modes = {false};
  config.params.sigma2 = sigma2;
  TradeTable t = compute_trade_table(config);
  std::printf("%s", format_trade_table(t).c_str());
  return tables.emplace(key, std::move(t)).first->second;
}

const TradeRow& row(const TradeTable& t, Variant v, NormalFeed feed = NormalFeed::shading, Prefilter prefilter = Prefilter::none) {
  for (const TradeRow& r : t.rows)
    if (r.variant == v && r.feed == feed && r.prefilter == prefilter) return r;
  throw std::runtime_error("missing row " + configuration_id(v, feed, prefilter));
}

}  // namespace

double ratio(double a, double b) { return a / b; }

// The 4-px normal map (2 px at this size), alpha 0.05: filtering the normal-mapped normal's
// derivatives lowers both tonemapped RMSE and LDR-FLIP against no SAA (measured 0.0375 vs 0.0464
// and 0.0427 vs 0.0491; asserted: >= 10 % and >= 5 % lower).
TEST(RealContent, FilteringTheMappedNormalBeatsNoSaaOnVisibleNormalMapDetail) {
  const TradeTable& t = table(SceneId::nmap_sphere, 0.05);
  const TradeRow& none = row(t, Variant::none);
  const TradeRow& avg = row(t, Variant::deferred_avg);
  EXPECT_LT(avg.rmse_tonemapped, 0.90 * none.rmse_tonemapped) << avg.rmse_tonemapped << " vs " << none.rmse_tonemapped;
  EXPECT_LT(avg.flip_ldr, 0.95 * none.flip_ldr) << avg.flip_ldr << " vs " << none.flip_ldr;
}

// The same case fed the geometric normal (what HDRP, Filament, Unreal and three.js feed): the
// filter sees only the sphere's curvature and leaves the map's aliasing alone: within 3 % of no
// SAA in tonemapped RMSE (measured 0.0457 vs 0.0464), and >= 15 % above the shading feed.
TEST(RealContent, TheGeometricNormalMissesTheNormalMapsDetail) {
  const TradeTable& t = table(SceneId::nmap_sphere, 0.05);
  const double none = row(t, Variant::none).rmse_tonemapped;
  const double geometric = row(t, Variant::deferred_avg, NormalFeed::geometric).rmse_tonemapped;
  const double shading = row(t, Variant::deferred_avg).rmse_tonemapped;
  EXPECT_NEAR(ratio(geometric, none), 1.0, 0.03) << geometric << " vs " << none;
  EXPECT_GT(geometric, 1.15 * shading) << geometric << " vs " << shading;
}

// An inversion that is real. Toksvig (and LEAN) prefiltering of the sub-pixel map turns the
// normals' spread into GGX roughness: tonemapped RMSE drops by ~45 % (0.0256 vs 0.0465), but the
// variance-matched GGX lobe has long tails that the map's bounded normal distribution (tilts
// <= 20 degrees) does not, so the whole sphere gets a haze the ground truth lacks, which FLIP
// (sensitive to light on dark) scores ~3x worse (0.168 vs 0.055). Asserted: RMSE < 0.7x and
// LDR-FLIP > 2x no SAA's, for both prefilters.
TEST(RealContent, PrefilteringHalvesTonemappedRmseButHazeTriplesFlip) {
  const TradeTable& t = table(SceneId::nmap_sphere_fine, 0.05);
  const TradeRow& none = row(t, Variant::none);
  for (Prefilter p : {Prefilter::toksvig, Prefilter::lean}) {
    const TradeRow& pre = row(t, Variant::none, NormalFeed::shading, p);
    EXPECT_LT(pre.rmse_tonemapped, 0.7 * none.rmse_tonemapped) << prefilter_name(p) << " " << pre.rmse_tonemapped;
    EXPECT_GT(pre.flip_ldr, 2.0 * none.flip_ldr) << prefilter_name(p) << " " << pre.flip_ldr << " vs " << none.flip_ldr;
  }
}

// The engines' bakes on the same map (docs/PREFILTER.md): Unreal's composite texture and
// Filament's vMF fit add about Toksvig's 2 (1 - L), HDRP a quarter of it, and with the papers'
// GGX the quarter is the least hazy: measured LDR-FLIP 0.0825 (HDRP) vs 0.1658 (Unreal), 0.1670
// (Filament), 0.1682 (Toksvig), none 0.0548; tonemapped RMSE 0.0243-0.0256 vs none's 0.0465.
// Asserted: HDRP < 0.6x every other bake's LDR-FLIP, every bake still > 1.2x no SAA's, and every
// bake's tonemapped RMSE < 0.7x no SAA's.
TEST(RealContent, TheEnginesBakesHdrpsQuarterIsTheLeastHazy) {
  const TradeTable& t = table(SceneId::nmap_sphere_fine, 0.05);
  const TradeRow& none = row(t, Variant::none);
  const TradeRow& hdrp = row(t, Variant::none, NormalFeed::shading, Prefilter::hdrp);
  for (Prefilter p : {Prefilter::toksvig, Prefilter::unreal, Prefilter::filament_vmf, Prefilter::hdrp}) {
    const TradeRow& bake = row(t, Variant::none, NormalFeed::shading, p);
    if (p != Prefilter::hdrp) {
      EXPECT_LT(hdrp.flip_ldr, 0.6 * bake.flip_ldr) << prefilter_name(p) << " " << bake.flip_ldr;
    }
    EXPECT_GT(bake.flip_ldr, 1.2 * none.flip_ldr) << prefilter_name(p) << " " << bake.flip_ldr << " vs " << none.flip_ldr;
    EXPECT_LT(bake.rmse_tonemapped, 0.7 * none.rmse_tonemapped) << prefilter_name(p) << " " << bake.rmse_tonemapped;
  }
}

// Another real inversion, and what the tail-preserving lobe changes about it: on the smooth
// torus-knot mesh at alpha 0.05 every engine form and every filter shaded with the papers' or the
// mapped lobe raises LDR-FLIP above no SAA's (0.0177; forward-aniso-projected 0.0451, Godot 0.0420,
// deferred-avg 0.0871): the 1-spp highlight of a smooth mesh hardly aliases at this roughness, and
// GGX(alpha^2 + K)'s tails are visible haze. The tail-preserving lobe with the anisotropic kernels,
// whose footprint follows the knot's curvature, goes below it (forward-aniso-projected/tail 0.0115,
// deferred-aniso/tail 0.0110 with the shipped lobe, docs/FILTERED_GGX.md); with the isotropic or
// axis-aligned kernels it stays above.
TEST(RealContent, OnASmoothMeshOnlyTheTailLobeWithAnAnisotropicKernelBeatsNoSaaInFlip) {
  const TradeTable& t = table(SceneId::torus_knot, 0.05);
  const double none = row(t, Variant::none).flip_ldr;
  for (const TradeRow& r : t.rows) {
    if (r.variant == Variant::none) continue;
    const bool anisotropic_kernel = r.variant == Variant::forward_aniso_projected || r.variant == Variant::deferred_aniso;
    if (r.lobe == Lobe::tail && anisotropic_kernel)
      EXPECT_LT(r.flip_ldr, none) << configuration_id(r);
    else
      EXPECT_GT(r.flip_ldr, none) << configuration_id(r);
  }
}

// Better than the paper for GGX: the kernel's sigma^2 = 0.25 is Beckmann's variance match (T&K
// 2019 Sec. 2.2; their Sec. 6 names GGX's mismatch). A quarter of it (sigma^2 = 0.0625) halves
// LDR-FLIP on the knot (forward-aniso-projected 0.0222 vs 0.0451, deferred-avg 0.0414 vs 0.0871)
// and lowers the 4-px normal map's too (deferred-avg 0.0416 vs 0.0427). Asserted: < 0.7x on the
// knot, no higher on the normal map.
TEST(RealContent, AQuarterOfTheKernelLowersFlipForGgx) {
  for (Variant v : {Variant::forward_aniso_projected, Variant::deferred_avg}) {
    const double paper = row(table(SceneId::torus_knot, 0.05), v).flip_ldr;
    const double quarter = row(table(SceneId::torus_knot, 0.05, 0.0625), v).flip_ldr;
    EXPECT_LT(quarter, 0.7 * paper) << variant_id(v) << " " << quarter << " vs " << paper;
  }
  const double paper = row(table(SceneId::nmap_sphere, 0.05), Variant::deferred_avg).flip_ldr;
  const double quarter = row(table(SceneId::nmap_sphere, 0.05, 0.0625), Variant::deferred_avg).flip_ldr;
  EXPECT_LE(quarter, paper) << quarter << " vs " << paper;
}

// The renderer's engine rows are the engines' forms: HDRP and Filament are deferred-sum with
// their constants on the geometric normal (REFERENCES.md), pixel for pixel up to the few ulps
// of alpha^2 (test_engines) carried through the BRDF: relative 1e-12.
TEST(RealContent, HdrpAndFilamentRowsAreDeferredSumOnTheGeometricNormal) {
  const GBuffer g = render_gbuffer(make_scene(SceneId::nmap_sphere), 64, 64);
  const Material m{0.05, false};
  const std::pair<Variant, saagen::ref::Params> cases[] = {{Variant::engine_hdrp, {0.1, 0.04}}, {Variant::engine_filament, {0.15, 0.04}}};
  for (const auto& [engine, params] : cases) {
    const Image e = render_variant(g, engine, m);
    const Image d = render_variant(g, Variant::deferred_sum, m, params, saagen::ref::Derivative::coarse, 0, NormalFeed::geometric);
    for (std::size_t i = 0; i < e.size(); ++i)
      ASSERT_NEAR(e.pixels[i], d.pixels[i], 1e-12 * std::max(1.0f, std::fabs(d.pixels[i]))) << variant_id(engine) << " " << i;
  }
}

// Without normal detail the two feeds are the same normal: identical images.
TEST(RealContent, FeedsAgreeWhereTheGeometryIsTheNormal) {
  const GBuffer g = render_gbuffer(make_scene(SceneId::torus_knot), 64, 64);
  const Material m{0.05, false};
  for (Variant v : {Variant::deferred_avg, Variant::forward_aniso_projected, Variant::deferred_previous})
    EXPECT_EQ(render_variant(g, v, m).pixels, render_variant(g, v, m, {}, saagen::ref::Derivative::coarse, 0, NormalFeed::geometric).pixels)
        << variant_id(v);
}

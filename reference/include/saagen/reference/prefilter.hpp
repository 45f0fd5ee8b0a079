// saagen reference: normal-map prefiltering (templates/40-prefilter.saa), in double precision.
//
// The texture-space half of SAA (Kaplanyan et al. 2016 Sec. 4): the spread of a normal map's
// normals inside one MIP texel becomes roughness. Two measures of that spread, both stored per
// texel by measure::NormalMap (normal_map.hpp):
//   - Toksvig 2005: the length L = |mean normal| of the unnormalised mean of the unit normals.
//     |N_a| = 1 / (1 + sigma^2) gives the per-axis slope variance sigma^2 = (1 - L) / L.
//   - LEAN mapping (Olano & Baker 2010): the slope moments E[s], E[s s^T]; the covariance is
//     Sigma_tex = E[s s^T] - E[s] E[s]^T.
// Slope variance adds to the alpha^2 domain with a factor 2 (Beckmann's slope distribution has
// per-axis variance alpha^2 / 2; T&K 2019 Sec. 2.2: A = diag(alpha^2) + 2 Sigma). The texture
// term is never clamped; kappa clamps only the screen-space kernel.
//
// Names and argument orders are the template functions'; Params supplies SIGMA2, KAPPA, the guard
// constants and the guarded/paper form, as in saa.hpp.
#pragma once

#include "saagen/reference/math.hpp"
#include "saagen/reference/saa.hpp"

namespace saagen::ref {

// Toksvig 2005: sigma^2 = max((1 - L) / L, 0); guarded: L = max(L, TINY_POSITIVE).
double toksvig_variance(const Params& p, double mean_length);

// Olano & Baker 2010: Sigma = E[s s^T] - E[s] E[s]^T. Guarded: E[s] clamped to +-SLOPE_MAX,
// E[s s^T] to [0, SLOPE_MAX^2] (diagonal) and +-SLOPE_MAX^2 (off-diagonal), and the result
// clamped to PSD (sym2_clamp_psd).
Sym2 lean_covariance(const Params& p, Vec2 slope_mean, Sym2 slope_second);

// Diagonal clamped to >= 0, off-diagonal to +-sqrt(m00) sqrt(m11).
Sym2 sym2_clamp_psd(Sym2 m);

// T&K 2021: a = saturate(alpha2), a' = (a + k(1 - a)) / (1 + k(1 - a)) (= p'/(1+p'), p' = p + k).
double projected_space_add(double alpha2, double k);

// saturate(alpha^2 + 2 sigma^2_Toksvig).
double prefilter_toksvig(const Params& p, double alpha2, double mean_length);
// saturate(alpha^2 + 2 sigma^2_Toksvig + min(2 sigma_px^2 (|dn_dx|^2 + |dn_dy|^2), kappa)).
double prefilter_toksvig_sum(const Params& p, double alpha2, double mean_length, Vec3 dn_dx, Vec3 dn_dy);
// projected_space_add(alpha^2, 2 sigma^2_Toksvig + min(kernel, kappa)).
double prefilter_toksvig_projected(const Params& p, double alpha2, double mean_length, Vec3 dn_dx, Vec3 dn_dy);

// The engines' offline normal-map-to-roughness bakes, from the same mean-normal length L (the
// box mean of the level-0 unit normals under a MIP texel). Each returns the baked alpha'^2 from
// the base alpha^2; a flat texel (L >= 1) returns alpha^2 unchanged (saturated).
//
// vMF concentration fitted to L (Banerjee et al. 2005, as in Han et al. 2007 and Neubelt &
// Pettineo 2013): kappa = (3L - L^3) / (1 - L^2); +infinity for L >= 1.
double vmf_kappa(double mean_length);
// Unreal's composite texture (TextureCompressorModule ApplyCompositeTexture, CTM_NormalRoughnessTo*):
// Toksvig's variance V = max((1 - L) / L - 4e-5, 0) times CompositePower (`power`, default 1), then
// B = 2 V (a - 1), a' = (B - a) / (B - 1) with a = alpha^2; that is a' = (a + 2V(1 - a)) /
// (1 + 2V(1 - a)), T&K 2021's projected-space addition of 2V (projected_space_add).
double unreal_composite_alpha2(double alpha2, double mean_length, double power = 1.0);
// Filament's tools/roughness-prefilter (solveVMF, citing Karis 2018 "Normal map filtering using
// vMF (part 3)"): alpha' = sqrt(alpha^2 + 2 / kappa), i.e. alpha'^2 = alpha^2 + 2 / kappa,
// saturated here (the tool writes the value unclamped).
double filament_vmf_alpha2(double alpha2, double mean_length);
// Unity HDRP (core CommonMaterial.hlsl TextureNormalVariance + NormalFiltering; the editor's
// NormalMapFilteringTexturePostprocessor): variance = min(1 / (4 kappa), 0.03125) (the
// postprocessor stores it in the normal map capped at NORMALMAP_HIGHEST_VARIANCE 0.03125), then
// alpha'^2 = saturate(alpha^2 + min(2 variance, threshold^2)): alpha^2 + min(1 / (2 kappa), 0.0625)
// at the postprocessor's largest threshold 0.25 (threshold 0.25: 2 x 0.03125 = 0.25^2; a
// material's smaller specular-AA threshold caps it lower at run time).
double hdrp_texture_alpha2(double alpha2, double mean_length, double threshold = 0.25);

// A = diag(ax^2, ay^2) + 2 Sigma_tex (not clamped).
Sym2 prefilter_lean(const Params& p, Vec2 alpha2, Vec2 slope_mean, Sym2 slope_second);
// A = diag(ax^2, ay^2) + 2 (Sigma_screen + Sigma_tex), Sigma_screen = sigma^2 Delta^T Delta of
// the slope derivatives (filter_roughness_matrix; not clamped).
Sym2 prefilter_lean_aniso_slope(const Params& p, Vec2 alpha2, Vec2 slope_mean, Sym2 slope_second, Vec2 dslope_dx, Vec2 dslope_dy);
// saturate(alpha^2 + tr(Sigma_tex) + min(2 sigma_px^2 (|dn_dx|^2 + |dn_dy|^2), kappa)).
double prefilter_lean_sum(const Params& p, double alpha2, Vec2 slope_mean, Sym2 slope_second, Vec3 dn_dx, Vec3 dn_dy);
// projected_space_add(alpha^2, tr(Sigma_tex) + min(kernel, kappa)).
double prefilter_lean_projected(const Params& p, double alpha2, Vec2 slope_mean, Sym2 slope_second, Vec3 dn_dx, Vec3 dn_dy);

}  // namespace saagen::ref

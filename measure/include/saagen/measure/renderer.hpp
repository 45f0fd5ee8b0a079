// saagen ground-truth renderer: the converged image and the 1-spp image of every SAA variant.
//
// Shading (both images): the specular term only,
//   L = F(i.h) f(i, o) (n.i) E,
// f the GGX microfacet BRDF without Fresnel (ref::ggx_brdf_axis, or ref::ggx_brdf_matrix for
// the forward non-axis-aligned variants), i the unit direction to the light, o to the camera,
// both in the hit's tangent frame (t, b, n), E the light's irradiance at normal incidence, and
// F = 1 (no Fresnel) or Schlick's F0 + (1 - F0)(1 - i.h)^5 with F0 = 0.04 and h = normalize(i
// + o). No shadows or inter-reflections: SAA addresses the specular term of one light, and
// occlusion edges would only add geometric aliasing common to every variant. Rays that miss
// the shape see a black background (radiance 0).
//
// Ground truth (render_ground_truth): per pixel, strata x strata (default 32 x 32 = 1024)
// jittered samples distributed by the truncated Gaussian pixel filter of sampling.hpp
// (variance sigma^2 = 0.25 px^2, the sigma^2 the SAA kernel assumes), shaded with the
// unfiltered BRDF of roughness alpha; the pixel value is their mean. One set of rays serves
// every material of a call (the geometry does not depend on alpha or Fresnel).
//
// KHR_materials_anisotropy (anisotropy.hpp): on an anisotropic surface both images shade in the
// frame turned to the anisotropy direction with (alpha_t^2, alpha_b^2) = anisotropic_alpha2; the
// forward forms take that pair as their unfiltered roughness (the matrix forms add their kernel
// to diag(alpha_t^2, alpha_b^2)), the isotropic deferred forms are applied once per axis (as the
// planner emits them on anisotropic roughness), deferred-aniso adds its kernel to the matrix,
// none shades the pair, and an engine's filtered alpha' becomes (mix(alpha', 1, s^2), alpha') as
// three.js's MeshPhysicalMaterial does. A normal map's LEAN covariance is carried into the turned
// frame (to_anisotropy_frame); the engines' isotropic bakes are taken on the base alpha.
//
// 1-spp variant images (render_gbuffer, then shade_pixel / render_variant): the shape is
// sampled once at every pixel centre; the per-pixel fields (world normal, tangent, bitangent,
// tangent-space light/view/half vectors, gl_FragCoord) of the 2x2 quad containing a pixel are
// handed to the reference *_fragment_quad function of the variant (saa.hpp), which takes
// ddx/ddy as a GPU does (Derivative::coarse by default; lavapipe's plain ddx is fine). The
// filtered roughness then feeds the BRDF at the pixel's own centre:
//   forward-aniso-*  -> matrix A -> ggx_brdf_matrix(i, o, A, ndf_clamp_tau(alpha^2))
//   forward-axis-*   -> (ax'^2, ay'^2) -> ggx_brdf_axis
//   deferred-*       -> alpha'^2 -> ggx_brdf_axis(i, o, (alpha'^2, alpha'^2))
//   none             -> ggx_brdf_axis with the unfiltered alpha^2 (no SAA).
//
// Quad partners off the surface: on a GPU the pixels of a quad that a triangle does not cover
// run as helper invocations that evaluate the same triangle's attributes, extrapolated. The
// analytic stand-in used here: a partner whose centre misses the shape, hits another connected
// surface (another tube), or lies outside the image takes the shaded pixel's own fields
// (normal, frame, vectors), i.e. a zero difference across that edge; only its gl_FragCoord
// stays its own (the rasteriser's value, which Listing 3's neighbour direction reads).
//
// Triangle meshes (the asset scenes, gltf.hpp, and the torus knot; Scene::per_triangle_quads)
// follow the GPU's rule exactly instead: a quad partner that is not on the shaded pixel's own
// triangle (another triangle of the mesh, across a uv seam or a split normal, where the tube
// passes in front of itself, another primitive, or nothing) takes what a helper invocation of
// that triangle computes, the triangle's attributes extrapolated to the partner's ray
// (Scene::extrapolate_surface; GBuffer::helpers), its uv included (tangent_plane_uv, the same
// plane); only partners on the same triangle take their own fields. (The analytic rule above
// took the far sheet's normal at the knot's occlusion edges: a kernel as wide as the angle between
// two tubes, bright speckles no GPU draws.)
//
// Normal-mapped scenes (Scene::normal_map). Ground truth: every sample's shading normal is the
// map's level-0 bilinear sample at its hit (Scene::intersect), so the 1024 samples integrate the
// full-resolution map over the pixel filter. 1-spp fields, as a GPU samples a texture: uv at the
// pixel centre; the derivatives of uv per 2x2 quad with coarse differences (ddx = uv of quad
// pixel 1 - pixel 0, ddy = pixel 2 - pixel 0, the same for the four pixels); the implicit LOD
// NormalMap::lod(ddx, ddy); the trilinear sample at (uv, LOD); its .normal renormalised and
// taken through the geometric TBN (Scene::apply_normal_map). A quad partner that misses the
// surface, hits another connected surface or lies outside the image takes the uv a helper
// invocation would interpolate: its ray intersected with the shaded pixel's tangent plane
// (the plane spanned by dpdu and dpdv through the hit) and mapped through dpdu, dpdv
// (tangent_plane_uv). A partner on the same surface takes its own uv (no unwrapping across a
// uv seam: the seams of the scenes are out of view).
#pragma once

#include "saagen/measure/image.hpp"
#include "saagen/measure/normal_map.hpp"
#include "saagen/measure/sampling.hpp"
#include "saagen/measure/scene.hpp"
#include "saagen/reference/math.hpp"
#include "saagen/reference/quad.hpp"
#include "saagen/reference/saa.hpp"
#include "saagen/template_variants.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace saagen::measure {

inline constexpr double kFresnelF0 = 0.04;

// Schlick's approximation F0 + (1 - F0)(1 - cos)^5 (cos clamped to [0, 1]).
double schlick_fresnel(double cos_theta, double f0 = kFresnelF0);

// Isotropic GGX roughness alpha (the BRDF reads alpha^2) and the Fresnel switch.
struct Material {
  double alpha = 0.1;
  bool fresnel = false;
};

// The variants, named as in the catalogue (docs/GUIDE.md "Variants"): the no-SAA baseline, the
// templates' SAA filters (one enumerator each, deferred_avg for deferred-avg, written from the
// templates' list, saagen/template_variants.hpp, in the templates' order), then the forms only the
// trade measures. Each enumerator has one row in renderer.cpp's kVariantRows (its id and its CPU
// reference); all_variants() follows the templates (docs/ARCHITECTURE.md, "The registry of variants").
enum class Variant {
  none,
#define SAAGEN_VARIANT_ENUMERATOR(identifier, id) identifier,
  SAAGEN_SAA_FILTERS(SAAGEN_VARIANT_ENUMERATOR)
#undef SAAGEN_VARIANT_ENUMERATOR
  // deferred-max's tangent-free function, measured as a row of its own.
  deferred_max_tangent_free,
  // The forms engines ship (shared/REFERENCES.md; engines.hpp): reference-renderer rows of the
  // trade only, never emitted. Each reads the normal its engine feeds it (engine_feed()).
  engine_hdrp,
  engine_filament,
  engine_godot,
  engine_unreal,
  engine_threejs,
  engine_babylon,
};

// "none", "forward-aniso-slope", ..., "deferred-max-tangent-free", ..., "engine-hdrp", ...
std::string_view variant_id(Variant v);
std::optional<Variant> variant_from_id(std::string_view id);
// saagen's variants and the no-SAA baseline (catalogue ids, plus the tangent-free form): none,
// then the templates' SAA filters in the templates' order, each followed by its measurement-only forms.
std::span<const Variant> all_variants();
// The engines' shipped forms.
std::span<const Variant> all_engines();
bool is_engine(Variant v);

// Which normal feeds a filter. Engines disagree: HDRP, Filament, Unreal and three.js filter the
// geometric (interpolated vertex) normal and leave normal-map detail to texture prefiltering;
// Godot and Babylon.js filter the shading normal after normal mapping.
//   shading    the normal-mapped normal (deferred variants) and the half vector in the frame
//              built on it (forward variants);
//   geometric  the base surface's normal and frame before the normal map (curvature only).
// On surfaces without normal detail the two are the same.
enum class NormalFeed { shading, geometric };
std::string_view feed_name(NormalFeed feed);  // "shading", "geometric"
// The normal an engine's shipped form reads.
NormalFeed engine_feed(Variant engine);

// Normal-map prefiltering, the texture-space half of SAA (Kaplanyan et al. 2016 Sec. 4;
// reference/prefilter.hpp): the spread of the map's normals under the pixel's trilinear MIP
// footprint (PixelFields::texel) becomes roughness added to the filtered roughness, in the
// variant's domain, never clamped by kappa. On procedural normal detail (the bump plane;
// PixelFields::has_footprint_moments) only `lean` applies: the footprint's slope moments are
// closed-form, and the row shades the band-limited normal; the other forms read the length of a
// mean unit normal, which a sum of sines has no closed form for (shade_pixel throws).
//   toksvig  2 sigma^2, sigma^2 = (1 - L) / L from the length L of the filtered mean normal
//            (Toksvig 2005; the map stores unnormalised mean normals, as Toksvig proposes);
//   lean     2 Sigma_tex from the filtered slope moments (Olano & Baker 2010): the full
//            covariance for the matrix forms, its diagonal for the axis-aligned forms, its
//            trace for the isotropic ones.
//   unreal, filament_vmf, hdrp
//            the engines' offline bakes of the same L (reference/prefilter.hpp: Unreal's
//            composite texture, Filament's roughness-prefilter, HDRP's normal-map filtering), as
//            the baked roughness minus the pixel's base alpha^2 (isotropic), so that the SAA
//            filter then widens the baked roughness as an engine's shader would.
// Only pixels of a normal-mapped surface have a texture term (0 elsewhere). prefilter_scale
// multiplies the texture term (1: the formulas as published; the trade measures others).
enum class Prefilter { none, toksvig, lean, unreal, filament_vmf, hdrp };
// "none", "toksvig", "lean", "unreal", "filament-vmf", "hdrp"
std::string_view prefilter_name(Prefilter prefilter);

// The lobe a filtered roughness is evaluated with (brdf.hpp, docs/FILTERED_GGX.md):
//   papers   GGX of the filtered roughness (alpha^2 + kernel), as the papers do;
//   tail     the tail-preserving filtered GGX: a GGX lobe of the unfiltered roughness's shape
//            plus a Beckmann core carrying the kernel (ggx_brdf_filtered_matrix / _axis);
//   mapped   one GGX lobe of alpha'^2 = ggx_filtered_alpha2(alpha^2, kernel), the roughness an
//            engine that keeps its own BRDF would feed (for a matrix: the kernel scaled by
//            ggx_kernel_scale of the mean alpha^2 and the mean kernel).
//   exact    the exact filtered GGX of the same kernel (ggx_brdf_filtered_exact: GGX convolved
//            with the kernel's Gaussian by quadrature): what a closed form could reach, a
//            measuring instrument that no target emits (TradeConfig::lobes leaves it out).
// Ignored by `none` and the engines' forms, which evaluate their own roughness with GGX.
enum class Lobe { papers, tail, mapped, exact };
std::string_view lobe_name(Lobe lobe);  // "papers", "tail", "mapped", "exact"

// The specular radiance of one light at a surface point, in the tangent frame.
// brdf: f(i, o) without Fresnel. Returns F f (n.i) E (0 when i.z <= 0).
double specular_radiance(double brdf, Vec3 light_ts, Vec3 view_ts, double irradiance, bool fresnel);

// ---------------------------------------------------------------------------------------------
// Ground truth

struct GroundTruthSettings {
  int width = 256;
  int height = 256;
  int strata = 32;  // samples per pixel = strata^2 (32 -> 1024)
  std::uint64_t seed = 0x5aa6e11ULL;
  int threads = 0;                 // 0: hardware concurrency
  double filter_variance = 0.25;   // sigma^2 of the pixel filter (px^2)
  double filter_truncation = 3.0;  // support half-width in units of the underlying sigma
};

struct GroundTruth {
  std::vector<Image> images;  // one per material, in the order given
  Image coverage;             // fraction of each pixel's samples that hit the shape
};

// progress(samples_done, samples_total), on the calling thread (parallel_rows).
using SampleProgress = std::function<void(std::uint64_t done, std::uint64_t total)>;

GroundTruth render_ground_truth(const Scene& scene, const GroundTruthSettings& settings, std::span<const Material> materials,
                                const SampleProgress& progress = {});

// ---------------------------------------------------------------------------------------------
// 1-spp fields and variant images

// A shading frame and the shading vectors in it (PixelFields::band_limited).
struct ShadingFrame {
  Vec3 normal, tangent, bitangent;  // world space
  Vec3 light_ts, view_ts, half_ts;  // i, o, normalize(i + o) in (t, b, n)
};

// What a fragment shader has at one pixel centre.
struct PixelFields {
  bool hit = false;
  int object = 0;
  Vec3 position;
  Vec3 normal;     // world-space shading normal
  Vec3 tangent;    // world-space tangent
  Vec3 bitangent;  // world-space bitangent
  Vec3 to_light;   // i, world
  Vec3 to_view;    // o, world
  double irradiance = 0.0;
  Vec3 light_ts;    // i in (t, b, n)
  Vec3 view_ts;     // o in (t, b, n)
  Vec3 half_ts;     // normalize(i + o) (world) expressed in (t, b, n), as Listing 1 forms it
  Vec2 frag_coord;  // (x + 0.5, y + 0.5)

  // The base surface before the normal map (SurfaceHit's geometric frame: the shading frame
  // above except in normal-mapped scenes and on the bump plane) and the texture (uv
  // derivatives, lod and texel stay zero in a scene without a map).
  bool has_normal_map = false;
  Vec3 geometric_normal;
  Vec3 geometric_tangent;
  Vec3 geometric_bitangent;
  Vec3 geometric_half_ts;  // normalize(i + o) in the geometric frame
  Vec2 uv;                 // texture coordinate at the pixel centre
  Vec2 duv_dx;             // coarse quad derivatives of uv (see the top of this file)
  Vec2 duv_dy;
  double lod = 0.0;   // NormalMap::lod(duv_dx, duv_dy) + normal_lod_bias, unclamped (-inf for no change)
  NormalTexel texel;  // NormalMap::trilinear(uv, lod): stored normal, mean normal, LEAN
  // The roughness texture's factor on alpha (SurfaceHit::alpha_scale) from its trilinear sample
  // at its own implicit LOD; 1 without one. Every form filters material.alpha * alpha_scale.
  double alpha_scale = 1.0;
  int triangle = -1;  // SurfaceHit::triangle
  // SurfaceHit::weight, its texture sampled trilinearly at its own LOD: multiplies the radiance.
  double weight = 1.0;
  double coat = 0.0;  // SurfaceHit::coat, its texture sampled as the weight's
  // KHR_materials_anisotropy (anisotropy.hpp), its texture sampled as the weight's: the strength,
  // the direction in the texture's tangent frame and that frame's bitangent sign. The frames above
  // (shading and geometric) are already turned to the direction; the base lobe is
  // anisotropic_alpha2(alpha, anisotropy) in them.
  bool anisotropic = false;
  double anisotropy = 0.0;
  Vec2 anisotropy_direction{1.0, 0.0};
  double bitangent_sign = 1.0;
  // Procedural normal detail (Scene::footprint_slope_moments: the bump plane's sum of sines), what
  // a procedural shader band-limited to its footprint computes: the slope moments over the pixel's
  // Gaussian footprint in closed form, in texel.slope_mean and texel.slope_second (LEAN's two
  // moments, as a normal map's texel holds them), and the frame of the band-limited normal
  // normalize(-E[s], 1) through the geometric TBN. The footprint is the ground truth's pixel
  // filter (variance sigma^2 = default_pixel_filter().variance() px^2 per screen axis) pushed
  // through the quad's coarse uv derivatives: S_uv = sigma^2 (duv_dx duv_dx^T + duv_dy duv_dy^T).
  // Only the prefiltered rows shade in that frame (shade_pixel); every other form keeps the
  // unfiltered normal at the pixel centre above.
  bool has_footprint_moments = false;
  ShadingFrame band_limited;
};

// The uv covariance of the pixel filter's footprint, sigma2 (ddx ddx^T + ddy ddy^T).
Sym2 uv_footprint(double sigma2, Vec2 duv_dx, Vec2 duv_dy);

// Fields at the pixel centre (x + 0.5, y + 0.5); hit == false when the ray misses.
// normal_lod_bias is added to the normal map's implicit LOD: the map's normal and the moments a
// prefilter reads (texel) come from that many levels coarser (TradeConfig::prefilter_lod_bias).
PixelFields pixel_fields(const Scene& scene, int x, int y, int width, int height, double normal_lod_bias = 0.0);

// The uv a helper invocation extrapolates for a ray from the shaded hit: the ray meets the
// plane through hit.position spanned by hit.dpdu, hit.dpdv at X, and X - p = a dpdu + b dpdv
// (least squares through the 2x2 Gram matrix) gives uv + (a, b). The shaded uv itself when the
// ray is parallel to the plane or meets it behind its origin.
Vec2 tangent_plane_uv(const SurfaceHit& shaded, const Ray& ray);

// The uv of quad pixel (px, py) seen from the shaded hit of surface `object`: the pixel's own
// uv when its centre hits the same connected surface inside the image, tangent_plane_uv of its
// ray otherwise.
Vec2 quad_partner_uv(const Scene& scene, const SurfaceHit& shaded, int object, int px, int py, int width, int height);

struct UvDerivatives {
  Vec2 ddx;  // uv(quad pixel 1) - uv(quad pixel 0)
  Vec2 ddy;  // uv(quad pixel 2) - uv(quad pixel 0)
};

// Coarse uv derivatives of the quad of pixel (x, y), whose centre hit is `shaded`.
UvDerivatives coarse_uv_derivatives(const Scene& scene, const SurfaceHit& shaded, int x, int y, int width, int height);

// The frame in which the projected forward filters (forward-aniso-projected,
// forward-axis-projected) difference their half vectors across a 2x2 quad.
// tangent: each quad pixel's own tangent frame, as Tokuyoshi & Kaplanyan 2019 Listing 1
// differentiates half_ts (the templates' *_fragment wrappers): a frame that turns about the normal
// from pixel to pixel (a seam, a pole, tangents generated from uv) adds its turn, |h.xy| per
// radian, to the derivative, and the kernel widens most where the lobe is wide
// (docs/FORWARD_DERIVATIVES.md).
// transported: the templates' *_transported_fragment wrappers: the derivatives of the
// world-space half vector and normal read in the pixel's own frame with the frame's first-order
// change along the normal removed, so the frame's tilt, which is the surface's curvature the
// filter measures, stays and its turn about the normal goes. The slope forms, which have no such
// wrapper, keep the papers' in both.
enum class HalfVectorFrame { tangent, transported };
// Its name in `saagen bench --half-vector-frame` and the table's "half_vector_frame".
constexpr std::string_view to_string(HalfVectorFrame frame) { return frame == HalfVectorFrame::transported ? "transported" : "tangent"; }

// The fields of one quad pixel that a filter reads (gather_quad).
struct QuadPixel {
  bool valid = false;
  Vec3 normal, tangent, bitangent, half_ts;
  Vec3 geometric_normal, geometric_tangent, geometric_bitangent, geometric_half_ts;
};

// The quad inputs of a pixel: the fields of the four pixels of its 2x2 quad, partners off the
// surface replaced by the pixel's own fields (see the top of this file).
struct QuadFields {
  ref::Quad<Vec3> normal;
  ref::Quad<Vec3> tangent;
  ref::Quad<Vec3> bitangent;
  ref::Quad<Vec3> half_ts;
  ref::Quad<Vec2> frag_coord;
  ref::Quad<Vec3> geometric_normal;
  ref::Quad<Vec3> geometric_tangent;
  ref::Quad<Vec3> geometric_bitangent;
  ref::Quad<Vec3> geometric_half_ts;
  int pixel = 0;                                                 // index of (x, y) in the quad, (x & 1) + 2 (y & 1)
  HalfVectorFrame half_vector_frame = HalfVectorFrame::tangent;  // the wrappers the projected forward filters read it with
};

struct GBuffer {
  int width = 0;
  int height = 0;
  std::vector<PixelFields> pixels;  // row-major
  // Scenes with per-triangle quads (Scene::per_triangle_quads): per pixel and quad position
  // ((x & 1) + 2 (y & 1)), the fields a helper invocation of the pixel's triangle computes there
  // (Scene::extrapolate_surface; the normal map's trilinear sample at the extrapolated uv and the
  // pixel's own LOD); valid only where that quad pixel is not on the same triangle. Empty for
  // the other scenes.
  std::vector<std::array<QuadPixel, 4>> helpers;
  // Per pixel, its quad inputs gathered once (gather_quads; default fields where the pixel misses),
  // for many shadings of one G-buffer; empty: each shading gathers them (gather_quad).
  std::vector<QuadFields> quads;
  const PixelFields& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

GBuffer render_gbuffer(const Scene& scene, int width, int height, int threads = 0, double normal_lod_bias = 0.0);

// Precondition: gbuffer.at(x, y).hit.
QuadFields gather_quad(const GBuffer& gbuffer, int x, int y, HalfVectorFrame frame = HalfVectorFrame::tangent);
// Fills gbuffer.quads: what gather_quad returns, for every hit pixel. shade_pixel reads them
// instead of gathering: the trade shades each G-buffer once per row (configuration x material).
void gather_quads(GBuffer& gbuffer, int threads = 0, HalfVectorFrame frame = HalfVectorFrame::tangent);

struct PixelShade {
  double radiance = 0.0;
  // The roughness the BRDF was evaluated with, alpha^2 domain: the matrix A of the
  // non-axis-aligned forms, (ax^2, 0, ay^2) of the axis-aligned ones, (a^2, 0, a^2) otherwise.
  ref::Sym2 roughness;
};

// The 1-spp shading of pixel (x, y) with a variant (radiance 0 and roughness 0 on a miss).
// feed: the normal the filter reads (ignored by none; engines always read engine_feed()).
// The BRDF is always evaluated in the shading frame.
PixelShade shade_pixel(const GBuffer& gbuffer, int x, int y, Variant variant, const Material& material, const ref::Params& params = {},
                       ref::Derivative mode = ref::Derivative::coarse, NormalFeed feed = NormalFeed::shading,
                       Prefilter prefilter = Prefilter::none, double prefilter_scale = 1.0, Lobe lobe = Lobe::papers);

Image render_variant(const GBuffer& gbuffer, Variant variant, const Material& material, const ref::Params& params = {},
                     ref::Derivative mode = ref::Derivative::coarse, int threads = 0, NormalFeed feed = NormalFeed::shading,
                     Prefilter prefilter = Prefilter::none, double prefilter_scale = 1.0, Lobe lobe = Lobe::papers);

}  // namespace saagen::measure

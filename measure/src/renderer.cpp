// Ground truth and 1-spp variant images (see renderer.hpp).
#include "saagen/measure/renderer.hpp"

#include "saagen/measure/anisotropy.hpp"
#include "saagen/measure/engines.hpp"
#include "saagen/measure/parallel.hpp"
#include "saagen/reference/brdf.hpp"
#include "saagen/reference/prefilter.hpp"
#include "saagen/reference/wrapper_forms.hpp"
#include "saagen/template_variants.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <variant>

namespace saagen::measure {

using ref::dot;
using ref::normalize;
using ref::Sym2;
using ref::to_tangent_space;

namespace {

constexpr std::array<Variant, 6> kAllEngines{
    Variant::engine_hdrp,   Variant::engine_filament, Variant::engine_godot,
    Variant::engine_unreal, Variant::engine_threejs,  Variant::engine_babylon,
};

// The shading vectors of a hit: i, o in world space and in the tangent frame, E.
struct LocalShading {
  Vec3 to_light, to_view, light_ts, view_ts;
  double irradiance = 0.0;
};

LocalShading local_shading(const Scene& scene, const Ray& ray, const SurfaceHit& hit) {
  LocalShading s;
  scene.light().at(hit.position, s.to_light, s.irradiance);
  s.to_view = -1.0 * ray.direction;
  s.light_ts = to_tangent_space(s.to_light, hit.tangent, hit.bitangent, hit.normal);
  s.view_ts = to_tangent_space(s.to_view, hit.tangent, hit.bitangent, hit.normal);
  return s;
}

// KHR_materials_anisotropy at a ground-truth hit (anisotropy.hpp): the frames turned to the
// direction of the texture's level 0; returns the strength (0 on isotropic surfaces).
double apply_level0_anisotropy(const Scene& scene, SurfaceHit& hit) {
  const SurfaceTextures* textures = scene.surface_textures_at(hit);
  if (!textures || !textures->anisotropy) return 0.0;
  const AnisotropySample a = anisotropy_level0(*textures->anisotropy, hit.uv);
  apply_anisotropy_frame(hit, a.direction);
  return a.strength;
}

}  // namespace

double schlick_fresnel(double cos_theta, double f0) {
  const double c = ref::saturate(cos_theta);
  const double m = 1.0 - c;
  const double m2 = m * m;
  return f0 + (1.0 - f0) * m2 * m2 * m;
}

std::span<const Variant> all_engines() { return kAllEngines; }

bool is_engine(Variant v) { return std::find(kAllEngines.begin(), kAllEngines.end(), v) != kAllEngines.end(); }

std::string_view feed_name(NormalFeed feed) { return feed == NormalFeed::shading ? "shading" : "geometric"; }

std::string_view prefilter_name(Prefilter prefilter) {
  switch (prefilter) {
    case Prefilter::none:
      return "none";
    case Prefilter::toksvig:
      return "toksvig";
    case Prefilter::lean:
      return "lean";
    case Prefilter::unreal:
      return "unreal";
    case Prefilter::filament_vmf:
      return "filament-vmf";
    case Prefilter::hdrp:
      return "hdrp";
  }
  return "?";
}

std::string_view lobe_name(Lobe lobe) {
  switch (lobe) {
    case Lobe::papers:
      return "papers";
    case Lobe::tail:
      return "tail";
    case Lobe::mapped:
      return "mapped";
    case Lobe::exact:
      return "exact";
  }
  return "?";
}

NormalFeed engine_feed(Variant engine) {
  switch (engine) {
    case Variant::engine_godot:
    case Variant::engine_babylon:
      return NormalFeed::shading;
    default:
      return NormalFeed::geometric;
  }
}

double specular_radiance(double brdf, Vec3 light_ts, Vec3 view_ts, double irradiance, bool fresnel) {
  if (!(light_ts.z > 0.0)) return 0.0;
  double value = brdf * light_ts.z * irradiance;
  if (fresnel) {
    const Vec3 h = normalize(light_ts + view_ts);
    value *= schlick_fresnel(dot(light_ts, h));
  }
  return value;
}

// ---------------------------------------------------------------------------------------------
// Ground truth

GroundTruth render_ground_truth(const Scene& scene, const GroundTruthSettings& settings, std::span<const Material> materials,
                                const SampleProgress& progress) {
  if (settings.width <= 0 || settings.height <= 0 || settings.strata <= 0)
    throw std::invalid_argument("render_ground_truth: bad image size or strata");
  // The default filter is built once per process; other variances/truncations per call.
  const bool default_filter = settings.filter_variance == 0.25 && settings.filter_truncation == 3.0;
  std::optional<GaussianPixelFilter> custom_filter;
  if (!default_filter) custom_filter.emplace(settings.filter_variance, settings.filter_truncation);
  const GaussianPixelFilter& filter = default_filter ? default_pixel_filter() : *custom_filter;

  const int w = settings.width, h = settings.height;
  GroundTruth gt;
  gt.images.assign(materials.size(), Image(w, h));
  gt.coverage = Image(w, h);
  const std::size_t n_materials = materials.size();
  const std::size_t spp = static_cast<std::size_t>(settings.strata) * settings.strata;

  const CameraFilm film(scene.camera(), w, h);
  auto render_row = [&](int y) {
    std::vector<FilmOffset> offsets;
    std::vector<double> sums(n_materials);
    for (int x = 0; x < w; ++x) {
      Rng rng(pixel_seed(settings.seed, x, y));
      stratified_filter_offsets(filter, settings.strata, rng, offsets);
      std::fill(sums.begin(), sums.end(), 0.0);
      std::size_t hits = 0;
      for (const FilmOffset& off : offsets) {
        const Ray ray = film.ray(x + 0.5 + off.dx, y + 0.5 + off.dy);
        SurfaceHit hit;
        if (!scene.intersect(ray, hit)) continue;
        ++hits;
        const double anisotropy = apply_level0_anisotropy(scene, hit);
        const LocalShading s = local_shading(scene, ray, hit);
        if (!(s.light_ts.z > 0.0) || !(s.view_ts.z > 0.0)) continue;
        const Vec3 half = normalize(s.light_ts + s.view_ts);
        const double fresnel = schlick_fresnel(dot(s.light_ts, half));
        // A clearcoat layer above passes 1 - coat F of the light (KHR_materials_clearcoat).
        const double common = s.light_ts.z * s.irradiance * hit.weight * (1.0 - hit.coat * fresnel);
        double last_alpha = -1.0, last_brdf = 0.0;
        for (std::size_t m = 0; m < n_materials; ++m) {
          const double alpha = materials[m].alpha * hit.alpha_scale;
          if (alpha != last_alpha) {
            last_brdf = ref::ggx_brdf_axis(s.light_ts, s.view_ts, anisotropic_alpha2(alpha, anisotropy));
            last_alpha = alpha;
          }
          sums[m] += last_brdf * common * (materials[m].fresnel ? fresnel : 1.0);
        }
      }
      const double inv = 1.0 / static_cast<double>(spp);
      for (std::size_t m = 0; m < n_materials; ++m) gt.images[m].at(x, y) = static_cast<float>(sums[m] * inv);
      gt.coverage.at(x, y) = static_cast<float>(static_cast<double>(hits) * inv);
    }
  };

  const std::uint64_t total = static_cast<std::uint64_t>(w) * h * spp;
  std::function<void(int)> row_progress;
  if (progress) row_progress = [&](int rows_done) { progress(static_cast<std::uint64_t>(rows_done) * w * spp, total); };
  parallel_rows(h, settings.threads, render_row, row_progress);
  return gt;
}

// ---------------------------------------------------------------------------------------------
// 1-spp fields

Vec2 tangent_plane_uv(const SurfaceHit& shaded, const Ray& ray) {
  const Vec3 plane_normal = ref::cross(shaded.dpdu, shaded.dpdv);
  const double denominator = dot(ray.direction, plane_normal);
  if (denominator == 0.0) return shaded.uv;
  // o + t d on the plane: (o + t d - p) . m = 0.
  const double t = dot(shaded.position - ray.origin, plane_normal) / denominator;
  if (!(t > 0.0)) return shaded.uv;
  const Vec3 offset = ray.origin + t * ray.direction - shaded.position;
  // Normal equations of offset = a dpdu + b dpdv: G (a, b) = (offset . dpdu, offset . dpdv).
  const double g_uu = dot(shaded.dpdu, shaded.dpdu), g_uv = dot(shaded.dpdu, shaded.dpdv), g_vv = dot(shaded.dpdv, shaded.dpdv);
  const double det = g_uu * g_vv - g_uv * g_uv;
  if (!(det > 0.0)) return shaded.uv;
  const double r_u = dot(offset, shaded.dpdu), r_v = dot(offset, shaded.dpdv);
  return shaded.uv + Vec2{(g_vv * r_u - g_uv * r_v) / det, (g_uu * r_v - g_uv * r_u) / det};
}

Vec2 quad_partner_uv(const Scene& scene, const SurfaceHit& shaded, int object, int px, int py, int width, int height) {
  const Ray ray = scene.camera().generate(px + 0.5, py + 0.5, width, height);
  const bool inside = px >= 0 && py >= 0 && px < width && py < height;
  SurfaceHit partner;
  if (inside && scene.intersect_surface(ray, partner) && partner.object == object &&
      (!scene.per_triangle_quads() || partner.triangle == shaded.triangle))
    return partner.uv;
  return tangent_plane_uv(shaded, ray);
}

UvDerivatives coarse_uv_derivatives(const Scene& scene, const SurfaceHit& shaded, int x, int y, int width, int height) {
  const int x0 = x & ~1, y0 = y & ~1;
  // Quad pixels 0 = (x0, y0), 1 = (x0 + 1, y0), 2 = (x0, y0 + 1); the shaded pixel uses its
  // own hit.
  auto uv_at = [&](int px, int py) {
    if (px == x && py == y) return shaded.uv;
    return quad_partner_uv(scene, shaded, shaded.object, px, py, width, height);
  };
  const Vec2 uv0 = uv_at(x0, y0);
  return {uv_at(x0 + 1, y0) - uv0, uv_at(x0, y0 + 1) - uv0};
}

Sym2 uv_footprint(double sigma2, Vec2 duv_dx, Vec2 duv_dy) {
  return {sigma2 * (duv_dx.x * duv_dx.x + duv_dy.x * duv_dy.x), sigma2 * (duv_dx.x * duv_dx.y + duv_dy.x * duv_dy.y),
          sigma2 * (duv_dx.y * duv_dx.y + duv_dy.y * duv_dy.y)};
}

namespace {

ShadingFrame shading_frame(const SurfaceHit& hit, const LocalShading& s) {
  return {hit.normal, hit.tangent, hit.bitangent,
          s.light_ts, s.view_ts,   to_tangent_space(normalize(s.to_view + s.to_light), hit.tangent, hit.bitangent, hit.normal)};
}

// PixelFields::texel's moments and band_limited frame of a hit with procedural normal detail.
void set_footprint_moments(const Scene& scene, const Ray& ray, const SurfaceHit& hit, const SlopeMoments& moments, PixelFields& f) {
  f.has_footprint_moments = true;
  f.texel.slope_mean = moments.mean;
  f.texel.slope_second = moments.second;
  // The slope s = -n.xy / n.z: the band-limited tangent-space normal is (-E[s], 1).
  f.texel.normal = normalize(Vec3{-moments.mean.x, -moments.mean.y, 1.0});
  SurfaceHit band_limited = hit;
  Scene::apply_normal_map(band_limited, f.texel.normal);
  f.band_limited = shading_frame(band_limited, local_shading(scene, ray, band_limited));
}

}  // namespace

PixelFields pixel_fields(const Scene& scene, int x, int y, int width, int height, double normal_lod_bias) {
  PixelFields f;
  f.frag_coord = {x + 0.5, y + 0.5};
  const Ray ray = scene.camera().generate(x + 0.5, y + 0.5, width, height);
  SurfaceHit hit;
  if (!scene.intersect_surface(ray, hit)) return f;
  const NormalMap* map = scene.normal_map_at(hit);
  const ScalarMap* roughness = scene.roughness_map_at(hit);
  const SurfaceTextures* textures = scene.surface_textures_at(hit);
  const ScalarMap* weight = textures ? textures->weight_map.get() : nullptr;
  const ScalarMap* coat = textures ? textures->coat_map.get() : nullptr;
  const Anisotropy* anisotropy = textures ? textures->anisotropy.get() : nullptr;
  // Procedural normal detail: whether the shape has footprint moments (asked with an empty
  // footprint; the pixel's own comes from the uv derivatives below).
  const bool procedural = scene.footprint_slope_moments(hit, Sym2{}).has_value();
  if (map || roughness || weight || coat || (anisotropy && anisotropy->textured()) || procedural) {
    const UvDerivatives d = coarse_uv_derivatives(scene, hit, x, y, width, height);
    f.duv_dx = d.ddx;
    f.duv_dy = d.ddy;
  }
  if (map) {
    // Implicit LOD from the quad's coarse derivatives, trilinear sample, renormalise, TBN.
    f.has_normal_map = true;
    f.lod = map->lod(f.duv_dx, f.duv_dy) + normal_lod_bias;
    f.texel = map->trilinear(hit.uv, f.lod);
    Scene::apply_normal_map(hit, normalize(f.texel.normal));
  }
  if (anisotropy) {
    const AnisotropySample a = anisotropy_trilinear(*anisotropy, hit.uv, f.duv_dx, f.duv_dy);
    f.anisotropic = true;
    f.anisotropy = a.strength;
    f.anisotropy_direction = a.direction;
    f.bitangent_sign = hit.bitangent_sign;
    apply_anisotropy_frame(hit, a.direction);
  }
  // The roughness texture's own implicit LOD (its size may differ from the normal map's).
  if (roughness) f.alpha_scale = roughness_alpha_scale(roughness->trilinear(hit.uv, roughness->lod(f.duv_dx, f.duv_dy)));
  if (textures) {
    f.weight = textures->weight * (weight ? ref::saturate(weight->trilinear(hit.uv, weight->lod(f.duv_dx, f.duv_dy))) : 1.0);
    f.coat = textures->coat * (coat ? ref::saturate(coat->trilinear(hit.uv, coat->lod(f.duv_dx, f.duv_dy))) : 1.0);
  }
  const LocalShading s = local_shading(scene, ray, hit);
  f.hit = true;
  f.object = hit.object;
  f.position = hit.position;
  f.normal = hit.normal;
  f.tangent = hit.tangent;
  f.bitangent = hit.bitangent;
  f.to_light = s.to_light;
  f.to_view = s.to_view;
  f.irradiance = s.irradiance;
  f.light_ts = s.light_ts;
  f.view_ts = s.view_ts;
  f.half_ts = to_tangent_space(normalize(s.to_view + s.to_light), hit.tangent, hit.bitangent, hit.normal);
  f.geometric_normal = hit.geometric_normal;
  f.geometric_tangent = hit.geometric_tangent;
  f.geometric_bitangent = hit.geometric_bitangent;
  f.geometric_half_ts =
      to_tangent_space(normalize(s.to_view + s.to_light), hit.geometric_tangent, hit.geometric_bitangent, hit.geometric_normal);
  f.uv = hit.uv;
  f.triangle = hit.triangle;
  if (procedural)
    set_footprint_moments(scene, ray, hit,
                          *scene.footprint_slope_moments(hit, uv_footprint(default_pixel_filter().variance(), f.duv_dx, f.duv_dy)), f);
  return f;
}

namespace {

QuadPixel quad_pixel(const PixelFields& f) {
  return {true,
          f.normal,
          f.tangent,
          f.bitangent,
          f.half_ts,
          f.geometric_normal,
          f.geometric_tangent,
          f.geometric_bitangent,
          f.geometric_half_ts};
}

// The fields a helper invocation of the triangle hit at (x, y) computes at quad pixel (px, py).
QuadPixel helper_pixel(const Scene& scene, const SurfaceHit& shaded, const PixelFields& f, int px, int py, int width, int height) {
  const Ray ray = scene.camera().generate(px + 0.5, py + 0.5, width, height);
  SurfaceHit hit;
  if (!scene.extrapolate_surface(shaded, ray, hit)) return {};
  if (const NormalMap* map = scene.normal_map_at(hit)) Scene::apply_normal_map(hit, normalize(map->trilinear(hit.uv, f.lod).normal));
  if (const SurfaceTextures* textures = scene.surface_textures_at(hit); textures && textures->anisotropy)
    apply_anisotropy_frame(hit, anisotropy_trilinear(*textures->anisotropy, hit.uv, f.duv_dx, f.duv_dy).direction);
  const LocalShading s = local_shading(scene, ray, hit);
  const Vec3 half = normalize(s.to_view + s.to_light);
  return {true,
          hit.normal,
          hit.tangent,
          hit.bitangent,
          to_tangent_space(half, hit.tangent, hit.bitangent, hit.normal),
          hit.geometric_normal,
          hit.geometric_tangent,
          hit.geometric_bitangent,
          to_tangent_space(half, hit.geometric_tangent, hit.geometric_bitangent, hit.geometric_normal)};
}

// GBuffer::helpers of a scene with per-triangle quads.
void fill_helpers(const Scene& scene, GBuffer& g, int threads) {
  g.helpers.assign(g.pixels.size(), {});
  parallel_rows(g.height, threads, [&](int y) {
    for (int x = 0; x < g.width; ++x) {
      const PixelFields& f = g.at(x, y);
      if (!f.hit) continue;
      SurfaceHit shaded;
      if (!scene.intersect_surface(scene.camera().generate(x + 0.5, y + 0.5, g.width, g.height), shaded)) continue;
      for (int q = 0; q < 4; ++q) {
        const int qx = (x & ~1) + (q & 1), qy = (y & ~1) + (q >> 1);
        if (qx == x && qy == y) continue;
        if (qx < g.width && qy < g.height) {
          const PixelFields& partner = g.at(qx, qy);
          if (partner.hit && partner.object == f.object && partner.triangle == f.triangle) continue;
        }
        g.helpers[static_cast<std::size_t>(y) * g.width + x][static_cast<std::size_t>(q)] =
            helper_pixel(scene, shaded, f, qx, qy, g.width, g.height);
      }
    }
  });
}

}  // namespace

GBuffer render_gbuffer(const Scene& scene, int width, int height, int threads, double normal_lod_bias) {
  GBuffer g;
  g.width = width;
  g.height = height;
  g.pixels.resize(static_cast<std::size_t>(width) * height);
  parallel_rows(height, threads, [&](int y) {
    for (int x = 0; x < width; ++x)
      g.pixels[static_cast<std::size_t>(y) * width + x] = pixel_fields(scene, x, y, width, height, normal_lod_bias);
  });
  if (scene.per_triangle_quads()) fill_helpers(scene, g, threads);
  return g;
}

QuadFields gather_quad(const GBuffer& gbuffer, int x, int y, HalfVectorFrame frame) {
  const PixelFields& self = gbuffer.at(x, y);
  if (!self.hit) throw std::invalid_argument("gather_quad: the pixel does not hit the shape");
  const int x0 = x & ~1, y0 = y & ~1;
  const bool per_triangle = !gbuffer.helpers.empty();
  std::array<QuadPixel, 4> source{};
  std::array<Vec2, 4> frag{};
  for (int q = 0; q < 4; ++q) {
    const int qx = x0 + (q & 1), qy = y0 + (q >> 1);
    frag[q] = {qx + 0.5, qy + 0.5};
    source[q] = quad_pixel(self);
    if (qx == x && qy == y) continue;
    if (qx < gbuffer.width && qy < gbuffer.height) {
      const PixelFields& partner = gbuffer.at(qx, qy);
      if (partner.hit && partner.object == self.object && (!per_triangle || partner.triangle == self.triangle)) {
        source[q] = quad_pixel(partner);
        continue;
      }
    }
    if (per_triangle) {
      const QuadPixel& helper = gbuffer.helpers[static_cast<std::size_t>(y) * gbuffer.width + x][static_cast<std::size_t>(q)];
      if (helper.valid) source[q] = helper;
    }
  }
  const int own = (x & 1) + 2 * (y & 1);
  auto quad = [&](Vec3 QuadPixel::*member) {
    return ref::Quad<Vec3>{source[0].*member, source[1].*member, source[2].*member, source[3].*member};
  };
  QuadFields q;
  q.normal = quad(&QuadPixel::normal);
  q.tangent = quad(&QuadPixel::tangent);
  q.bitangent = quad(&QuadPixel::bitangent);
  q.half_ts = quad(&QuadPixel::half_ts);
  q.frag_coord = {frag[0], frag[1], frag[2], frag[3]};
  q.geometric_normal = quad(&QuadPixel::geometric_normal);
  q.geometric_tangent = quad(&QuadPixel::geometric_tangent);
  q.geometric_bitangent = quad(&QuadPixel::geometric_bitangent);
  q.geometric_half_ts = quad(&QuadPixel::geometric_half_ts);
  q.pixel = own;
  q.half_vector_frame = frame;
  return q;
}

void gather_quads(GBuffer& gbuffer, int threads, HalfVectorFrame frame) {
  std::vector<QuadFields> quads(gbuffer.pixels.size());
  parallel_rows(gbuffer.height, threads, [&](int y) {
    for (int x = 0; x < gbuffer.width; ++x)
      if (gbuffer.at(x, y).hit) quads[static_cast<std::size_t>(y) * gbuffer.width + x] = gather_quad(gbuffer, x, y, frame);
  });
  gbuffer.quads = std::move(quads);
}

namespace {

// The quad inputs of hit pixel (x, y): gbuffer.quads' when gathered, else gathered into `storage`.
const QuadFields& quad_fields(const GBuffer& gbuffer, int x, int y, std::optional<QuadFields>& storage) {
  if (!gbuffer.quads.empty()) return gbuffer.quads[static_cast<std::size_t>(y) * gbuffer.width + x];
  return storage.emplace(gather_quad(gbuffer, x, y));
}

// The quad inputs a filter reads, from the shading or the geometric frame.
struct FeedQuads {
  const ref::Quad<Vec3>& normal;
  const ref::Quad<Vec3>& tangent;
  const ref::Quad<Vec3>& bitangent;
  const ref::Quad<Vec3>& half_ts;
};

FeedQuads feed_quads(const QuadFields& q, NormalFeed feed) {
  if (feed == NormalFeed::geometric) return {q.geometric_normal, q.geometric_tangent, q.geometric_bitangent, q.geometric_half_ts};
  return {q.normal, q.tangent, q.bitangent, q.half_ts};
}

// The quad's half vectors in world space, from each pixel's own (orthonormal) frame.
ref::Quad<Vec3> world_half_vectors(const FeedQuads& in) {
  return ref::map_indexed(in.half_ts, [&](Vec3 h, int q) { return in.tangent[q] * h.x + in.bitangent[q] * h.y + in.normal[q] * h.z; });
}

// alpha^2 after an engine's shipped form (engines.hpp), on the normal the engine feeds.
double engine_alpha2(Variant engine, double alpha, const QuadFields& q, ref::Derivative mode) {
  const ref::Quad<Vec3>& n = feed_quads(q, engine_feed(engine)).normal;
  const Vec3 dndx = ref::ddx(n, q.pixel, mode), dndy = ref::ddy(n, q.pixel, mode);
  switch (engine) {
    case Variant::engine_hdrp:
      return hdrp_alpha2(alpha, dndx, dndy);
    case Variant::engine_filament:
      return filament_alpha2(alpha, dndx, dndy);
    case Variant::engine_godot:
      return godot_alpha2(alpha, dndx, dndy);
    case Variant::engine_unreal:
      return unreal_alpha2(alpha, dndx, dndy);
    case Variant::engine_threejs:
      return threejs_alpha2(alpha, dndx, dndy);
    case Variant::engine_babylon:
      return babylon_alpha2(alpha, dndx, dndy);
    default:
      throw std::invalid_argument("engine_alpha2: not an engine");
  }
}

// The texture's roughness at a pixel in the alpha^2 domain (prefilter.hpp): 2 sigma^2 I
// (Toksvig), 2 Sigma_tex (LEAN) or an engine's baked alpha'^2 less the base alpha2, as a
// symmetric matrix in the tangent frame.
Sym2 texture_roughness(const PixelFields& f, Prefilter prefilter, const ref::Params& params, double alpha2) {
  if (prefilter == Prefilter::none) return {};
  if (f.has_footprint_moments) {
    if (prefilter != Prefilter::lean)
      throw std::invalid_argument("shade_pixel: procedural normal detail has LEAN's moments only; prefilter " +
                                  std::string(prefilter_name(prefilter)) + " needs a normal map");
    return 2.0 * ref::lean_covariance(params, f.texel.slope_mean, f.texel.slope_second);
  }
  if (!f.has_normal_map) return {};
  const double length = ref::length(f.texel.mean_normal);
  double v = 0.0;
  switch (prefilter) {
    case Prefilter::lean:
      return 2.0 * ref::lean_covariance(params, f.texel.slope_mean, f.texel.slope_second);
    case Prefilter::toksvig:
      v = 2.0 * ref::toksvig_variance(params, length);
      break;
    case Prefilter::unreal:
      v = ref::unreal_composite_alpha2(alpha2, length) - alpha2;
      break;
    case Prefilter::filament_vmf:
      v = ref::filament_vmf_alpha2(alpha2, length) - alpha2;
      break;
    default:
      v = ref::hdrp_texture_alpha2(alpha2, length) - alpha2;
      break;
  }
  return {v, 0.0, v};
}

// deferred-aniso as the emitted passes compute it: the geometry pass's tensor in the frame built
// from the fed normal, the lighting pass's A = diag(alpha^2) + (n.h)^2 K there (the tail-preserving
// lobe's diag(alpha^2) + K, deferred_aniso_tail_roughness); then A carried
// into the pixel's shading frame (t, b), A' = M A M^T with M = [t'.t b'.t; t'.b b'.b], so that
// the texture term and every lobe apply as to the forward matrix. With the shading feed the two
// frames share n and M is a rotation: the BRDF is deferred_aniso_brdf's (tail lobe).
Sym2 deferred_aniso_in_pixel_frame(const ref::Params& params, const PixelFields& f, const ref::Quad<Vec3>& normal, int pixel,
                                   ref::Derivative mode, double alpha2, Lobe lobe) {
  const Vec3 n = normal[pixel];
  const Sym2 tensor = ref::deferred_aniso_fragment_quad(params, normal, pixel, mode);
  const Sym2 a = lobe == Lobe::tail ? ref::deferred_aniso_tail_roughness(tensor, alpha2)
                                    : ref::deferred_aniso_roughness(params, f.to_light, f.to_view, n, tensor, alpha2);
  const Vec3 t = ref::normal_frame_tangent(n), b = ref::normal_frame_bitangent(n);
  const double m00 = dot(t, f.tangent), m01 = dot(b, f.tangent), m10 = dot(t, f.bitangent), m11 = dot(b, f.bitangent);
  // Rows of M A: (m00 a.xx + m01 a.xy, m00 a.xy + m01 a.yy), (m10 a.xx + m11 a.xy, m10 a.xy + m11 a.yy).
  const double r0x = m00 * a.xx + m01 * a.xy, r0y = m00 * a.xy + m01 * a.yy;
  const double r1x = m10 * a.xx + m11 * a.xy, r1y = m10 * a.xy + m11 * a.yy;
  return {r0x * m00 + r0y * m01, r0x * m10 + r0y * m11, r1x * m10 + r1y * m11};
}

// ---------------------------------------------------------------------------------------------
// The variants: one row each. A template's SAA filter is registered here by naming convention: its
// row calls the CPU reference of its fragment wrapper, ref::<identifier>_fragment_quad (saa.hpp),
// in the form its signature has; which filters there are, and their order, come from the
// templates (saagen/template_variants.hpp, generated from templates/*.saa). A filter whose
// reference has none of the forms gets a row of its own in custom_filter(), and the
// static_asserts below refuse a template filter without a reference.

// What a filter's reference reads at a pixel.
struct FilterInputs {
  const ref::Params& params;
  Vec2 alpha2;  // the unfiltered roughness per axis (the lobe's anisotropy included)
  double a2;    // the material's alpha^2, before the lobe's anisotropy
  const FeedQuads& in;
  const QuadFields& q;
  const PixelFields& f;
  ref::Derivative mode;
  Lobe lobe;  // what shades the filtered roughness (deferred-aniso's A depends on it)
};

// The three forms of a filter's result: a roughness matrix A (forward-aniso-*, deferred-aniso),
// per-axis (ax'^2, ay'^2) (forward-axis-*), or an isotropic alpha^2 -> alpha'^2 (the other
// deferred-*), which shade_pixel applies once per axis of an anisotropic lobe.
using MatrixFilter = Sym2 (*)(const FilterInputs&);
using AxisFilter = Vec2 (*)(const FilterInputs&);
using IsotropicFilter = double (*)(const FilterInputs&, double unfiltered);
using Filter = std::variant<std::monostate, MatrixFilter, AxisFilter, IsotropicFilter>;

// A half-vector filter's row in the form of its result: a roughness matrix (Sym2) or per axis.
template <class Result, class Form>
constexpr Filter matrix_or_axis(Form filter) {
  if constexpr (std::is_same_v<Result, Sym2>) {
    return MatrixFilter{filter};
  } else {
    return AxisFilter{filter};
  }
}

// The row's filter of a fragment wrapper's reference, in the form its signature has; none when it
// has none of them (then custom_filter() must have the row).
template <class Reference>
constexpr Filter filter_by_form(Reference) {
  using namespace ref::wrapper_forms;
  if constexpr (reads_half_vectors<Reference>) {
    return matrix_or_axis<half_vector_result_t<Reference>>(
        [](const FilterInputs& x) { return Reference{}(x.params, x.alpha2, x.in.half_ts, x.q.pixel, x.mode); });
  } else if constexpr (reads_half_vectors_in_frames<Reference>) {
    return matrix_or_axis<half_vector_in_frames_result_t<Reference>>([](const FilterInputs& x) {
      return Reference{}(x.params, x.alpha2, world_half_vectors(x.in), x.in.normal, x.in.tangent, x.in.bitangent, x.q.pixel, x.mode);
    });
  } else if constexpr (reads_normal_frame<Reference>) {
    return IsotropicFilter{[](const FilterInputs& x, double unfiltered) {
      return Reference{}(x.params, unfiltered, x.in.normal, x.in.tangent, x.in.bitangent, x.q.frag_coord, x.q.pixel, x.mode);
    }};
  } else if constexpr (reads_normals<Reference>) {
    return IsotropicFilter{
        [](const FilterInputs& x, double unfiltered) { return Reference{}(x.params, unfiltered, x.in.normal, x.q.pixel, x.mode); }};
  } else {
    return Filter{};
  }
}

// The filters whose row is not their wrapper's reference: deferred-aniso's tensor is turned into
// the pixel's frame, on the base alpha^2, then the lobe's anisotropy is added along t (0 when isotropic).
constexpr Filter custom_filter(Variant variant) {
  if (variant == Variant::deferred_aniso) {
    return MatrixFilter{[](const FilterInputs& x) {
      return deferred_aniso_in_pixel_frame(x.params, x.f, x.in.normal, x.q.pixel, x.mode, x.a2, x.lobe) +
             Sym2{x.alpha2.x - x.a2, 0.0, x.alpha2.y - x.a2};
    }};
  }
  return Filter{};
}

// The projected forms' wrappers in transported frames (templates/10-forward.saa:
// *_transported_fragment), which a quad gathered for HalfVectorFrame::transported is shaded with;
// none for the other filters.
constexpr Filter transported_filter(Variant variant) {
  if (variant == Variant::forward_aniso_projected)
    return filter_by_form(SAAGEN_REFERENCE_CALLABLE(forward_aniso_projected_transported_fragment_quad));
  if (variant == Variant::forward_axis_projected)
    return filter_by_form(SAAGEN_REFERENCE_CALLABLE(forward_axis_projected_transported_fragment_quad));
  return Filter{};
}

template <class Reference>
constexpr Filter filter_of(Variant variant, Reference reference) {
  const Filter custom = custom_filter(variant);
  return custom.index() != 0 ? custom : filter_by_form(reference);
}

struct VariantRow {
  Variant variant;
  std::string_view id;
  // The template filter whose row this one follows in all_variants(): a measurement-only form,
  // a function of that template variant that the trade measures as a row of its own.
  std::string_view form_of;
  Filter filter;  // none and the engines: monostate (shade_pixel shades them itself)
};

// In the order of the Variant enumerators (checked below), so that a row is found by its value.
#define SAAGEN_TEMPLATE_FILTER_ROW(identifier, id) \
  {Variant::identifier, id, "", filter_of(Variant::identifier, SAAGEN_REFERENCE_CALLABLE(identifier##_fragment_quad))},
constexpr auto kVariantRows = std::to_array<VariantRow>({
    {Variant::none, "none", "", {}},
    SAAGEN_SAA_FILTERS(SAAGEN_TEMPLATE_FILTER_ROW)
    // The measurement-only forms, then the engines' (shade_pixel shades them itself).
    {Variant::deferred_max_tangent_free, "deferred-max-tangent-free", "deferred-max",
     filter_by_form(SAAGEN_REFERENCE_CALLABLE(deferred_max_tangent_free_fragment_quad))},
    {Variant::engine_hdrp, "engine-hdrp", "", {}},
    {Variant::engine_filament, "engine-filament", "", {}},
    {Variant::engine_godot, "engine-godot", "", {}},
    {Variant::engine_unreal, "engine-unreal", "", {}},
    {Variant::engine_threejs, "engine-threejs", "", {}},
    {Variant::engine_babylon, "engine-babylon", "", {}},
});
#undef SAAGEN_TEMPLATE_FILTER_ROW

constexpr bool rows_follow_the_enum() {
  for (std::size_t i = 0; i < kVariantRows.size(); ++i)
    if (static_cast<std::size_t>(kVariantRows[i].variant) != i) return false;
  return true;
}
static_assert(rows_follow_the_enum(), "kVariantRows: one row per Variant, in the enumerators' order");

constexpr const VariantRow* find_row(std::string_view id) {
  for (const VariantRow& row : kVariantRows)
    if (row.id == id) return &row;
  return nullptr;
}

constexpr bool every_template_filter_has_a_filter_row() {
  for (std::string_view id : templates::kSaaFilterIds)
    if (!find_row(id) || find_row(id)->filter.index() == 0) return false;
  return true;
}
static_assert(every_template_filter_has_a_filter_row(),
              "a template's SAA filter (templates/*.saa) has no row with its CPU reference in kVariantRows");

constexpr std::size_t measurement_only_form_count() {
  std::size_t count = 0;
  for (const VariantRow& row : kVariantRows) count += row.form_of.empty() ? 0 : 1;
  return count;
}

// saagen's variants as the trade measures them: the no-SAA baseline, then the templates' filters
// in the templates' order, each followed by its measurement-only forms.
constexpr std::size_t kAllVariantCount = 1 + templates::kSaaFilterIds.size() + measurement_only_form_count();
constexpr std::array<Variant, kAllVariantCount> kAllVariants = [] {
  std::array<Variant, kAllVariantCount> variants{};
  std::size_t next = 0;
  variants[next++] = Variant::none;
  for (std::string_view id : templates::kSaaFilterIds) {
    variants[next++] = find_row(id)->variant;
    for (const VariantRow& row : kVariantRows)
      if (row.form_of == id) variants[next++] = row.variant;
  }
  return variants;
}();

const VariantRow& variant_row(Variant v) { return kVariantRows.at(static_cast<std::size_t>(v)); }

// The pixel's fields in the band-limited normal's frame (PixelFields::band_limited): what a
// prefiltered row shades on procedural normal detail.
PixelFields band_limited_fields(const PixelFields& f) {
  PixelFields band = f;
  band.normal = f.band_limited.normal;
  band.tangent = f.band_limited.tangent;
  band.bitangent = f.band_limited.bitangent;
  band.light_ts = f.band_limited.light_ts;
  band.view_ts = f.band_limited.view_ts;
  band.half_ts = f.band_limited.half_ts;
  return band;
}

}  // namespace

std::string_view variant_id(Variant v) { return variant_row(v).id; }

std::optional<Variant> variant_from_id(std::string_view id) {
  if (const VariantRow* row = find_row(id)) return row->variant;
  return std::nullopt;
}

std::span<const Variant> all_variants() { return kAllVariants; }

namespace {

// A pixel's filtered roughness through the lobe it is shaded with (shade_pixel): the texture term
// joins each form in its own domain (prefilter.hpp): added to alpha^2 and saturated; in projected
// space for deferred-projected-space; to A for the matrix forms. Then the lobe's mapping and BRDF.
class LobeShading {
 public:
  LobeShading(const PixelFields& f, Variant variant, double alpha, const ref::Params& params, Prefilter prefilter, double prefilter_scale,
              Lobe lobe)
      : f_(f),
        variant_(variant),
        a2_(alpha * alpha),
        // The unfiltered roughness per axis: (alpha_t^2, alpha_b^2) on an anisotropic lobe (in its
        // turned frame), (alpha^2, alpha^2) otherwise.
        alpha2_(f.anisotropic ? anisotropic_alpha2(alpha, f.anisotropy) : Vec2{a2_, a2_}),
        per_axis_(alpha2_.x != alpha2_.y),
        texture_(texture_term(f, params, prefilter, prefilter_scale, a2_)),
        // Isotropic forms take the mean of the two axes: 2 sigma^2 (Toksvig), tr(Sigma_tex) (LEAN).
        texture_isotropic_(0.5 * ref::trace(texture_)),
        // The lobe applies to saagen's filters; none and the engines keep the papers' GGX.
        evaluated_(variant == Variant::none || is_engine(variant) ? Lobe::papers : lobe) {}

  Vec2 alpha2() const { return alpha2_; }
  double a2() const { return a2_; }
  bool per_axis() const { return per_axis_; }
  const Sym2& roughness() const { return roughness_; }
  double brdf() const { return brdf_; }

  // Per-axis filtered roughness (texture term included) through the lobe.
  void shade_axis(Vec2 filtered) {
    if (evaluated_ == Lobe::mapped)
      filtered = {ref::ggx_filtered_alpha2(alpha2_.x, filtered.x - alpha2_.x), ref::ggx_filtered_alpha2(alpha2_.y, filtered.y - alpha2_.y)};
    roughness_ = {filtered.x, 0.0, filtered.y};
    if (evaluated_ == Lobe::exact) {
      brdf_ = ref::ggx_brdf_filtered_exact(f_.light_ts, f_.view_ts, roughness_, alpha2_);
      return;
    }
    brdf_ = evaluated_ == Lobe::tail ? ref::ggx_brdf_filtered_axis(f_.light_ts, f_.view_ts, filtered, alpha2_)
                                     : ref::ggx_brdf_axis(f_.light_ts, f_.view_ts, filtered);
  }

  double with_isotropic_texture(double filtered) const {
    return variant_ == Variant::deferred_projected_space ? ref::projected_space_add(filtered, texture_isotropic_)
                                                         : ref::saturate(filtered + texture_isotropic_);
  }

  void isotropic(double filtered) {
    filtered = with_isotropic_texture(filtered);
    shade_axis({filtered, filtered});
  }

  // An isotropic form (alpha^2 -> alpha'^2) on the lobe: once, or once per axis of an
  // anisotropic lobe (as the planner emits a deferred-* filter on anisotropic roughness).
  template <class Form>
  void isotropic_form(Form&& form) {
    if (!per_axis_) return isotropic(form(a2_));
    shade_axis({with_isotropic_texture(form(alpha2_.x)), with_isotropic_texture(form(alpha2_.y))});
  }

  void axis(Vec2 filtered) { shade_axis({ref::saturate(filtered.x + texture_.xx), ref::saturate(filtered.y + texture_.yy)}); }

  void matrix(Sym2 a) {
    a = a + texture_;
    if (evaluated_ == Lobe::mapped) {
      const Sym2 unfiltered{alpha2_.x, 0.0, alpha2_.y};
      const Sym2 kernel = a - unfiltered;
      a = unfiltered + ref::ggx_kernel_scale(0.5 * (alpha2_.x + alpha2_.y), 0.5 * ref::trace(kernel)) * kernel;
    }
    roughness_ = a;
    if (evaluated_ == Lobe::exact) {
      brdf_ = ref::ggx_brdf_filtered_exact(f_.light_ts, f_.view_ts, a, alpha2_);
      return;
    }
    brdf_ = evaluated_ == Lobe::tail ? ref::ggx_brdf_filtered_matrix(f_.light_ts, f_.view_ts, a, alpha2_)
                                     : ref::ggx_brdf_matrix(f_.light_ts, f_.view_ts, a, ref::ndf_clamp_tau(alpha2_));
  }

 private:
  // The texture term, in the anisotropic lobe's turned frame where it has one.
  static Sym2 texture_term(const PixelFields& f, const ref::Params& params, Prefilter prefilter, double prefilter_scale, double a2) {
    const Sym2 texture = prefilter_scale * texture_roughness(f, prefilter, params, a2);
    return f.anisotropic ? to_anisotropy_frame(texture, f.anisotropy_direction, f.bitangent_sign) : texture;
  }

  const PixelFields& f_;
  Variant variant_;
  double a2_;
  Vec2 alpha2_;
  bool per_axis_;
  Sym2 texture_;
  double texture_isotropic_;
  Lobe evaluated_;
  Sym2 roughness_;
  double brdf_ = 0.0;
};

// An engine's shipped form (engines.hpp) on the lobe: its alpha'^2, or on an anisotropic lobe the
// extension's mapping of its alpha' (three.js's order).
void shade_engine(LobeShading& shading, Variant engine, double alpha, const QuadFields& q, const PixelFields& f, ref::Derivative mode) {
  const double filtered = engine_alpha2(engine, alpha, q, mode);
  if (!shading.per_axis()) return shading.isotropic(filtered);
  const Vec2 e = anisotropic_alpha2(std::sqrt(filtered), f.anisotropy);
  shading.shade_axis({shading.with_isotropic_texture(e.x), shading.with_isotropic_texture(e.y)});
}

// A saagen filter's row (kVariantRows) on the lobe, in the form its reference has.
void shade_filter(LobeShading& shading, Variant variant, const FilterInputs& inputs) {
  const Filter transported = inputs.q.half_vector_frame == HalfVectorFrame::transported ? transported_filter(variant) : Filter{};
  const Filter& filter = transported.index() != 0 ? transported : variant_row(variant).filter;
  if (const MatrixFilter* form = std::get_if<MatrixFilter>(&filter)) {
    shading.matrix((*form)(inputs));
  } else if (const AxisFilter* form = std::get_if<AxisFilter>(&filter)) {
    shading.axis((*form)(inputs));
  } else if (const IsotropicFilter* form = std::get_if<IsotropicFilter>(&filter)) {
    shading.isotropic_form([&](double unfiltered) { return (*form)(inputs, unfiltered); });
  } else {
    throw std::invalid_argument("shade_pixel: unknown variant");
  }
}

}  // namespace

PixelShade shade_pixel(const GBuffer& gbuffer, int x, int y, Variant variant, const Material& material, const ref::Params& params,
                       ref::Derivative mode, NormalFeed feed, Prefilter prefilter, double prefilter_scale, Lobe lobe) {
  const PixelFields& own = gbuffer.at(x, y);
  std::optional<PixelFields> band;
  if (prefilter != Prefilter::none && own.has_footprint_moments) band = band_limited_fields(own);
  const PixelFields& f = band ? *band : own;
  PixelShade out;
  if (!f.hit) return out;
  const double alpha = material.alpha * f.alpha_scale;
  LobeShading shading(f, variant, alpha, params, prefilter, prefilter_scale, lobe);
  if (variant == Variant::none) {
    shading.isotropic_form([](double unfiltered) { return unfiltered; });
  } else {
    std::optional<QuadFields> gathered;
    const QuadFields& q = quad_fields(gbuffer, x, y, gathered);
    if (is_engine(variant)) {
      shade_engine(shading, variant, alpha, q, f, mode);
    } else {
      const FeedQuads in = feed_quads(q, feed);
      shade_filter(shading, variant, FilterInputs{params, shading.alpha2(), shading.a2(), in, q, f, mode, lobe});
    }
  }
  out.roughness = shading.roughness();
  out.radiance = f.weight * specular_radiance(shading.brdf(), f.light_ts, f.view_ts, f.irradiance, material.fresnel);
  if (f.coat > 0.0) out.radiance *= 1.0 - f.coat * schlick_fresnel(dot(f.light_ts, normalize(f.light_ts + f.view_ts)));
  return out;
}

Image render_variant(const GBuffer& gbuffer, Variant variant, const Material& material, const ref::Params& params, ref::Derivative mode,
                     int threads, NormalFeed feed, Prefilter prefilter, double prefilter_scale, Lobe lobe) {
  Image image(gbuffer.width, gbuffer.height);
  parallel_rows(gbuffer.height, threads, [&](int y) {
    for (int x = 0; x < gbuffer.width; ++x)
      image.at(x, y) =
          static_cast<float>(shade_pixel(gbuffer, x, y, variant, material, params, mode, feed, prefilter, prefilter_scale, lobe).radiance);
  });
  return image;
}

}  // namespace saagen::measure

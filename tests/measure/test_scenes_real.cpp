// Tests of the "real content" scenes (measure/src): the triangle mesh and its BVH, the
// torus-knot tube's interpolated normals against the analytic tube, the geometric and shading
// frames of every hit, the normal-mapped sphere's ground-truth normals (level-0 bilinear through
// the TBN) and its 1-spp texture sampling (coarse quad uv derivatives, implicit LOD, helper
// partners extrapolated on the tangent plane), and the feature sizes and LODs documented in
// scene.hpp; the built-in scenes' table (lists, names, normal detail).
//
// Runtime: G-buffers at the base 256 x 256 view of the unit sphere cost ~4 ray casts per pixel,
// the ground-truth smoke renders are 16 x 16 x 16 spp; the binary runs in a few seconds.
#include "saagen/measure/render.hpp"
#include "saagen/reference/brdf.hpp"
#include "saagen/reference/prefilter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace saagen::measure;
namespace ref = saagen::ref;
using ref::Vec2;
using ref::Vec3;

namespace {

constexpr double kPi = ref::kPi;

double angle_between(Vec3 a, Vec3 b) { return std::atan2(ref::length(ref::cross(a, b)), ref::dot(a, b)); }

// Orthonormal, right-handed (b = n x t) frame.
void expect_frame(Vec3 n, Vec3 t, Vec3 b, const std::string& what, double tol = 1e-12) {
  EXPECT_NEAR(ref::length(n), 1.0, tol) << what;
  EXPECT_NEAR(ref::length(t), 1.0, tol) << what;
  EXPECT_NEAR(ref::dot(n, t), 0.0, tol) << what;
  EXPECT_LT(ref::length(b - ref::cross(n, t)), tol) << what;
}

// The sphere's uv (scene.hpp) at a point of the unit sphere, times the tiling.
Vec2 sphere_uv(Vec3 p, Vec2 tiling) { return tiling * Vec2{std::atan2(p.x, p.z) / (2.0 * kPi) + 0.5, 1.0 - std::acos(p.y) / kPi}; }

// The analytic first hit of a ray with the unit sphere at the origin (the unrotated nmap
// scenes); false on a miss.
bool unit_sphere_hit(const Ray& r, Vec3& p) {
  const double b = ref::dot(r.origin, r.direction);
  const double c = ref::dot(r.origin, r.origin) - 1.0;
  const double disc = b * b - c;
  if (disc < 0.0) return false;
  p = r.origin + (-b - std::sqrt(disc)) * r.direction;
  return true;
}

// Texture uv seen through film position (fx, fy) of a size x size view of an nmap scene.
Vec2 film_uv(const Scene& scene, double fx, double fy, int size) {
  Vec3 p;
  EXPECT_TRUE(unit_sphere_hit(scene.camera().generate(fx, fy, size, size), p));
  return sphere_uv(p, scene.uv_tiling());
}

// log2 of the analytic texel footprint at film position (fx, fy): rho = max(|d(uv size)/dx|,
// |d(uv size)/dy|) (Vulkan's isotropic rho) with the derivatives of the exact film -> uv map
// taken by central differences (step 1e-3 px: truncation error ~1e-7 of the derivative).
double analytic_lod(const Scene& scene, double fx, double fy, int size) {
  const double e = 1e-3;
  const double texels = kContentNormalMapSize;
  const Vec2 dx = (film_uv(scene, fx + e, fy, size) - film_uv(scene, fx - e, fy, size)) / (2.0 * e);
  const Vec2 dy = (film_uv(scene, fx, fy + e, size) - film_uv(scene, fx, fy - e, size)) / (2.0 * e);
  return std::log2(std::max(ref::length(dx) * texels, ref::length(dy) * texels));
}

// Bound of the linear-interpolation error over a triangle of parameter legs (hu, hv) for a
// function with second-derivative norms (fuu, fuv, fvv): f(x) - I f(x) = -1/2 sum_i l_i
// (x_i - x)^T H (x_i - x) for the barycentrics l_i, and sum_i l_i (u_i - x_u)^2 <= hu^2 / 4 (the
// l-weighted variance of values in an interval of length hu), likewise for v and, by
// Cauchy-Schwarz, sum_i l_i |du_i dv_i| <= hu hv / 4. So |e| <= (fuu hu^2 + 2 fuv hu hv +
// fvv hv^2) / 8.
double interpolation_bound(double fuu, double fuv, double fvv, double hu, double hv) {
  return (fuu * hu * hu + 2.0 * fuv * hu * hv + fvv * hv * hv) / 8.0;
}

// Largest second-derivative norms of a vector field of (u, v) over the unit square, by central
// differences on a grid (step h; sampled every `stride` vertices of a fine grid).
template <class F>
void max_second_derivatives(F&& f, double& fuu, double& fuv, double& fvv) {
  const double h = 1e-4;
  fuu = fuv = fvv = 0.0;
  for (int i = 0; i < 2048; ++i)
    for (int j = 0; j < 48; ++j) {
      const Vec2 x{(i + 0.5) / 2048.0, (j + 0.5) / 48.0};
      const Vec3 c = f(x);
      const Vec3 uu = (f(x + Vec2{h, 0.0}) - 2.0 * c + f(x - Vec2{h, 0.0})) / (h * h);
      const Vec3 vv = (f(x + Vec2{0.0, h}) - 2.0 * c + f(x - Vec2{0.0, h})) / (h * h);
      const Vec3 uv = (f(x + Vec2{h, h}) - f(x + Vec2{h, -h}) - f(x + Vec2{-h, h}) + f(x + Vec2{-h, -h})) / (4.0 * h * h);
      fuu = std::max(fuu, ref::length(uu));
      fuv = std::max(fuv, ref::length(uv));
      fvv = std::max(fvv, ref::length(vv));
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Mesh and BVH

// The BVH must return exactly the brute-force nearest hit (same triangle, same t, same uv) for
// rays aimed at random points of the knot's bounding box from random directions, and agree on
// misses.
TEST(Mesh, BvhEqualsBruteForce) {
  const TriangleMesh& mesh = *content_torus_knot_mesh();
  EXPECT_EQ(mesh.triangles().size(), 2u * 512u * 24u);
  EXPECT_LE(mesh.bvh_depth(), 20);  // SAH splits of 24576 triangles into leaves of <= 8 (mesh.hpp)
  Rng rng(12345);
  int hits = 0;
  const int n_rays = 3000;
  for (int i = 0; i < n_rays; ++i) {
    // Origin on a sphere of radius 4, target uniform in [-1.7, 1.7]^2 x [-0.7, 0.7].
    const double z = 2.0 * rng.next_double() - 1.0, phi = 2.0 * kPi * rng.next_double();
    const double s = std::sqrt(1.0 - z * z);
    const Vec3 origin = 4.0 * Vec3{s * std::cos(phi), s * std::sin(phi), z};
    const Vec3 target{3.4 * rng.next_double() - 1.7, 3.4 * rng.next_double() - 1.7, 1.4 * rng.next_double() - 0.7};
    const Ray ray{origin, ref::normalize(target - origin)};
    SurfaceHit a, b;
    const bool hit_a = mesh.intersect(ray, 0.0, a);
    const bool hit_b = mesh.intersect_brute_force(ray, 0.0, b);
    ASSERT_EQ(hit_a, hit_b) << "ray " << i;
    if (!hit_a) continue;
    ++hits;
    EXPECT_EQ(a.t, b.t) << "ray " << i;
    EXPECT_EQ(a.uv, b.uv) << "ray " << i;
    EXPECT_EQ(a.normal, b.normal) << "ray " << i;
  }
  std::printf("BVH vs brute force: %d rays, %d hits\n", n_rays, hits);
  EXPECT_GT(hits, n_rays / 5);  // the comparison must cover many hits, not just misses
}

// Interpolated normals and positions against the analytic tube at the same (interpolated) uv,
// within the linear-interpolation bound above: legs hu = 1/512, hv = 1/24, second derivatives
// of the analytic normal and surface measured on a grid (1.05 x for the finite differences).
// The normal error e of the interpolated vector turns into an angle <= |e| / (1 - |e|) after
// normalisation. Vertex normals and tangents must be the analytic ones (rounding only).
TEST(Mesh, KnotNormalsMatchAnalyticTube) {
  const TorusKnot& knot = content_torus_knot();
  const TriangleMesh& mesh = *content_torus_knot_mesh();
  for (const MeshVertex& v : mesh.vertices()) {
    const Vec2 uv{std::fmod(v.uv.x, 1.0), std::fmod(v.uv.y, 1.0)};
    ASSERT_LT(ref::length(v.normal - knot.normal(uv)), 1e-14);
    ASSERT_LT(ref::length(v.tangent - knot.tangent(uv)), 1e-14);
    ASSERT_LT(std::fabs(ref::dot(v.normal, v.tangent)), 1e-14);  // T is orthogonal to N1, N2
  }

  double nuu, nuv, nvv, suu, suv, svv;
  max_second_derivatives([&](Vec2 uv) { return knot.normal(uv); }, nuu, nuv, nvv);
  max_second_derivatives([&](Vec2 uv) { return knot.point(uv); }, suu, suv, svv);
  // n turns by 2 pi per unit v in the plane normal to T: |n_vv| = (2 pi)^2.
  EXPECT_NEAR(nvv, 4.0 * kPi * kPi, 1e-3 * 4.0 * kPi * kPi);
  const double hu = 1.0 / knot.segments, hv = 1.0 / knot.sides;
  const double e_normal = 1.05 * interpolation_bound(nuu, nuv, nvv, hu, hv);
  const double angle_bound = e_normal / (1.0 - e_normal);
  const double position_bound = 1.05 * interpolation_bound(suu, suv, svv, hu, hv);

  Rng rng(777);
  double worst_angle = 0.0, worst_distance = 0.0;
  const Ray dummy{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  for (int i = 0; i < 20000; ++i) {
    const int tri = static_cast<int>(rng.next_double() * mesh.triangles().size());
    double b1 = rng.next_double(), b2 = rng.next_double();
    if (b1 + b2 > 1.0) {
      b1 = 1.0 - b1;
      b2 = 1.0 - b2;
    }
    SurfaceHit hit;
    mesh.fill_hit(tri, dummy, 0.0, b1, b2, hit);
    const auto& t = mesh.triangles()[tri];
    const Vec3 x =
        (1.0 - b1 - b2) * mesh.vertices()[t[0]].position + b1 * mesh.vertices()[t[1]].position + b2 * mesh.vertices()[t[2]].position;
    worst_angle = std::max(worst_angle, angle_between(hit.normal, knot.normal(hit.uv)));
    worst_distance = std::max(worst_distance, ref::length(x - knot.point(hit.uv)));
    expect_frame(hit.normal, hit.tangent, hit.bitangent, "mesh hit frame");
  }
  std::printf(
      "knot: |n_uu| %.1f |n_uv| %.1f |n_vv| %.2f -> normal bound %.5f rad, worst %.5f; "
      "position bound %.5f, worst %.5f\n",
      nuu, nuv, nvv, angle_bound, worst_angle, position_bound, worst_distance);
  EXPECT_LT(worst_angle, angle_bound);
  EXPECT_LT(worst_distance, position_bound);
  // The bound must be tight enough to mean something: the tube's 24 sides alone give
  // (2 pi / 24)^2 / 8 = 0.0086 rad. The observed error sits well below it because |n_vv| =
  // (2 pi)^2 points along -n, and renormalisation removes that part of the interpolation
  // error (nlerp between two unit normals stays on their great circle), but not 10x below.
  EXPECT_LT(angle_bound, 0.02);
  EXPECT_GT(worst_angle, 0.1 * angle_bound);
}

// ---------------------------------------------------------------------------------------------
// Frames

// Every hit of every content scene (and the bump plane) carries two orthonormal right-handed
// frames; the geometric frame of the sphere, torus, tubes and mesh equals the shading frame; the
// bump plane's is the plane's; a normal-mapped hit's geometric tangent is dpdu made orthogonal
// to the geometric normal, dpdu x dpdv is along the geometric normal, and the shading normal
// tilts by no more than the map's largest tilt (30 degrees by the slope bound).
TEST(Frames, GeometricAndShadingFramesAreOrthonormal) {
  std::vector<SceneId> ids{content_scenes().begin(), content_scenes().end()};
  ids.insert(ids.end(), all_scenes().begin(), all_scenes().end());
  const int size = 48;
  for (SceneId id : ids) {
    const Scene scene = make_scene(id, 0.05);
    const std::string name(scene_name(id));
    int hits = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        SurfaceHit h;
        if (!scene.intersect(scene.camera().generate(x + 0.5, y + 0.5, size, size), h)) continue;
        ++hits;
        expect_frame(h.normal, h.tangent, h.bitangent, name + " shading");
        expect_frame(h.geometric_normal, h.geometric_tangent, h.geometric_bitangent, name + " geometric");
        const Vec3 plane = ref::cross(h.dpdu, h.dpdv);
        if (id == SceneId::bump_plane) {
          EXPECT_LT(ref::length(h.geometric_normal - Vec3{0.0, 1.0, 0.0}), 1e-15);
        } else if (scene.normal_map()) {
          const Vec3 n = h.geometric_normal;
          const Vec3 t = ref::normalize(h.dpdu - ref::dot(h.dpdu, n) * n);
          EXPECT_LT(ref::length(h.geometric_tangent - t), 1e-14) << name;
          EXPECT_EQ(h.bitangent_sign, 1.0) << name;
          EXPECT_LT(angle_between(h.normal, h.geometric_normal), 30.0 * kPi / 180.0) << name;
        } else {
          EXPECT_EQ(h.geometric_normal, h.normal) << name;
          EXPECT_EQ(h.geometric_tangent, h.tangent) << name;
        }
        // The analytic shapes' dpdu x dpdv is along the normal (up to sign);
        // a mesh's is the face normal, within the tessellation angle of the vertex normal.
        const double tilt = std::asin(std::min(1.0, ref::length(ref::cross(ref::normalize(plane), h.geometric_normal))));
        EXPECT_LT(tilt, id == SceneId::torus_knot ? 0.2 : 1e-9) << name;
      }
    EXPECT_GT(hits, size * size / 5) << name;
  }
}

// ---------------------------------------------------------------------------------------------
// Normal-mapped sphere: ground truth

// The ground truth's shading normal (Scene::intersect) is the level-0 bilinear map normal at
// the hit's uv taken through the analytic TBN of the sphere: t = normalize(dpdu) = (z, 0, -x) /
// rho, b = n x t (v grows upwards, so the bitangent sign is +1). At a uv chosen on a texel
// centre the bilinear sample is that texel's normal.
TEST(NormalMapped, GroundTruthNormalIsLevel0Bilinear) {
  const Scene scene = make_scene(SceneId::nmap_sphere);
  const NormalMap& map = *scene.normal_map();
  const int texels = kContentNormalMapSize;
  // Texel (700, 260) of the tiled texture: uv = ((700.5, 260.5) / 512), u / 2 and v in the
  // sphere's own parameterisation; its point p(u, v) on the unit sphere.
  const Vec2 texel_uv{700.5 / texels, 260.5 / texels};
  const double phi = 2.0 * kPi * (texel_uv.x / 2.0 - 0.5), theta = kPi * (1.0 - texel_uv.y);
  const Vec3 p{std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)};
  const Ray ray{scene.camera().position, ref::normalize(p - scene.camera().position)};
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(ray, hit));
  EXPECT_LT(ref::length(hit.position - p), 1e-12);
  EXPECT_NEAR(hit.uv.x, texel_uv.x, 1e-12);
  EXPECT_NEAR(hit.uv.y, texel_uv.y, 1e-12);
  EXPECT_EQ(hit.bitangent_sign, 1.0);

  const Vec3 n = p;
  const Vec3 t = ref::normalize(Vec3{p.z, 0.0, -p.x});
  const Vec3 b = ref::cross(n, t);
  auto tbn = [&](Vec3 m) { return ref::normalize(m.x * t + m.y * b + m.z * n); };
  const Vec3 expected = tbn(ref::normalize(map.bilinear(0, hit.uv).normal));
  EXPECT_LT(angle_between(hit.normal, expected), 1e-12);
  // On the texel centre the bilinear weights are (1, 0, 0, 0) up to |uv error| * 512 ~ 1e-9.
  EXPECT_LT(angle_between(hit.normal, tbn(map.texel(0, 700, 260).normal)), 1e-8);
  // The map tilts that normal away from the geometric one (it is not a no-op).
  EXPECT_GT(angle_between(hit.normal, hit.geometric_normal), 1e-3);
  expect_frame(hit.normal, hit.tangent, hit.bitangent, "mapped frame");

  // intersect_surface gives the unmapped hit.
  SurfaceHit base;
  ASSERT_TRUE(scene.intersect_surface(ray, base));
  EXPECT_EQ(base.normal, hit.geometric_normal);
  EXPECT_EQ(base.uv, hit.uv);
}

// ---------------------------------------------------------------------------------------------
// Normal-mapped sphere: 1 spp

// The 1-spp LOD at interior pixels equals log2 of the analytic texel footprint at the pixel
// centre. Tolerance: the coarse difference uv(p1) - uv(p0) is the mean of the exact derivative
// over the segment p0 -> p1 (and likewise for ddy), so it differs from the derivative at the
// shaded pixel by at most the derivative's variation over the quad: 1.5 x the spread of the
// analytic LOD over the quad's four centres (1.5 for the curvature within the quad) + 1e-6.
TEST(NormalMapped, OneSppLodIsLog2OfAnalyticFootprint) {
  const int size = 256;
  for (SceneId id : {SceneId::nmap_sphere, SceneId::nmap_sphere_fine}) {
    const Scene scene = make_scene(id);
    const GBuffer g = render_gbuffer(scene, size, size, 2);
    Rng rng(99);
    int checked = 0;
    double worst = 0.0;
    for (int i = 0; i < 400; ++i) {
      const int x = 40 + static_cast<int>(rng.next_double() * 176);
      const int y = 40 + static_cast<int>(rng.next_double() * 176);
      const int x0 = x & ~1, y0 = y & ~1;
      bool quad_on_sphere = true;
      for (int q = 0; q < 4; ++q) quad_on_sphere = quad_on_sphere && g.at(x0 + (q & 1), y0 + q / 2).hit;
      // Stay away from the rim, where the footprint changes by octaves across a quad.
      const double r = std::hypot(x + 0.5 - size / 2.0, y + 0.5 - size / 2.0);
      if (!quad_on_sphere || r > 80.0) continue;
      const PixelFields& f = g.at(x, y);
      ASSERT_TRUE(f.has_normal_map);
      const double expected = analytic_lod(scene, x + 0.5, y + 0.5, size);
      double spread = 0.0;
      for (int q = 0; q < 4; ++q)
        spread = std::max(spread, std::fabs(analytic_lod(scene, x0 + (q & 1) + 0.5, y0 + q / 2 + 0.5, size) - expected));
      const double tol = 1.5 * spread + 1e-6;
      EXPECT_NEAR(f.lod, expected, tol) << scene_name(id) << " pixel " << x << "," << y;
      worst = std::max(worst, std::fabs(f.lod - expected) / tol);
      ++checked;
    }
    std::printf("%s: %d pixels, worst |lod - analytic| / tolerance %.3f\n", std::string(scene_name(id)).c_str(), checked, worst);
    EXPECT_GT(checked, 150);
  }
}

// Quad partners off the sphere take the uv of the tangent-plane extrapolation: the partner's
// ray meets the plane through the shaded point p with normal p at X, and on the unit sphere
// dpdu and dpdv are orthogonal, so uv = uv(p) + ((X - p) . dpdu / |dpdu|^2, (X - p) . dpdv /
// |dpdv|^2) with dpdu = 2 pi (z, 0, -x) / tiling.x and dpdv = pi (-y x / rho, rho, -y z / rho) /
// tiling.y. Checked on every rim pixel whose quad has a partner that misses, through the stored
// coarse derivatives.
TEST(NormalMapped, QuadPartnerExtrapolationIsTangentPlane) {
  const int size = 64;
  const Scene scene = make_scene(SceneId::nmap_sphere);
  const Vec2 tiling = scene.uv_tiling();
  const GBuffer g = render_gbuffer(scene, size, size, 2);
  int checked = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const PixelFields& f = g.at(x, y);
      if (!f.hit) continue;
      const int x0 = x & ~1, y0 = y & ~1;
      bool partner_missing = false;
      for (int q = 0; q < 3; ++q) partner_missing = partner_missing || !g.at(x0 + (q & 1), y0 + q / 2).hit;
      if (!partner_missing) continue;
      const Vec3 p = f.position;
      const double rho = std::hypot(p.x, p.z);
      const Vec3 dpdu = (2.0 * kPi / tiling.x) * Vec3{p.z, 0.0, -p.x};
      const Vec3 dpdv = (kPi / tiling.y) * Vec3{-p.y * p.x / rho, rho, -p.y * p.z / rho};
      auto uv_of = [&](int px, int py) {
        const Ray r = scene.camera().generate(px + 0.5, py + 0.5, size, size);
        Vec3 hit_point;
        if (unit_sphere_hit(r, hit_point)) return sphere_uv(hit_point, tiling);
        const double t = ref::dot(p - r.origin, p) / ref::dot(r.direction, p);
        const Vec3 d = r.origin + t * r.direction - p;
        return sphere_uv(p, tiling) + Vec2{ref::dot(d, dpdu) / ref::dot(dpdu, dpdu), ref::dot(d, dpdv) / ref::dot(dpdv, dpdv)};
      };
      const Vec2 uv0 = uv_of(x0, y0);
      const Vec2 ddx = uv_of(x0 + 1, y0) - uv0, ddy = uv_of(x0, y0 + 1) - uv0;
      const double scale = std::max(ref::length(ddx), ref::length(ddy));
      EXPECT_LT(ref::length(f.duv_dx - ddx), 1e-9 * (1.0 + scale)) << x << "," << y;
      EXPECT_LT(ref::length(f.duv_dy - ddy), 1e-9 * (1.0 + scale)) << x << "," << y;
      ++checked;
    }
  std::printf("rim quads with a missing partner checked: %d\n", checked);
  EXPECT_GT(checked, 40);

  // The function itself, on a hit and an explicit ray past the sphere.
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect_surface(scene.camera().generate(32.5, 5.5, size, size), hit));
  const Ray past = scene.camera().generate(32.5, 2.5, size, size);
  const Vec3 p = hit.position;
  const double t = ref::dot(p - past.origin, p) / ref::dot(past.direction, p);
  const Vec3 d = past.origin + t * past.direction - p;
  const Vec2 expected =
      hit.uv + Vec2{ref::dot(d, hit.dpdu) / ref::dot(hit.dpdu, hit.dpdu), ref::dot(d, hit.dpdv) / ref::dot(hit.dpdv, hit.dpdv)};
  const Vec2 got = tangent_plane_uv(hit, past);
  EXPECT_NEAR(got.x, expected.x, 1e-12);
  EXPECT_NEAR(got.y, expected.y, 1e-12);
  EXPECT_GT(ref::length(got - hit.uv), 1e-3);
}

// The 1-spp shading normal is the renormalised trilinear sample at (uv, lod) through the TBN,
// and the stored texel is that sample; the fields' geometric half vector is the half vector in
// the geometric frame.
TEST(NormalMapped, OneSppFieldsAreTheTrilinearSample) {
  const int size = 64;
  const Scene scene = make_scene(SceneId::nmap_sphere_fine);
  const NormalMap& map = *scene.normal_map();
  const PixelFields f = pixel_fields(scene, 30, 27, size, size);
  ASSERT_TRUE(f.hit && f.has_normal_map);
  EXPECT_EQ(f.lod, map.lod(f.duv_dx, f.duv_dy));
  const NormalTexel texel = map.trilinear(f.uv, f.lod);
  EXPECT_EQ(f.texel.normal, texel.normal);
  EXPECT_EQ(f.texel.slope_second, texel.slope_second);
  SurfaceHit expected;
  ASSERT_TRUE(scene.intersect_surface(scene.camera().generate(30.5, 27.5, size, size), expected));
  Scene::apply_normal_map(expected, ref::normalize(texel.normal));
  EXPECT_EQ(f.normal, expected.normal);
  const Vec3 h = ref::normalize(f.to_light + f.to_view);
  EXPECT_NEAR(f.geometric_half_ts.z, ref::dot(h, f.geometric_normal), 1e-14);
  EXPECT_NEAR(f.geometric_half_ts.x, ref::dot(h, f.geometric_tangent), 1e-14);
  EXPECT_NEAR(f.half_ts.z, ref::dot(h, f.normal), 1e-14);
  // Minified: the prefiltered texel's mean normal is shorter than 1 (Toksvig).
  EXPECT_LT(ref::length(f.texel.mean_normal), 0.995);

  // A scene without a map keeps geometric == shading and no texture fields.
  const PixelFields plain = pixel_fields(make_scene(SceneId::sphere), 30, 27, size, size);
  ASSERT_TRUE(plain.hit);
  EXPECT_FALSE(plain.has_normal_map);
  EXPECT_EQ(plain.geometric_half_ts, plain.half_ts);
  EXPECT_EQ(plain.lod, 0.0);
}

// Procedural bumps (the bump plane, renderer.hpp PixelFields::has_footprint_moments): the 1-spp
// fields hold the closed-form slope moments of the pixel filter's footprint through the quad's
// coarse uv derivatives; a prefiltered row shades the band-limited normal normalize(-E[s], 1) with
// LEAN's covariance added to alpha^2, every other row the unfiltered normal at the centre. Equal
// up to rounding (1e-12 relative: the same operations in another order), exactly where nothing is
// recomputed.
TEST(ProceduralBumps, PrefilteredRowsShadeTheBandLimitedNormal) {
  const int size = 64;
  const Scene scene = make_scene(SceneId::bump_plane);
  const ref::Params params{};
  const Material material{0.05, false};
  const double a2 = material.alpha * material.alpha;
  const GBuffer gbuffer = render_gbuffer(scene, size, size, 1);
  int checked = 0;
  for (const auto& [x, y] : {std::pair{30, 27}, std::pair{41, 18}, std::pair{12, 50}}) {
    const PixelFields& f = gbuffer.at(x, y);
    ASSERT_TRUE(f.hit && f.has_footprint_moments && !f.has_normal_map);
    SurfaceHit centre;
    ASSERT_TRUE(scene.intersect_surface(scene.camera().generate(x + 0.5, y + 0.5, size, size), centre));
    const UvDerivatives d = coarse_uv_derivatives(scene, centre, x, y, size, size);
    EXPECT_EQ(f.duv_dx, d.ddx);
    EXPECT_EQ(f.duv_dy, d.ddy);
    const SlopeMoments m = *scene.footprint_slope_moments(centre, uv_footprint(default_pixel_filter().variance(), d.ddx, d.ddy));
    EXPECT_EQ(f.texel.slope_mean, m.mean);
    EXPECT_EQ(f.texel.slope_second, m.second);
    // The unfiltered normal is the analytic one at the centre; the band-limited one is E[s]'s.
    EXPECT_EQ(f.normal, centre.normal);
    SurfaceHit band = centre;
    Scene::apply_normal_map(band, ref::normalize(Vec3{-m.mean.x, -m.mean.y, 1.0}));
    EXPECT_EQ(f.band_limited.normal, band.normal);

    // none: GGX at alpha^2 on the centre's vectors; none+lean: alpha^2 + tr(2 Sigma) / 2 on the band-limited ones.
    const PixelShade plain = shade_pixel(gbuffer, x, y, Variant::none, material, params);
    EXPECT_EQ(plain.roughness.xx, a2);
    EXPECT_DOUBLE_EQ(plain.radiance,
                     specular_radiance(ref::ggx_brdf_axis(f.light_ts, f.view_ts, {a2, a2}), f.light_ts, f.view_ts, f.irradiance, false));
    const ref::Sym2 texture = 2.0 * ref::lean_covariance(params, m.mean, m.second);
    EXPECT_GT(ref::trace(texture), 0.0);
    const PixelShade lean =
        shade_pixel(gbuffer, x, y, Variant::none, material, params, ref::Derivative::coarse, NormalFeed::shading, Prefilter::lean);
    const double filtered = ref::saturate(a2 + 0.5 * ref::trace(texture));
    EXPECT_NEAR(lean.roughness.xx, filtered, 1e-12 * filtered);
    const ShadingFrame& b = f.band_limited;
    const double expected =
        specular_radiance(ref::ggx_brdf_axis(b.light_ts, b.view_ts, {filtered, filtered}), b.light_ts, b.view_ts, f.irradiance, false);
    EXPECT_NEAR(lean.radiance, expected, 1e-12 * std::max(expected, 1e-300));
    // The matrix form takes the full covariance: A - (its geometric-feed kernel alone) = 2 Sigma.
    const PixelShade matrix = shade_pixel(gbuffer, x, y, Variant::forward_aniso_projected, material, params, ref::Derivative::coarse,
                                          NormalFeed::geometric, Prefilter::lean, 1.0, Lobe::tail);
    const PixelShade kernel_only = shade_pixel(gbuffer, x, y, Variant::forward_aniso_projected, material, params, ref::Derivative::coarse,
                                               NormalFeed::geometric, Prefilter::none, 1.0, Lobe::tail);
    EXPECT_NEAR(matrix.roughness.xy - kernel_only.roughness.xy, texture.xy, 1e-12);
    EXPECT_NEAR(matrix.roughness.xx - kernel_only.roughness.xx, texture.xx, 1e-12);
    // Only LEAN's moments exist in closed form: a Toksvig-family row is refused.
    EXPECT_THROW(
        shade_pixel(gbuffer, x, y, Variant::none, material, params, ref::Derivative::coarse, NormalFeed::shading, Prefilter::toksvig),
        std::invalid_argument);
    ++checked;
  }
  EXPECT_EQ(checked, 3);
  // Scenes without procedural detail have no footprint moments.
  EXPECT_FALSE(pixel_fields(make_scene(SceneId::sphere), 30, 27, size, size).has_footprint_moments);
  EXPECT_FALSE(pixel_fields(make_scene(SceneId::nmap_sphere), 30, 27, size, size).has_footprint_moments);
}

// The emitted deferred-aniso pass with a texture covariance (templates/20-deferred.saa:
// deferred_aniso_covariance in the geometry pass, _brdf_with_covariance in the lighting pass)
// against the trade's deferred-aniso rows with LEAN and the tail-preserving lobe.
// The pass works in the frame (t', b') built from the normal the G-buffer stores; the renderer in
// the pixel's shading frame (t, b): A_pixel = Q A Q^T, Q = [t.t' t.b'; b.t' b.b'].
namespace {

ref::Sym2 to_pixel_frame(const ref::Sym2& a, Vec3 frame_normal, Vec3 tangent, Vec3 bitangent) {
  const Vec3 tf = ref::normal_frame_tangent(frame_normal), bf = ref::normal_frame_bitangent(frame_normal);
  const double q00 = ref::dot(tangent, tf), q01 = ref::dot(tangent, bf), q10 = ref::dot(bitangent, tf), q11 = ref::dot(bitangent, bf);
  const double r0x = q00 * a.xx + q01 * a.xy, r0y = q00 * a.xy + q01 * a.yy;
  const double r1x = q10 * a.xx + q11 * a.xy, r1y = q10 * a.xy + q11 * a.yy;
  return {r0x * q00 + r0y * q01, r0x * q10 + r0y * q11, r1x * q10 + r1y * q11};
}

void expect_sym2_near(const ref::Sym2& got, const ref::Sym2& want, double tolerance) {
  EXPECT_NEAR(got.xx, want.xx, tolerance);
  EXPECT_NEAR(got.xy, want.xy, tolerance);
  EXPECT_NEAR(got.yy, want.yy, tolerance);
}

}  // namespace

// The covariance in the frame built from n: R (2 Sigma) R^T, for texture frames turned about n by
// any angle and mirrored. Carried back, it is 2 Sigma; a quarter turn swaps the variances.
TEST(DeferredAnisoCovariance, CovarianceIsCarriedIntoTheFrameBuiltFromTheNormal) {
  const ref::Params params{};
  const Vec2 mean{0.2, -0.1};
  const ref::Sym2 sigma{0.04, 0.015, 0.01};
  const ref::Sym2 second = sigma + ref::Sym2{mean.x * mean.x, mean.x * mean.y, mean.y * mean.y};
  const ref::Sym2 texture = 2.0 * ref::lean_covariance(params, mean, second);
  for (const Vec3 n : {Vec3{0.0, 0.0, 1.0}, ref::normalize(Vec3{0.3, -0.5, 0.8}), ref::normalize(Vec3{-0.7, 0.1, -0.6})}) {
    const Vec3 t0 = ref::normal_frame_tangent(n), b0 = ref::normal_frame_bitangent(n);
    for (const double angle : {0.0, 0.4, 1.3, 2.9})
      for (const double sign : {1.0, -1.0}) {
        const Vec3 t = std::cos(angle) * t0 + std::sin(angle) * b0, b = sign * ref::cross(n, t);
        const ref::Sym2 c = ref::deferred_aniso_covariance(params, mean, second, t, b, n);
        expect_sym2_near(to_pixel_frame(c, n, t, b), texture, 1e-15);
      }
    // t = b0, b = n x b0 = -t0: R = [0 -1; 1 0], C = (S11, -S01, S00).
    const ref::Sym2 quarter = ref::deferred_aniso_covariance(params, mean, second, b0, -1.0 * t0, n);
    expect_sym2_near(quarter, {texture.yy, -texture.xy, texture.xx}, 1e-15);
  }
}

// Normal-mapped sphere, shading feed (the G-buffer's normal is the mapped one, and so is the
// normal the kernel measures): the whole roughness matrix and the BRDF of the emitted pass are
// the row's, to double rounding.
TEST(DeferredAnisoCovariance, EmittedPassIsTheLeanRowOnANormalMap) {
  const int size = 64;
  const GBuffer gbuffer = render_gbuffer(make_scene(SceneId::nmap_sphere), size, size, 1);
  const ref::Params params{};
  const Material material{0.05, false};
  const double a2 = material.alpha * material.alpha;
  int checked = 0;
  // Every 7th pixel of every 7th row on the sphere (its tangent frame and the frame built from n
  // are a few degrees apart here: CovarianceIsCarriedIntoTheFrameBuiltFromTheNormal turns them).
  for (int y = 3; y < size; y += 7)
    for (int x = 3; x < size; x += 7) {
      const PixelFields& f = gbuffer.at(x, y);
      if (!f.hit) continue;
      ASSERT_TRUE(f.has_normal_map);
      const PixelShade row = shade_pixel(gbuffer, x, y, Variant::deferred_aniso, material, params, ref::Derivative::coarse,
                                         NormalFeed::shading, Prefilter::lean, 1.0, Lobe::tail);
      const QuadFields q = gather_quad(gbuffer, x, y);
      const ref::Sym2 tensor = ref::deferred_aniso_fragment_quad(params, q.normal, q.pixel);
      const ref::Sym2 covariance =
          ref::deferred_aniso_covariance(params, f.texel.slope_mean, f.texel.slope_second, f.tangent, f.bitangent, f.normal);
      EXPECT_GT(ref::trace(covariance), 0.0);
      // The tail lobe's row: A = diag(alpha^2) + K + C (deferred_aniso_tail_roughness).
      const ref::Sym2 a = ref::deferred_aniso_tail_roughness(tensor + covariance, a2);
      const double scale = ref::trace(row.roughness);
      expect_sym2_near(to_pixel_frame(a, f.normal, f.tangent, f.bitangent), row.roughness, 1e-12 * scale);
      const double brdf = ref::ggx_brdf_filtered_matrix(f.light_ts, f.view_ts, row.roughness, {a2, a2});
      const double emitted = ref::deferred_aniso_brdf_with_covariance(params, f.to_light, f.to_view, f.normal, tensor, covariance, a2);
      EXPECT_NEAR(emitted, brdf, 1e-9 * std::max(brdf, 1e-300));
      ++checked;
    }
  EXPECT_GT(checked, 20);
}

// The bump plane's deferred-aniso:geometric+lean row (the trade's best deferred configuration
// there): its texture term 2 Sigma (LEAN's covariance of the footprint moments, in the
// band-limited normal's shading frame) is the emitted covariance carried back into that frame,
// and the rest of its A is the geometric normal's kernel, as deferred_aniso_tail_roughness gives it.
TEST(DeferredAnisoCovariance, EmittedCovarianceIsTheBandLimitedRowsTextureTerm) {
  const int size = 64;
  const GBuffer gbuffer = render_gbuffer(make_scene(SceneId::bump_plane), size, size, 1);
  const ref::Params params{};
  const Material material{0.05, false};
  const double a2 = material.alpha * material.alpha;
  int checked = 0;
  for (const auto& [x, y] : {std::pair{30, 27}, std::pair{41, 18}, std::pair{12, 50}}) {
    const PixelFields& f = gbuffer.at(x, y);
    ASSERT_TRUE(f.hit && f.has_footprint_moments);
    const ShadingFrame& band = f.band_limited;
    const ref::Sym2 texture = 2.0 * ref::lean_covariance(params, f.texel.slope_mean, f.texel.slope_second);
    const ref::Sym2 covariance =
        ref::deferred_aniso_covariance(params, f.texel.slope_mean, f.texel.slope_second, band.tangent, band.bitangent, band.normal);
    expect_sym2_near(to_pixel_frame(covariance, band.normal, band.tangent, band.bitangent), texture, 1e-12 * ref::trace(texture));
    const PixelShade row = shade_pixel(gbuffer, x, y, Variant::deferred_aniso, material, params, ref::Derivative::coarse,
                                       NormalFeed::geometric, Prefilter::lean, 1.0, Lobe::tail);
    // The row's kernel part: the geometric normal's tensor and A in its frame, carried into the
    // band-limited frame by M = [t.t_g' t.b_g'; b.t_g' b.b_g'] (renderer.cpp, deferred_aniso_in_pixel_frame).
    const QuadFields q = gather_quad(gbuffer, x, y);
    const Vec3 n_g = q.geometric_normal[q.pixel];
    const ref::Sym2 kernel = ref::deferred_aniso_tail_roughness(ref::deferred_aniso_fragment_quad(params, q.geometric_normal, q.pixel), a2);
    const double scale = ref::trace(row.roughness);
    expect_sym2_near(row.roughness - to_pixel_frame(covariance, band.normal, band.tangent, band.bitangent),
                     to_pixel_frame(kernel, n_g, band.tangent, band.bitangent), 1e-12 * scale);
    ++checked;
  }
  EXPECT_EQ(checked, 3);
}

// ---------------------------------------------------------------------------------------------
// Quad partners across an occlusion edge (renderer.hpp)

// Where a surface passes in front of itself, a quad partner pixel on the far sheet is not what a
// GPU's derivative reads: its helper invocation evaluates the shaded triangle's own attributes.
// The torus knot is a triangle mesh and takes per-triangle quads (the asset scenes' rule). A far
// partner here: 0.1 or more away (7 pixel widths at 256 x 256) with a normal more than 60 degrees
// off the shaded pixel's; taking its normal widened the kernel into bright speckles along the
// knot's occlusion edges.
TEST(QuadPartners, AcrossAnOcclusionEdgeTheFarSheetIsNotTaken) {
  const double cos_bound = std::cos(60.0 * ref::kPi / 180.0);
  const int size = 256;
  const GBuffer gbuffer = render_gbuffer(make_scene(SceneId::torus_knot), size, size, 2);
  int far_partners = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const PixelFields& f = gbuffer.at(x, y);
      if (!f.hit) continue;
      const QuadFields q = gather_quad(gbuffer, x, y);
      for (int p = 0; p < 4; ++p) {
        const PixelFields& partner = gbuffer.at((x & ~1) + (p & 1), (y & ~1) + (p >> 1));
        if (!partner.hit || ref::length(partner.position - f.position) < 0.1 ||
            dot(partner.geometric_normal, f.geometric_normal) > cos_bound)
          continue;
        ++far_partners;
        const Vec3 taken = q.geometric_normal[p];
        EXPECT_LT(ref::length(taken - f.geometric_normal), ref::length(taken - partner.geometric_normal))
            << "(" << x << ", " << y << ") partner " << p;
      }
    }
  EXPECT_GE(far_partners, 100);  // 366 at this size: the edges are there
}

// ---------------------------------------------------------------------------------------------
// Documented numbers (scene.hpp)

// At the centre of the base 256 x 256 view: nmap-sphere's LOD 0.22 (0.22 - 0.26 over the
// central 32 x 32 pixels) and sinusoid periods of 3.4 - 4.2 px; nmap-sphere-fine's LOD 3.22
// (3.22 - 3.26) and periods of 0.43 - 0.52 px. The map's largest tilt lies in 15 - 30 degrees.
TEST(Documented, FeatureSizesAndLods) {
  const int size = 256;
  struct Expect {
    SceneId id;
    double lod_lo, lod_hi, period_lo, period_hi;
  };
  for (const Expect& e : {Expect{SceneId::nmap_sphere, 0.22, 0.26, 3.4, 4.2}, Expect{SceneId::nmap_sphere_fine, 3.22, 3.26, 0.43, 0.52}}) {
    const Scene scene = make_scene(e.id);
    const GBuffer g = render_gbuffer(scene, size, size, 2);
    double lo = 1e9, hi = -1e9;
    for (int y = 112; y < 144; ++y)
      for (int x = 112; x < 144; ++x) {
        lo = std::min(lo, g.at(x, y).lod);
        hi = std::max(hi, g.at(x, y).lod);
      }
    const double centre = g.at(size / 2, size / 2).lod;
    // Period of wave k in pixels: (texels per period) / (texels per pixel) = (512 / |(m, n)|)
    // / 2^lod.
    double period_lo = 1e9, period_hi = 0.0;
    for (const PeriodicWave& w : content_height_field().waves) {
      const double px = kContentNormalMapSize / w.cycles() / std::exp2(centre);
      period_lo = std::min(period_lo, px);
      period_hi = std::max(period_hi, px);
    }
    std::printf("%s: centre lod %.3f, central 32x32 [%.3f, %.3f], periods %.2f - %.2f px\n", std::string(scene_name(e.id)).c_str(), centre,
                lo, hi, period_lo, period_hi);
    EXPECT_GE(lo, e.lod_lo);
    EXPECT_LE(hi, e.lod_hi);
    EXPECT_GE(period_lo, e.period_lo);
    EXPECT_LE(period_hi, e.period_hi);
  }
  const NormalMap& map = *content_normal_map();
  double tilt = 0.0;
  for (int y = 0; y < map.height(0); ++y)
    for (int x = 0; x < map.width(0); ++x) tilt = std::max(tilt, std::acos(map.texel(0, x, y).normal.z));
  std::printf("largest tilt of the map: %.2f degrees (slope bound %.2f)\n", tilt * 180.0 / kPi,
              std::atan(content_height_field().slope_bound()) * 180.0 / kPi);
  EXPECT_GT(tilt, 15.0 * kPi / 180.0);
  EXPECT_LE(tilt, std::atan(content_height_field().slope_bound()));
}

// ---------------------------------------------------------------------------------------------
// Scene plumbing

// Names round-trip, the content scenes stay out of all_scenes (the trade's default list), they
// rotate about the vertical axis, and describe() holds the map's and the mesh's numbers.
TEST(Scenes, NamesRotationAndDescribe) {
  for (SceneId id : content_scenes()) {
    EXPECT_EQ(scene_from_name(scene_name(id)), id);
    EXPECT_EQ(std::find(all_scenes().begin(), all_scenes().end(), id), all_scenes().end());
    const Scene a = make_scene(id), b = make_scene(id, 0.1);
    EXPECT_NEAR(b.object_to_world().col_x.x, std::cos(0.1) * a.object_to_world().col_x.x + std::sin(0.1) * a.object_to_world().col_x.z,
                1e-15);
    EXPECT_NE(a.describe(), b.describe());
  }
  const std::string nmap = make_scene(SceneId::nmap_sphere).describe();
  EXPECT_NE(nmap.find(content_normal_map()->describe()), std::string::npos);
  EXPECT_NE(nmap.find(content_height_field().describe()), std::string::npos);
  EXPECT_NE(nmap.find("tiling=(2,1)"), std::string::npos);
  EXPECT_NE(make_scene(SceneId::nmap_sphere_fine).describe().find("tiling=(16,8)"), std::string::npos);
  const std::string knot = make_scene(SceneId::torus_knot).describe();
  EXPECT_NE(knot.find(content_torus_knot_mesh()->describe()), std::string::npos);
  EXPECT_NE(knot.find("segments=512,sides=24"), std::string::npos);
  // The analytic scenes' descriptions (cache keys) carry no map.
  EXPECT_EQ(make_scene(SceneId::sphere).describe().find("normal_map"), std::string::npos);
}

// A small ground truth of each content scene: finite, non-zero where the shape is, the mapped
// sphere's coverage equal to the plain sphere's (the map changes shading, not geometry), and
// the knot filling a good part of the frame.
TEST(Scenes, GroundTruthSmoke) {
  GroundTruthSettings settings;
  settings.width = settings.height = 16;
  settings.strata = 4;
  settings.threads = 2;
  const Material materials[] = {{0.1, false}};
  const GroundTruth sphere = render_ground_truth(make_scene(SceneId::sphere), settings, materials);
  for (SceneId id : content_scenes()) {
    const GroundTruth gt = render_ground_truth(make_scene(id), settings, materials);
    double sum = 0.0, coverage = 0.0;
    for (std::size_t i = 0; i < gt.images[0].size(); ++i) {
      ASSERT_TRUE(std::isfinite(gt.images[0].pixels[i]));
      sum += gt.images[0].pixels[i];
      coverage += gt.coverage.pixels[i];
    }
    coverage /= gt.coverage.size();
    EXPECT_GT(sum, 0.0) << scene_name(id);
    if (id != SceneId::torus_knot)
      EXPECT_EQ(gt.coverage.pixels, sphere.coverage.pixels) << scene_name(id);
    else
      EXPECT_GT(coverage, 0.25);
  }
}

// The ground truth's cost per content scene: bench/bench_reference.cpp (BM_GroundTruthContent).

// The built-in scenes are rows of one table: every row is in exactly one group, its name finds
// it again, each enumerator names its row, and its normal detail is what the trade feeds it.
TEST(BuiltinScenes, EveryRowIsListedNamedAndClassifiedOnce) {
  std::vector<SceneId> listed(all_scenes().begin(), all_scenes().end());
  listed.insert(listed.end(), content_scenes().begin(), content_scenes().end());
  ASSERT_FALSE(listed.empty());
  std::sort(listed.begin(), listed.end());
  for (std::size_t i = 0; i < listed.size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(listed[i]), i) << "the groups list every row once";
    const std::string_view name = scene_name(listed[i]);
    EXPECT_EQ(scene_from_name(name), listed[i]) << name;
    EXPECT_EQ(make_scene(listed[i]).name(), name);
  }
  const std::pair<SceneId, std::string_view> enumerators[] = {{SceneId::sphere, "sphere"},
                                                              {SceneId::torus, "torus"},
                                                              {SceneId::tubes, "tubes"},
                                                              {SceneId::bump_plane, "bump_plane"},
                                                              {SceneId::nmap_sphere, "nmap-sphere"},
                                                              {SceneId::nmap_sphere_fine, "nmap-sphere-fine"},
                                                              {SceneId::torus_knot, "torus-knot"}};
  for (const auto& [id, name] : enumerators) EXPECT_EQ(scene_name(id), name);
  EXPECT_EQ(scene_normal_detail(SceneId::sphere), NormalDetail::none);
  EXPECT_EQ(scene_normal_detail(SceneId::torus_knot), NormalDetail::none);
  EXPECT_EQ(scene_normal_detail(SceneId::bump_plane), NormalDetail::procedural);
  EXPECT_EQ(scene_normal_detail(SceneId::nmap_sphere), NormalDetail::normal_map);
  EXPECT_EQ(scene_normal_detail(SceneId::nmap_sphere_fine), NormalDetail::normal_map);
  EXPECT_FALSE(scene_from_name("no-such-scene").has_value());
}

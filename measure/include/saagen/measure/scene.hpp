// saagen ground-truth renderer: analytic scenes.
//
// Each scene is one analytic shape (with closed-form intersection, shading normal and a smooth
// tangent frame), a rigid placement, a pinhole camera and one light. Every ray hit provides
// what the SAA variants read per pixel: position, shading normal n, tangent t and bitangent
// b = n x t (so (t, b, n) is a right-handed orthonormal frame), and an object index (the tube
// of a row of tubes), which the 1-spp renderer uses to decide whether a quad partner lies on
// the same surface.
//
// Conventions: right-handed world space, +y up; the camera looks towards -z; pixel (x, y) has
// its centre at film position (x + 0.5, y + 0.5) with y growing downwards (quad.hpp's layout).
// The whole shape can rotate about the world vertical axis through a per-scene pivot, and the
// camera can pan parallel to its film (Camera::panned): the trade's animation (trade.hpp); the
// light stays fixed.
//
// The standard scenes (make_scene):
//   sphere      unit sphere at the origin, camera at z = 4, directional light from the upper
//               left near the camera: a small highlight on the front and grazing half vectors
//               (small h_z) all along the rim. Tangent frame: the stereographic field
//               (smooth everywhere except the pole facing away from the camera). Pivot
//               (0, 0, -1), so the rotation also slides the sphere sideways.
//   torus       R = 1, r = 0.35, tilted 55 degrees towards the camera (hole visible), point
//               light; tangent along the major circle (smooth everywhere).
//   tubes       a row of 9 thin parallel open cylinders (r = 0.05, 1.2 long on each side of
//               the centre) receding at 35 degrees: normals turn by 180 degrees across a few
//               pixels, and the top and bottom of every tube are seen at grazing angles;
//               tangent along the axis. Directional light placed so that i.a = -o.a at the
//               image centre (a the axis): a highlight line runs along every tube.
//   bump_plane  a 5 x 5 square seen from above at ~33 degrees, shaded with a sum of four
//               sines (wavelengths 0.083 - 0.23, i.e. ~8 - 22 pixels per period at the image
//               centre at 256 px, fewer towards the back): analytic normal normalize(-dh/dx,
//               -dh/dy, 1) in the plane's frame; light near the mirror direction of the view, so
//               the glint patch is centred.
//
// The "real content" scenes (content_scenes; not in all_scenes, the trade's default list):
//   nmap-sphere       the sphere scene (same sphere, camera, light, pivot) shaded with a
//                     512 x 512 tangent-space normal map repeated (2, 1) times over the sphere's
//                     (longitude, latitude) uv, so texels are square at the equator (pi / 512
//                     long). The map: normals_from_gradient of a periodic height field of 8
//                     sinusoids (content_height_field: fixed seed, stratified directions, 106 -
//                     125 periods per tile = 4.1 - 4.8 texels per period, slope bound tan 30
//                     degrees; largest tilt of a level-0 normal 20.3 degrees). Measured at the
//                     base 256 x 256 view: LOD 0.224 at the image centre (0.224 - 0.253 over the
//                     central 32 x 32 pixels), i.e. ~1.17 texels per pixel, and sinusoid periods
//                     of 3.5 - 4.1 px there ("features of ~4 px", magnified to ~1:1). The
//                     highlight sits on the upper left of the front; the uv seam (-z) and the
//                     poles (+-y, z = 0 < 1/4) are behind the silhouette.
//   nmap-sphere-fine  the same with tiling (16, 8): LOD 3.224 at the centre (3.224 - 3.253 over
//                     the central 32 x 32), 9.3 texels per pixel, periods of 0.44 - 0.52 px
//                     (features below a pixel, strongly minified).
//   torus-knot        a (2, 3) torus-knot tube (mesh.hpp: core radius R = 1, offset a = 0.45,
//                     tube radius 0.2) as a TRIANGLE MESH of 512 x 24 segments (24576
//                     triangles, BVH) with the analytic tube normals and curve tangents at the
//                     vertices, interpolated barycentrically (so the geometric normal is the
//                     interpolated vertex normal, not the face normal); no normal map. Tilted
//                     25 degrees about x, rolled 10 degrees and centred: it spans ~83 % of the
//                     frame (35 % coverage); a directional light from the upper left near the
//                     camera draws a highlight band along every strand.
#pragma once

#include "saagen/measure/normal_map.hpp"
#include "saagen/measure/scalar_map.hpp"
#include "saagen/measure/shape.hpp"
#include "saagen/reference/math.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace saagen::measure {

// x -> R x + translation, R a rotation given by its columns (the images of the unit axes).
struct Rigid {
  Vec3 col_x{1.0, 0.0, 0.0};
  Vec3 col_y{0.0, 1.0, 0.0};
  Vec3 col_z{0.0, 0.0, 1.0};
  Vec3 translation{};

  Vec3 apply_vector(Vec3 v) const { return v.x * col_x + v.y * col_y + v.z * col_z; }
  Vec3 apply_point(Vec3 p) const { return apply_vector(p) + translation; }
  Vec3 inverse_vector(Vec3 v) const { return {ref::dot(v, col_x), ref::dot(v, col_y), ref::dot(v, col_z)}; }
  Vec3 inverse_point(Vec3 p) const { return inverse_vector(p - translation); }

  // Rotation by angle (radians, right-handed) about a unit axis through the origin.
  static Rigid rotation(Vec3 axis, double angle);
  static Rigid translate(Vec3 t);
};

// a after b: x -> a(b(x)).
Rigid compose(const Rigid& a, const Rigid& b);

// Sphere of the given radius centred at the origin. Tangent frame: with n = (a, b, c), the
// field t ~ ((1 + c)^2 + b^2 - a^2, -2ab, -2a(1 + c)), the image of the plane's x axis under
// the inverse stereographic projection from the pole -z; smooth except at n = -z.
// uv: longitude u = atan2(x, z) / (2 pi) + 1/2 (seam at the back, -z) and latitude
// v = 1 - theta / pi, theta = acos(y / r) (v grows upwards; poles at +-y), so that at the front
// dpdu points along +x and dpdv along +y: dpdu = 2 pi (z, 0, -x), dpdv = pi (-y x / rho, rho,
// -y z / rho) with rho = sqrt(x^2 + z^2) (both zero at the poles).
class Sphere final : public Shape {
 public:
  explicit Sphere(double radius) : radius_(radius) {}
  bool intersect(const Ray& ray, double t_min, SurfaceHit& hit) const override;
  std::string describe() const override;
  static Vec3 stereographic_tangent(Vec3 n);

 private:
  void set_uv(SurfaceHit& hit) const;
  double radius_;
};

// Torus around the y axis: (|p|^2 + R^2 - r^2)^2 = 4 R^2 (px^2 + pz^2). The ray equation is
// a quartic; its real roots are bracketed between the critical points (roots of the cubic
// derivative, solved in closed form) and refined by safeguarded Newton iterations.
// Normal: normalize(p - R normalize(px, 0, pz)); tangent: the major-circle direction
// normalize(-pz, 0, px). uv: u = phi / (2 pi), phi = atan2(pz, px) the major angle; v = psi /
// (2 pi), psi = atan2(py, rho - R) the tube angle (both wrapped to [0, 1)).
class Torus final : public Shape {
 public:
  Torus(double major_radius, double minor_radius) : major_(major_radius), minor_(minor_radius) {}
  bool intersect(const Ray& ray, double t_min, SurfaceHit& hit) const override;
  std::string describe() const override;

 private:
  void set_uv(SurfaceHit& hit) const;
  double major_;
  double minor_;
};

// A row of `count` open cylinders of the given radius with axes parallel to x, centred on
// y = (k - (count - 1) / 2) spacing, z = 0, |x| <= half_length. Only the outer surface is
// visible (a ray that would enter through an open end sees nothing). Normal: the radial
// direction; tangent: +x. SurfaceHit::object is the tube index k. uv: u = (x + half_length) /
// (2 half_length) along the axis, v = psi / (2 pi) around it (psi = atan2(z, y - y_k)).
class TubeRow final : public Shape {
 public:
  TubeRow(int count, double radius, double spacing, double half_length)
      : count_(count), radius_(radius), spacing_(spacing), half_length_(half_length) {}
  bool intersect(const Ray& ray, double t_min, SurfaceHit& hit) const override;
  std::string describe() const override;
  double axis_y(int k) const { return (k - 0.5 * (count_ - 1)) * spacing_; }

 private:
  int count_;
  double radius_;
  double spacing_;
  double half_length_;
};

// One term a sin(k . (x, y) + phase) of a height field.
struct SineWave {
  Vec2 wave_vector;  // k, radians per unit length
  double amplitude = 0.0;
  double phase = 0.0;
};

// The square |x|, |y| <= half_size of the plane z = 0, seen from +z, bump-mapped with
// h(x, y) = sum of SineWaves (the geometry stays flat: only the shading normal follows h).
// Normal: normalize(-dh/dx, -dh/dy, 1). Tangent: x axis made orthogonal to n,
// normalize(e_x - n_x n). Geometric frame: the plane's (e_x, e_y, e_z); uv = (x, y) mapped from
// [-half_size, half_size] to [0, 1].
//
// Footprint moments (the procedural counterpart of a normal map's LEAN texel): the slope is
// s = grad h = sum_j a_j k_j cos(theta_j), theta_j = k_j . x + phase_j, and over points
// x ~ N(x0, S) the characteristic function of the Gaussian gives E[cos(k . x + p)] =
// cos(k . x0 + p) g(k), g(k) = exp(-k^T S k / 2). So, exactly,
//   E[s]     = sum_j a_j k_j cos(theta_j(x0)) g(k_j),
//   E[s s^T] = sum_j sum_l a_j a_l k_j k_l^T (cos(theta_j - theta_l) g(k_j - k_l) + cos(theta_j + theta_l) g(k_j + k_l)) / 2
// (cos A cos B = (cos(A - B) + cos(A + B)) / 2), the band-limiting of each sinusoid by the
// footprint (Norton, Rockwood & Skolmoski 1982's clamping, with the Gaussian's exact attenuation
// instead of a cut-off) carried to the second moment. N waves cost N (N + 1) / 2 pair terms.
class BumpPlane final : public Shape {
 public:
  BumpPlane(double half_size, std::vector<SineWave> waves) : half_size_(half_size), waves_(std::move(waves)) {}
  bool intersect(const Ray& ray, double t_min, SurfaceHit& hit) const override;
  std::string describe() const override;
  std::optional<SlopeMoments> footprint_slope_moments(Vec2 uv, Sym2 footprint) const override;
  double height(double x, double y) const;
  Vec2 gradient(double x, double y) const;  // (dh/dx, dh/dy)
  Vec3 normal(double x, double y) const;
  // The moments above at plane point (x, y) for a covariance S of plane points (units^2).
  SlopeMoments slope_moments(Vec2 centre, Sym2 covariance) const;
  const std::vector<SineWave>& waves() const { return waves_; }
  double half_size() const { return half_size_; }

 private:
  double half_size_;
  std::vector<SineWave> waves_;
};

// Pinhole camera.
struct Camera {
  Vec3 position{0.0, 0.0, 4.0};
  Vec3 look_at{};
  Vec3 up{0.0, 1.0, 0.0};
  double fov_y_degrees = 35.0;
  // Sub-pixel offset (pixels, x right, y down) added to every film position generate() takes:
  // a temporal anti-aliasing jitter (taa.hpp), which a GPU puts into the projection matrix, so
  // that every primary ray of a frame, the quad partners' included, moves with it while
  // gl_FragCoord stays the pixel centre.
  Vec2 jitter{};

  // The same camera with the field of view narrowed so that an image of `size` pixels has
  // the pixel footprint of a `full_size` image: the centre crop of the full image (square
  // images: the aspect ratio is width / height of the image rendered).
  Camera cropped(int size, int full_size) const;

  // The same camera translated parallel to its film, position and look-at point alike, by
  // (right, up) pixels of an image `height` pixels high, measured at the look-at distance: a
  // point at that distance is seen (right, up) pixels the other way, (fx - right, fy + up).
  Camera panned(double right_pixels, double up_pixels, int height) const;

  // Primary ray through film position (fx, fy) in pixels (x right, y down) of a
  // width x height image (CameraFilm(*this, width, height).ray(fx, fy)).
  Ray generate(double fx, double fy, int width, int height) const;

  // The film position (fx, fy) whose primary ray passes through the world point p (generate's
  // inverse, jitter included); nullopt when p is not in front of the camera.
  std::optional<Vec2> project(Vec3 p, int width, int height) const;
};

// A camera's primary rays for one image size: the frame, the field of view's tangent and the
// aspect ratio computed once, so that a renderer tracing many rays per pixel does not recompute
// them per ray. ray() is Camera::generate to the last bit (the same operations in the same order).
class CameraFilm {
 public:
  CameraFilm(const Camera& camera, int width, int height);
  Ray ray(double fx, double fy) const;

 private:
  Vec3 position_, forward_, right_, true_up_;
  Vec2 jitter_;
  double tan_half_ = 0.0, aspect_ = 0.0;
  int width_ = 0, height_ = 0;
};

struct Light {
  enum class Kind { directional, point };
  Kind kind = Kind::directional;
  Vec3 vector{0.0, 0.0, 1.0};  // directional: unit direction towards the light; point: position
  double intensity = 1.0;      // directional: irradiance on a surface facing it; point: I (E = I / d^2)

  // Unit direction to the light and the irradiance E at p (normal incidence).
  void at(Vec3 p, Vec3& to_light, double& irradiance) const;
};

// A scene the trade renders: a built-in one, or one registered at run time (register_scene).
// The built-in scenes are the analytic ones (all_scenes) and the "real content" ones
// (content_scenes: normal maps and a triangle mesh, see the top of this file), each one row of
// kBuiltinScenes in measure/src/builtin_scenes.cpp (name, group, normal detail, the function that
// builds it) and nothing else: a scene's id is its row's index. The enumerators name the rows
// that code refers to directly; a new row needs none.
enum class SceneId { sphere, torus, tubes, bump_plane, nmap_sphere, nmap_sphere_fine, torus_knot };

std::string_view scene_name(SceneId id);
std::optional<SceneId> scene_from_name(std::string_view name);  // any SceneId
std::span<const SceneId> all_scenes();                          // sphere, torus, tubes, bump_plane
std::span<const SceneId> content_scenes();                      // nmap-sphere, nmap-sphere-fine, torus-knot

// The normal detail of a scene's surfaces, which decides the feeds and prefilters the trade measures
// on it: none (the geometric normal is the shading normal), a procedural height field's normals
// (bump_plane) or a normal map (the nmap spheres, an asset with a normal texture).
enum class NormalDetail { none, procedural, normal_map };
NormalDetail scene_normal_detail(SceneId id);

struct Anisotropy;

// The textures of each connected surface (SurfaceHit::object) of a scene built from an asset
// (gltf.hpp): the tangent-space normal map (its texels already decoded and scaled by the
// material's normalTexture.scale) and the roughness texture whose square scales alpha
// (SurfaceHit::alpha_scale). In such a scene the texture frame is the mesh's own (interpolated
// vertex tangents and their bitangent sign, MeshVertex), not dpdu made orthogonal to n.
struct SurfaceTextures {
  std::shared_ptr<const NormalMap> normal_map;     // null: no normal texture
  std::shared_ptr<const ScalarMap> roughness_map;  // null: no roughness texture
  // The lobe's weight (a clearcoat layer's factor, 0 where the surface has no coat) and its
  // texture (clearcoatTexture's R), multiplying the radiance; 1 and none for a base lobe.
  double weight = 1.0;
  std::shared_ptr<const ScalarMap> weight_map;
  // A clearcoat layer above this lobe (KHR_materials_clearcoat's factor, and its texture's R):
  // the radiance is multiplied by 1 - coat F(i.h), F Schlick's with F0 = 0.04 (the layer's
  // Fresnel, ior 1.5); 0 and none: no layer.
  double coat = 0.0;
  std::shared_ptr<const ScalarMap> coat_map;
  // KHR_materials_anisotropy of the lobe (anisotropy.hpp); null: isotropic.
  std::shared_ptr<const Anisotropy> anisotropy;
};
// The alpha factor of a roughness texture's sample g (G channel): g^2, g clamped to
// [1 / 255, 1] (the smallest non-zero 8-bit value: a zero alpha is a delta lobe no GGX
// evaluation takes).
double roughness_alpha_scale(double g);

struct SurfaceMaterials {
  std::vector<SurfaceTextures> by_object;  // indexed by SurfaceHit::object
  std::string description;                 // every number that defines them (cache keys)
  const SurfaceTextures* at(int object) const {
    return object >= 0 && object < static_cast<int>(by_object.size()) ? &by_object[static_cast<std::size_t>(object)] : nullptr;
  }
};

class Scene {
 public:
  Scene(std::string name, std::shared_ptr<const Shape> shape, Rigid placement, Camera camera, Light light, Vec3 pivot,
        double rotation_radians);

  // Nearest hit of a world-space ray (fields transformed to world space, uv in texture
  // units). With a normal map, the shading frame comes from the map's level-0 bilinear sample
  // at hit.uv (apply_normal_map): what the ground truth integrates over the pixel filter.
  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  // The same hit before the normal map: the shading frame equals the geometric frame in a
  // normal-mapped scene (identical to intersect otherwise).
  bool intersect_surface(const Ray& ray, SurfaceHit& hit) const;
  // The hit a GPU's helper invocation of `shaded`'s triangle evaluates for this ray: the ray
  // meets the plane of that triangle (t > 0) and every attribute is that triangle's barycentric
  // interpolation, extrapolated (fields as intersect_surface gives them, before the normal map).
  // False when the shape is no triangle mesh, shaded.triangle is -1 or the ray misses the plane.
  bool extrapolate_surface(const SurfaceHit& shaded, const Ray& ray, SurfaceHit& hit) const;
  // Whether the 1-spp images take quad partners from the shaded triangle's extrapolated
  // attributes whenever a partner pixel is not on that triangle, as a GPU's helper invocations do:
  // every triangle mesh (the asset scenes, whose meshes have uv seams and split normals, and the
  // torus knot, whose tube passes in front of itself: renderer.hpp). The analytic shapes take a
  // partner's own fields on the same connected surface (none of them passes in front of itself).
  bool per_triangle_quads() const;
  // Sets the shading frame of a hit from a tangent-space normal m (any length, z > 0): the
  // TBN transform n = normalize(m.x t + s m.y b + m.z n_g) with the geometric frame (t, b, n_g)
  // and s = hit.bitangent_sign; the shading tangent is t made orthogonal to n, b = n x t.
  static void apply_normal_map(SurfaceHit& hit, Vec3 normal_ts);
  // The shape's footprint slope moments (Shape::footprint_slope_moments) at a hit, for a
  // covariance of texture uv (texture units^2, as the quad's uv derivatives give it); nullopt
  // on scenes without procedural normal detail.
  std::optional<SlopeMoments> footprint_slope_moments(const SurfaceHit& hit, Sym2 uv_footprint) const;

  // The same scene seen through another camera.
  Scene with_camera(const Camera& camera) const;
  // The same scene shaded with a normal map repeated `tiling` times over the shape's uv
  // square (texture uv = tiling * shape uv).
  // source: the numbers the map was generated from (kept in describe()).
  Scene with_normal_map(std::shared_ptr<const NormalMap> map, Vec2 tiling, std::string source = {}) const;
  const NormalMap* normal_map() const { return normal_map_.get(); }
  // The same scene with per-surface textures (asset scenes; see SurfaceMaterials).
  Scene with_surface_materials(std::shared_ptr<const SurfaceMaterials> surfaces) const;
  const SurfaceMaterials* surface_materials() const { return surfaces_.get(); }
  // The normal map and roughness map that shade a hit: the per-surface ones of an asset scene,
  // else the scene's single normal map (and no roughness map).
  const NormalMap* normal_map_at(const SurfaceHit& hit) const;
  const ScalarMap* roughness_map_at(const SurfaceHit& hit) const;
  // The per-surface textures of a hit in an asset scene; null otherwise.
  const SurfaceTextures* surface_textures_at(const SurfaceHit& hit) const { return surfaces_ ? surfaces_->at(hit.object) : nullptr; }
  // Whether any surface of the scene has a normal map.
  bool has_normal_map() const;
  Vec2 uv_tiling() const { return tiling_; }

  const std::string& name() const { return name_; }
  const Camera& camera() const { return camera_; }
  const Light& light() const { return light_; }
  double rotation() const { return rotation_; }
  const Rigid& object_to_world() const { return object_to_world_; }
  // Every number that affects a rendered image of the scene (cache keys).
  std::string describe() const;

 private:
  std::string name_;
  std::shared_ptr<const Shape> shape_;
  Rigid placement_;
  Camera camera_;
  Light light_;
  Vec3 pivot_;
  double rotation_;
  Rigid object_to_world_;
  std::shared_ptr<const NormalMap> normal_map_;
  Vec2 tiling_{1.0, 1.0};
  std::string normal_map_source_;  // how the map was made (part of describe())
  std::shared_ptr<const SurfaceMaterials> surfaces_;
  // intersect_surface's second half: object-space fields to world space and texture units.
  void finish_surface_hit(SurfaceHit& hit) const;
};

// The standard scene, rotated by rotation_radians about the vertical axis through its pivot;
// for a registered scene, its factory's scene.
Scene make_scene(SceneId id, double rotation_radians = 0.0);

// Scenes built at run time (a glTF asset: gltf.hpp), registered once per process and then named
// by a SceneId beyond the standard ones, so that the trade, its cache and the report treat them
// as the standard scenes. make(rotation) must return the scene rotated about its pivot.
struct RegisteredScene {
  std::string name;  // [A-Za-z0-9_.-]+, not a standard scene's name
  std::function<Scene(double rotation_radians)> make;
  bool has_normal_map = false;  // some surface has a normal map
};
// The id of a registered scene; registering a name again returns the first registration's id
// when `key` (what identifies the content, e.g. the asset's path) is the same, and throws
// std::invalid_argument otherwise.
SceneId register_scene(RegisteredScene scene, const std::string& key);
// The registration behind an id; null for a standard scene or an unknown id.
const RegisteredScene* registered_scene(SceneId id);

// The content of the real-content scenes, built once per process and shared by every frame:
// the height field and kContentNormalMapSize^2 normal map of nmap-sphere(-fine), and the torus
// knot and its mesh (with BVH) of torus-knot.
inline constexpr int kContentNormalMapSize = 512;
struct PeriodicHeightField;
struct TorusKnot;
class TriangleMesh;
const PeriodicHeightField& content_height_field();
std::shared_ptr<const NormalMap> content_normal_map();
const TorusKnot& content_torus_knot();
std::shared_ptr<const TriangleMesh> content_torus_knot_mesh();

}  // namespace saagen::measure

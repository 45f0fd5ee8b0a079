// The built-in scenes and the ids of every scene the trade renders (see scene.hpp). A built-in
// scene is one row of kBuiltinScenes below, with the function that builds it: adding one touches
// this file only. Its id is its row's index; every list (all_scenes, content_scenes), name lookup,
// preset and trade predicate reads the rows. Scenes built at run time (a glTF asset) are
// registered under ids beyond the rows (register_scene).
#include "saagen/measure/height_field.hpp"
#include "saagen/measure/mesh.hpp"
#include "saagen/measure/scene.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <deque>
#include <mutex>
#include <optional>
#include <stdexcept>

namespace saagen::measure {

using ref::dot;
using ref::kPi;
using ref::normalize;

namespace {
double radians(double degrees) { return degrees * kPi / 180.0; }
}  // namespace

// ---------------------------------------------------------------------------------------------
// The built-in scenes, as data (as pbrt-v4 describes a scene): each is one row of kBuiltinScenes,
// with the function that builds it.

namespace {
enum class SceneGroup { analytic, content };  // all_scenes(), content_scenes()

struct BuiltinScene {
  std::string_view name;
  SceneGroup group;
  NormalDetail detail;                                       // the normal detail the trade feeds the filters
  Scene (*make)(std::string name, double rotation_radians);  // the scene, named, turned about its pivot
  // The SceneId enumerator that code names the scene by (scene.hpp), where it has one: a row
  // needs none, and one that has it sits at the enumerator's index (checked below).
  std::optional<SceneId> enumerator = std::nullopt;
};

Scene make_sphere_scene(std::string name, double rotation_radians) {
  Camera camera{{0.0, 0.0, 4.0}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, 34.0};
  Light light{Light::Kind::directional, normalize(Vec3{-0.45, 0.55, 1.0}), 1.0};
  return Scene(std::move(name), std::make_shared<Sphere>(1.0), Rigid{}, camera, light, {0.0, 0.0, -1.0}, rotation_radians);
}

Scene make_torus_scene(std::string name, double rotation_radians) {
  // Tilt the torus axis (object y) 55 degrees towards the camera, then roll it by 20
  // degrees about the view axis.
  const Rigid placement = compose(Rigid::rotation({0.0, 0.0, 1.0}, radians(20.0)), Rigid::rotation({1.0, 0.0, 0.0}, radians(55.0)));
  Camera camera{{0.0, 0.0, 4.2}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, 36.0};
  const Vec3 light_position{-2.5, 3.0, 4.0};
  // I = |position|^2 gives an irradiance of about 1 near the torus.
  Light light{Light::Kind::point, light_position, dot(light_position, light_position)};
  return Scene(std::move(name), std::make_shared<Torus>(1.0, 0.35), placement, camera, light, {0.0, 0.0, 0.0}, rotation_radians);
}

Scene make_tubes_scene(std::string name, double rotation_radians) {
  // Axes (object x) turned 35 degrees into the depth, then tilted 8 degrees.
  const Rigid placement = compose(Rigid::rotation({0.0, 0.0, 1.0}, radians(8.0)), Rigid::rotation({0.0, 1.0, 0.0}, radians(35.0)));
  Camera camera{{0.0, 0.1, 4.0}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, 36.0};
  // A cylinder only shows a highlight line where the half vector is perpendicular to
  // its axis a, i.e. where i.a = -o.a. The light direction is the view direction at
  // the centre, o, mirrored across the plane normal to a (i.a = -o.a) and turned by
  // 50 degrees about a, so the line runs along the upper side of every tube.
  const Vec3 axis = placement.apply_vector({1.0, 0.0, 0.0});
  const Vec3 view = normalize(camera.position - camera.look_at);
  const Vec3 along = dot(view, axis) * axis;
  const Rigid turn = Rigid::rotation(axis, radians(-50.0));
  Light light{Light::Kind::directional, normalize(turn.apply_vector(view - along) - along), 1.0};
  return Scene(std::move(name), std::make_shared<TubeRow>(9, 0.05, 0.22, 1.2), placement, camera, light, {0.0, 0.0, 0.0}, rotation_radians);
}

Scene make_bump_plane_scene(std::string name, double rotation_radians) {
  // Object (x, y, z) -> world (x, -z, y): the bump plane's normal is world +y.
  Rigid placement;
  placement.col_x = {1.0, 0.0, 0.0};
  placement.col_y = {0.0, 0.0, -1.0};
  placement.col_z = {0.0, 1.0, 0.0};
  // Waves: wavelength lambda along a direction, amplitude from the slope amplitude
  // a |k| (the largest tilt each wave gives to the normal).
  auto wave = [](double wavelength, Vec2 direction, double slope, double phase) {
    const double k = 2.0 * kPi / wavelength;
    const Vec2 unit = direction / ref::length(direction);
    return SineWave{k * unit, slope / k, phase};
  };
  std::vector<SineWave> waves{wave(0.15, {1.0, 0.3}, 0.20, 0.3), wave(0.11, {-0.4, 1.0}, 0.15, 1.7), wave(0.083, {0.8, -0.7}, 0.12, 4.1),
                              wave(0.23, {0.2, 1.0}, 0.18, 2.6)};
  Camera camera{{0.0, 2.0, 3.4}, {0.0, 0.0, 0.3}, {0.0, 1.0, 0.0}, 40.0};
  // Mirror of the view direction at the look-at point about the plane's normal,
  // turned slightly, so the glint patch sits near the image centre.
  const Vec3 view = normalize(camera.position - camera.look_at);
  Light light{Light::Kind::directional, normalize(Vec3{0.12, view.y, -view.z}), 1.0};
  return Scene(std::move(name), std::make_shared<BumpPlane>(2.5, std::move(waves)), placement, camera, light, {0.0, 0.0, 0.0},
               rotation_radians);
}

// The sphere scene's sphere, camera, light and pivot, shaded with the content map. u spans 2 pi and
// v spans pi on the unit sphere, so tiling (2k, k) keeps the texels square at the equator: a texel
// is pi / (k 512) long.
Scene make_normal_mapped_sphere(std::string name, Vec2 tiling, double rotation_radians) {
  const Scene base = make_sphere_scene("sphere", rotation_radians);
  Scene scene(std::move(name), std::make_shared<Sphere>(1.0), Rigid{}, base.camera(), base.light(), {0.0, 0.0, -1.0}, rotation_radians);
  return scene.with_normal_map(content_normal_map(), tiling, content_height_field().describe());
}

Scene make_nmap_sphere_scene(std::string name, double rotation_radians) {
  return make_normal_mapped_sphere(std::move(name), {2.0, 1.0}, rotation_radians);
}

Scene make_nmap_sphere_fine_scene(std::string name, double rotation_radians) {
  return make_normal_mapped_sphere(std::move(name), {16.0, 8.0}, rotation_radians);
}

Scene make_torus_knot_scene(std::string name, double rotation_radians) {
  // The knot lies in the object xy plane (core circle radius 1, extent ~1.65); tilted
  // 25 degrees about x so that the strands overlap in depth, rolled 10 degrees.
  // Shifted by (-0.08, 0.19) to centre its image; the pivot is the shifted centre.
  const Vec3 centre{-0.08, 0.19, 0.0};
  const Rigid placement = compose(
      Rigid::translate(centre), compose(Rigid::rotation({0.0, 0.0, 1.0}, radians(10.0)), Rigid::rotation({1.0, 0.0, 0.0}, radians(-25.0))));
  Camera camera{{0.0, 0.0, 5.5}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, 38.0};
  Light light{Light::Kind::directional, normalize(Vec3{-0.4, 0.6, 1.0}), 1.0};
  return Scene(std::move(name), content_torus_knot_mesh(), placement, camera, light, centre, rotation_radians);
}

constexpr std::array kBuiltinScenes{
    BuiltinScene{"sphere", SceneGroup::analytic, NormalDetail::none, make_sphere_scene, SceneId::sphere},
    BuiltinScene{"torus", SceneGroup::analytic, NormalDetail::none, make_torus_scene, SceneId::torus},
    BuiltinScene{"tubes", SceneGroup::analytic, NormalDetail::none, make_tubes_scene, SceneId::tubes},
    BuiltinScene{"bump_plane", SceneGroup::analytic, NormalDetail::procedural, make_bump_plane_scene, SceneId::bump_plane},
    BuiltinScene{"nmap-sphere", SceneGroup::content, NormalDetail::normal_map, make_nmap_sphere_scene, SceneId::nmap_sphere},
    BuiltinScene{"nmap-sphere-fine", SceneGroup::content, NormalDetail::normal_map, make_nmap_sphere_fine_scene, SceneId::nmap_sphere_fine},
    BuiltinScene{"torus-knot", SceneGroup::content, NormalDetail::none, make_torus_knot_scene, SceneId::torus_knot},
};

constexpr SceneId id_of_row(std::size_t row) { return static_cast<SceneId>(row); }

constexpr bool rows_sit_at_their_enumerators() {
  for (std::size_t i = 0; i < kBuiltinScenes.size(); ++i)
    if (kBuiltinScenes[i].enumerator && *kBuiltinScenes[i].enumerator != id_of_row(i)) return false;
  return true;
}
static_assert(rows_sit_at_their_enumerators(), "kBuiltinScenes: a row that names a SceneId enumerator sits at its index");

constexpr std::size_t scene_count(SceneGroup group) {
  std::size_t count = 0;
  for (const BuiltinScene& scene : kBuiltinScenes) count += scene.group == group ? 1 : 0;
  return count;
}

template <SceneGroup group>
constexpr std::array<SceneId, scene_count(group)> scenes_in() {
  std::array<SceneId, scene_count(group)> ids{};
  std::size_t next = 0;
  for (std::size_t i = 0; i < kBuiltinScenes.size(); ++i)
    if (kBuiltinScenes[i].group == group) ids[next++] = id_of_row(i);
  return ids;
}

constexpr auto kAnalyticScenes = scenes_in<SceneGroup::analytic>();
constexpr auto kContentScenes = scenes_in<SceneGroup::content>();

const BuiltinScene* builtin_scene(SceneId id) {
  const auto index = static_cast<std::size_t>(id);
  return index < kBuiltinScenes.size() ? &kBuiltinScenes[index] : nullptr;
}
}  // namespace

Scene make_scene(SceneId id, double rotation_radians) {
  if (const RegisteredScene* registered = registered_scene(id)) return registered->make(rotation_radians);
  if (const BuiltinScene* builtin = builtin_scene(id)) return builtin->make(std::string(builtin->name), rotation_radians);
  throw std::invalid_argument("unknown scene id");
}

namespace {
// Registered scenes: a deque keeps every entry (and the name a string_view refers to) in place.
struct SceneRegistry {
  std::mutex mutex;
  std::deque<std::pair<std::string, RegisteredScene>> entries;  // (key, scene)
};
SceneRegistry& scene_registry() {
  static SceneRegistry registry;
  return registry;
}
constexpr int kFirstRegisteredScene = 64;
static_assert(kBuiltinScenes.size() <= kFirstRegisteredScene, "the built-in scenes' ids stay below the registered ones'");
bool valid_scene_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return true;
}
}  // namespace

SceneId register_scene(RegisteredScene scene, const std::string& key) {
  if (!valid_scene_name(scene.name)) throw std::invalid_argument("scene name '" + scene.name + "': use letters, digits, '_', '-', '.'");
  for (const BuiltinScene& builtin : kBuiltinScenes)
    if (builtin.name == scene.name) throw std::invalid_argument("scene name '" + scene.name + "' is a standard scene's");
  SceneRegistry& registry = scene_registry();
  std::lock_guard lock(registry.mutex);
  for (std::size_t i = 0; i < registry.entries.size(); ++i) {
    if (registry.entries[i].second.name != scene.name) continue;
    if (registry.entries[i].first == key) return static_cast<SceneId>(kFirstRegisteredScene + static_cast<int>(i));
    throw std::invalid_argument("scene name '" + scene.name + "' is already registered for " + registry.entries[i].first);
  }
  registry.entries.emplace_back(key, std::move(scene));
  return static_cast<SceneId>(kFirstRegisteredScene + static_cast<int>(registry.entries.size()) - 1);
}

const RegisteredScene* registered_scene(SceneId id) {
  const int index = static_cast<int>(id) - kFirstRegisteredScene;
  if (index < 0) return nullptr;
  SceneRegistry& registry = scene_registry();
  std::lock_guard lock(registry.mutex);
  if (index >= static_cast<int>(registry.entries.size())) return nullptr;
  return &registry.entries[static_cast<std::size_t>(index)].second;
}

std::string_view scene_name(SceneId id) {
  if (const RegisteredScene* registered = registered_scene(id)) return registered->name;
  if (const BuiltinScene* builtin = builtin_scene(id)) return builtin->name;
  return "?";
}

std::optional<SceneId> scene_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kBuiltinScenes.size(); ++i)
    if (kBuiltinScenes[i].name == name) return id_of_row(i);
  for (int i = kFirstRegisteredScene;; ++i) {
    const RegisteredScene* registered = registered_scene(static_cast<SceneId>(i));
    if (!registered) break;
    if (registered->name == name) return static_cast<SceneId>(i);
  }
  return std::nullopt;
}

NormalDetail scene_normal_detail(SceneId id) {
  if (const RegisteredScene* registered = registered_scene(id))
    return registered->has_normal_map ? NormalDetail::normal_map : NormalDetail::none;
  if (const BuiltinScene* builtin = builtin_scene(id)) return builtin->detail;
  return NormalDetail::none;
}

std::span<const SceneId> all_scenes() { return kAnalyticScenes; }
std::span<const SceneId> content_scenes() { return kContentScenes; }

// ---------------------------------------------------------------------------------------------
// Shared content (built once per process; function-local statics are initialised thread-safely)

const PeriodicHeightField& content_height_field() {
  // 8 waves of ~110 cycles per texture tile (4.65 texels per period at 512 texels), slope
  // bound tan(30 deg): no normal tilts more than 30 degrees.
  static const PeriodicHeightField field = PeriodicHeightField::random(0x6e6d6170ULL, 8, 110.0, std::tan(radians(30.0)));
  return field;
}

std::shared_ptr<const NormalMap> content_normal_map() {
  static const std::shared_ptr<const NormalMap> map = [] {
    const PeriodicHeightField& field = content_height_field();
    return std::make_shared<const NormalMap>(kContentNormalMapSize, kContentNormalMapSize,
                                             normals_from_gradient(kContentNormalMapSize, [&](Vec2 uv) { return field.gradient(uv); }));
  }();
  return map;
}

const TorusKnot& content_torus_knot() {
  static const TorusKnot knot{};
  return knot;
}

std::shared_ptr<const TriangleMesh> content_torus_knot_mesh() {
  static const std::shared_ptr<const TriangleMesh> mesh = std::make_shared<const TriangleMesh>(content_torus_knot().mesh());
  return mesh;
}

}  // namespace saagen::measure

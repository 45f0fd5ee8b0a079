// saagen ground-truth renderer: glTF 2.0 assets (.gltf with external or embedded buffers and
// images, .glb) as trade scenes.
//
// Loaded with Debian's tinygltf (libtinygltf-dev; PNG and JPEG decoded by its stb_image) rather
// than assimp: tinygltf keeps glTF's own data model (accessors, nodes, materials with their
// extensions as JSON values, KHR_lights_punctual), so the material fields glTF defines
// (roughness factor x G of metallicRoughnessTexture, normalTexture.scale, KHR_materials_clearcoat,
// KHR_materials_anisotropy) and the TANGENT.w sign are read as the specification states them;
// assimp converts every format to its own material keys and post-processes the mesh
// (aiProcess_CalcTangentSpace is not MikkTSpace).
//
// What is loaded (glTF 2.0 specification, Sec. 3.5 - 3.9; the extensions' READMEs):
//   meshes      every primitive instanced by the nodes of the default scene (scene 0 when none
//               is named), TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN, indexed or not, baked
//               into world space by the nodes' matrices or TRS (normals by the inverse
//               transpose). Each instanced primitive is one connected surface
//               (SurfaceHit::object): a draw call, whose 2x2 quads never take another's pixels.
//   attributes  POSITION (float), NORMAL (float; flat face normals when absent, as the
//               specification requires), TEXCOORD_0 (float or normalised unsigned byte/short),
//               TANGENT (float, w the bitangent sign).
//   tangents    the asset's own; where a primitive has none, generated per vertex
//               (generate_tangents): MikkTSpace's frame, in the image-up parameterisation
//               that glTF's "+Y up" normal textures mean.
//   materials   perceptual roughness = roughnessFactor x G of metallicRoughnessTexture (linear)
//               -> GGX alpha = roughness^2; normalTexture decoded as
//               normalize((2 c - 1) * (scale, scale, 1)); KHR_materials_clearcoat (factor,
//               roughness factor and texture (G), normal texture and scale) and
//               KHR_materials_anisotropy (strength, rotation, texture: R and G a direction,
//               B a strength factor) shades the base lobe (anisotropy.hpp): alpha_t =
//               mix(alpha, 1, s^2) along the rotated direction, alpha_b = alpha across it.
//               The trade shades the base specular lobe: its GGX alpha is the trade's alpha
//               times the square of the roughness texture's G (SurfaceHit::alpha_scale), so
//               the alpha sweep stays the trade's axis and the texture's variation is kept.
//               An asset with clearcoat gets a second scene, NAME-coat (make_gltf_coat_scene):
//               the coat lobe alone, a second filtered lobe on the same geometry, with the
//               coat's normal texture (the geometric normal where it has none, as the
//               extension specifies), its roughness texture's G scaling the trade's alpha, and
//               the weight clearcoatFactor x R of clearcoatTexture (0 on uncoated surfaces,
//               which still occlude); the trade's Fresnel rows are then the extension's coat
//               Fresnel (F0 = 0.04, ior 1.5). In NAME, the base lobe under a coat passes
//               1 - clearcoat F(i.h) of the light (SurfaceTextures::coat), as the extension's
//               layering does.
//   textures    PNG or JPEG, 8 or 16 bits, power-of-two sizes, REPEAT wrapping, TEXCOORD_0:
//               MIP chains of exact 2x2 box means (NormalMap, ScalarMap), trilinear at the
//               quad's implicit LOD in the 1-spp images, level 0 bilinear in the ground truth.
//   camera      the first perspective camera instanced in the scene; else framed from the
//               bounds (frame_bounds).
//   light       the first KHR_lights_punctual light instanced in the scene (directional: its
//               -z axis; point and spot: a point light at the node, spot cones not applied),
//               with irradiance 1 at the bounds' centre (the trade compares images, not
//               photometric units); else a directional light from the camera's upper left.
//
// Refused, with one line "PATH: what is wrong" (GltfError) and nothing rendered: a file that
// cannot be read or parsed (a truncated GLB), an asset or external buffer or image that is no
// regular file (a FIFO would block the read, a device never end) or is beyond the size limit, a required extension not listed above, points
// and lines, sparse or out-of-range accessors, indices beyond the vertices, a material's image
// that is missing or undecodable, textures of another size, wrap mode or texture coordinate
// set (checked on every use), counts beyond GltfLimits (totals checked before the work), a URI
// that is absolute or leaves the asset's folder (before anything is opened), JSON deeper or
// larger than the limits (before it is parsed), an integer beyond 32 bits (tinygltf would
// truncate it into another index), an index that is not a whole number, a material factor
// outside the specification's range, a position that is not finite (or beyond 1e100) after the
// node transforms, all vertices at one point, a degenerate camera or light transform, and an
// asset.version other than 2.x. Text from the asset (names, URIs) is quoted with its control
// characters escaped.
#pragma once

#include "saagen/measure/anisotropy.hpp"
#include "saagen/measure/mesh.hpp"
#include "saagen/measure/normal_map.hpp"
#include "saagen/measure/scalar_map.hpp"
#include "saagen/measure/scene.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace saagen::measure {

// One line: "<path>: <what is wrong>".
class GltfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What one asset may hold, checked before the memory is taken (a vertex costs ~100 bytes, a
// triangle with its BVH share ~200, a decoded normal-map texel with its MIP chain ~120).
// Totals are checked before the work they bound: the asset's JSON is scanned (size, nesting,
// values) before it is parsed, a file is sized before it is read, an image's header is read
// before it is decoded (and only images a material uses are decoded), the node graph's instances
// and their triangles are counted before any is expanded.
struct GltfLimits {
  std::size_t max_triangles = 4'000'000;        // instanced, in all
  std::size_t max_vertices = 12'000'000;        // flat-shaded primitives take 3 per triangle
  int max_texture_size = 4096;                  // texels per side, checked before decoding
  std::size_t max_texels = 4096 * 4096;         // level-0 texels of all texture maps built, together
  std::uintmax_t max_file_bytes = 1ull << 30;   // the asset and each external buffer or image
  std::uintmax_t max_total_bytes = 1ull << 30;  // the asset and every external file it reads, together
  std::size_t max_json_bytes = 64u << 20;       // the JSON (a .gltf file, a .glb's JSON chunk)
  std::size_t max_json_values = 4'000'000;      // values in that JSON (each costs ~0.3 KB parsed)
  int max_json_depth = 64;                      // nesting of its arrays and objects
  std::size_t max_node_instances = 1'000'000;   // node visits of the scene's walk (a node listed
                                                // by two parents is visited twice)
};

struct GltfMaterial {
  std::string name;
  double roughness_factor = 1.0;                   // perceptual
  std::shared_ptr<const ScalarMap> roughness_map;  // G of metallicRoughnessTexture
  std::shared_ptr<const NormalMap> normal_map;     // decoded and scaled
  double normal_scale = 1.0;
  // KHR_materials_clearcoat
  bool clearcoat = false;
  double clearcoat_factor = 0.0;
  double clearcoat_roughness_factor = 0.0;  // perceptual
  std::shared_ptr<const ScalarMap> clearcoat_roughness_map;
  std::shared_ptr<const ScalarMap> clearcoat_map;  // R of clearcoatTexture
  std::shared_ptr<const NormalMap> clearcoat_normal_map;
  double clearcoat_normal_scale = 1.0;
  // KHR_materials_anisotropy
  bool anisotropy = false;
  double anisotropy_strength = 0.0;
  double anisotropy_rotation = 0.0;  // radians
  bool anisotropy_texture = false;
  // The lobe it shades (anisotropy.hpp); null where the material has none, or a zero strength
  // and no texture (isotropic).
  std::shared_ptr<const Anisotropy> anisotropic_lobe;

  // The perceptual roughness the base lobe spans (roughness_factor times the smallest and the
  // largest G of its texture; the factor alone without one), and the coat's likewise.
  std::pair<double, double> roughness_range() const;
  std::pair<double, double> clearcoat_roughness_range() const;
  // "NAME: roughness ..., normal texture ..." (control characters in the name as \xNN).
  std::string describe() const;
  // The same without the name.
  std::string describe_factors() const;
};

struct GltfAsset {
  std::string path;
  std::vector<std::string> files;            // every file read: the asset, then its external buffers and images
  std::string name;                          // the file's stem in [A-Za-z0-9_.-]: the scene's name
  std::shared_ptr<const TriangleMesh> mesh;  // world space; object = instanced primitive
  std::vector<int> object_material;          // per object: index into materials
  std::vector<GltfMaterial> materials;       // the asset's, then the default material
  std::optional<Camera> camera;              // the asset's first perspective camera
  std::optional<Light> light;                // the asset's first punctual light
  Vec3 bounds_lo{}, bounds_hi{};
  int primitives = 0;                                // instanced primitives (objects)
  int generated_tangent_primitives = 0;              // of those, with tangents generated here
  std::shared_ptr<const SurfaceMaterials> surfaces;  // per object textures, for Scene
  // The coat lobe's per object textures and weights; null when no material has a coat.
  std::shared_ptr<const SurfaceMaterials> coat_surfaces;

  bool has_normal_map() const;
  bool has_coat_normal_map() const;
  // Counts, materials and where camera and light come from (for the bench header).
  std::string summary() const;
};

GltfAsset load_gltf(const std::string& path, const GltfLimits& limits = {});

// Per-vertex tangents of an indexed triangle list (TANGENT absent): per triangle, dp/du and
// dp/dv from the uv (Lengyel 2001; PBRT 3 Sec. 3.6.2); at each vertex, dp/du made orthogonal to
// the vertex normal and normalised, summed over the triangles around the vertex weighted by
// their corner angle (MikkTSpace's weighting), normalised; the sign w = +1 where n x t points
// along -dp/dv (glTF's v grows downwards in the image, its normal textures are "+Y up"), -1
// otherwise (the summed dp/dv decides). Where it differs from MikkTSpace (Mikkelsen 2008): the
// vertices are the asset's indexed vertices as given (MikkTSpace first welds those with equal
// position, normal and uv, and splits a vertex whose triangles disagree in handedness or turn
// the tangent by more than its angular threshold), so at a uv mirror seam both sides share the
// majority sign. Vertices with no usable uv gradient get normal_frame_tangent(n), w = +1.
void generate_tangents(std::vector<MeshVertex>& vertices, const std::vector<std::array<int, 3>>& triangles);

// A camera looking at the box's centre from the front (+z), 30 degrees to the right and 20
// degrees above, with a 35-degree square view that holds every corner of the box (5 % margin).
Camera frame_bounds(Vec3 lo, Vec3 hi);

// The trade scene of an asset, rotated about the vertical axis through the bounds' centre.
Scene make_gltf_scene(const std::shared_ptr<const GltfAsset>& asset, double rotation_radians = 0.0);

// The coat lobe's scene of an asset with clearcoat (see the top of this file), named NAME-coat.
// Precondition: asset->coat_surfaces.
Scene make_gltf_coat_scene(const std::shared_ptr<const GltfAsset>& asset, double rotation_radians = 0.0);

// Loads the asset (GltfError on a bad one) and registers it as a scene (register_scene) named
// by its file's stem, keyed by its canonical path: the id the trade takes in
// TradeConfig::scenes. The same path twice gives the same id and loads once.
SceneId register_gltf_scene(const std::string& path, const GltfLimits& limits = {});
// The same, and the asset's coat scene after it when it has clearcoat.
std::vector<SceneId> register_gltf_scenes(const std::string& path, const GltfLimits& limits = {});
// The asset behind a registered glTF scene; null for any other id.
std::shared_ptr<const GltfAsset> gltf_asset_of(SceneId id);
// Whether a registered scene is an asset's coat lobe (make_gltf_coat_scene, NAME-coat).
bool is_gltf_coat_scene(SceneId id);

}  // namespace saagen::measure

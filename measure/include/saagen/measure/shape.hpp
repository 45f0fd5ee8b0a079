// saagen ground-truth renderer: what a shape is to the renderer. A Shape (the analytic shapes of
// scene.hpp, the triangle meshes of mesh.hpp) intersects rays in its object space and returns a
// SurfaceHit: the hit's shading and geometric frames, uv and position derivatives.
#pragma once

#include "saagen/reference/math.hpp"

#include <optional>
#include <string>

namespace saagen::measure {

using ref::Sym2;
using ref::Vec2;
using ref::Vec3;

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit length
};

// What a ray hit provides (world space once returned by Scene::intersect).
//
// Two frames: the shading frame (normal, tangent, bitangent) that the BRDF and the SAA variants
// read, and the geometric frame of the base surface before any normal map (what an engine's
// vertex attributes give): for a mesh the interpolated vertex normal, for the bump plane the
// plane's frame (0, 0, 1), for the sphere, torus and tubes the same as the shading frame. In a
// normal-mapped scene the geometric tangent is the texture tangent (dpdu made orthogonal to the
// geometric normal), the frame the map's tangent-space normals and slopes are expressed in.
// Both frames are right-handed (b = n x t).
//
// uv: the surface parameterisation (texture units once returned by Scene::intersect, i.e. times
// the scene's uv tiling), and dpdu, dpdv the partial derivatives of the position with respect
// to u and v (for a mesh the triangle's constant partials, as a GPU's attribute interpolation).
struct SurfaceHit {
  double t = 0.0;
  Vec3 position;
  Vec3 normal;               // shading normal n (unit)
  Vec3 tangent;              // t (unit, orthogonal to n)
  Vec3 bitangent;            // b = n x t
  int object = 0;            // index of the connected surface (tube index); 0 for single surfaces
  Vec3 geometric_normal;     // base surface normal (unit)
  Vec3 geometric_tangent;    // unit, orthogonal to geometric_normal
  Vec3 geometric_bitangent;  // geometric_normal x geometric_tangent
  Vec2 uv;
  Vec3 dpdu;
  Vec3 dpdv;
  // +1 when dpdv lies on the side of geometric_bitangent (the texture's +v direction is +b),
  // -1 for a mirrored parameterisation (MikkTSpace's bitangent sign).
  double bitangent_sign = 1.0;
  // The factor the surface's roughness texture applies to the material's GGX alpha at the hit
  // (glTF: perceptual roughness = factor x G, so alpha = factor^2 G^2 and this is G^2); 1 on
  // surfaces without one. Scene::intersect fills it from level 0 (bilinear), pixel_fields from
  // the trilinear sample at the quad's LOD.
  double alpha_scale = 1.0;
  // The triangle hit (TriangleMesh; -1 for the analytic shapes): which attribute planes a GPU's
  // helper invocations extrapolate (Scene::extrapolate_surface).
  int triangle = -1;
  // The weight of the lobe at the hit (SurfaceTextures::weight, times its texture): the radiance
  // is multiplied by it; 1 on every built-in scene.
  double weight = 1.0;
  // SurfaceTextures::coat at the hit (times its texture); 0 without a layer above.
  double coat = 0.0;
};

// The first and second moments of the shading normal's slope s = -n.xy / n.z (in the geometric
// frame's axes) over a distribution of surface points: LEAN's two moments (Olano & Baker 2010,
// Sec. 3), E[s] and E[s s^T].
struct SlopeMoments {
  Vec2 mean;
  Sym2 second;
};

// A shape in its object space: the analytic shapes of scene.hpp, TriangleMesh (mesh.hpp).
class Shape {
 public:
  virtual ~Shape() = default;
  // The nearest hit with t > t_min along a ray whose direction has unit length.
  virtual bool intersect(const Ray& ray, double t_min, SurfaceHit& hit) const = 0;
  // Every number that defines the shape (part of the ground-truth cache key).
  virtual std::string describe() const = 0;
  // Procedural normal detail: the slope moments over surface points Gaussian-distributed with
  // mean uv and covariance `footprint` (uv units^2), in closed form; nullopt for shapes whose
  // shading normal has no procedural detail (all but the bump plane).
  virtual std::optional<SlopeMoments> footprint_slope_moments(Vec2 uv, Sym2 footprint) const {
    (void)uv;
    (void)footprint;
    return std::nullopt;
  }
};

}  // namespace saagen::measure

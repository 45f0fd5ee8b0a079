// saagen ground-truth renderer: the anisotropic specular lobe of glTF's KHR_materials_anisotropy.
//
// The extension (Khronos, KHR_materials_anisotropy README, "Anisotropy" and "Implementation",
// https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_materials_anisotropy):
//   direction  d = (cos r, sin r) in the texture's tangent frame, r = anisotropyRotation (radians,
//              counter-clockwise from the tangent); with anisotropyTexture,
//              d = R(r) normalize(2 (R, G) - 1), its red and green channels a direction in
//              [-1, 1]^2 ((1, 0) where they encode none);
//   strength   s = anisotropyStrength, times the texture's blue channel, clamped to [0, 1];
//   frame      anisotropicT = normalize(TBN (d, 0)), anisotropicB = normalize(n x anisotropicT);
//   roughness  alpha_t = mix(alpha, 1, s^2) along anisotropicT, alpha_b = alpha along anisotropicB,
//              the anisotropic GGX of the glTF BRDF (D and V with (alpha_t, alpha_b)).
// Here the frame is kept orthonormal: anisotropicT is TBN (d, 0) made orthogonal to the shading
// normal (Gram-Schmidt, as Scene::apply_normal_map makes the texture tangent), which the
// extension's vector equals wherever the shading normal is the geometric one. three.js's
// MeshPhysicalMaterial (lights_physical_fragment) computes the same alpha_t and frame.
//
// In the renderer (renderer.hpp) an anisotropic surface's shading frame and geometric frame are
// both turned to the anisotropy direction, so that the lobe is axis-aligned there: the ground
// truth evaluates ggx_brdf_axis with (alpha_t^2, alpha_b^2), and every 1-spp form filters that
// roughness in that frame (the matrix and axis forms add their kernel to diag(alpha_t^2, alpha_b^2);
// an isotropic deferred kernel is applied once per axis, as the planner emits it).
#pragma once

#include "saagen/measure/scalar_map.hpp"
#include "saagen/measure/scene.hpp"
#include "saagen/reference/math.hpp"

#include <memory>
#include <string>

namespace saagen::measure {

// One material's KHR_materials_anisotropy (null in SurfaceTextures: isotropic).
struct Anisotropy {
  double strength = 0.0;                   // anisotropyStrength
  Vec2 rotation{1.0, 0.0};                 // (cos r, sin r) of anisotropyRotation
  std::shared_ptr<const ScalarMap> red;    // anisotropyTexture's channels, linear in [0, 1];
  std::shared_ptr<const ScalarMap> green;  // all three null without a texture
  std::shared_ptr<const ScalarMap> blue;

  bool textured() const { return red != nullptr; }
  // Every number that defines it (cache keys).
  std::string describe() const;
};

// The extension's strength and direction at a surface point: direction in the texture's tangent
// frame (x along the tangent, y along the bitangent the normal map's +y means, sign s b).
struct AnisotropySample {
  double strength = 0.0;
  Vec2 direction{1.0, 0.0};
};

// From the texture's (R, G, B) at the point (ignored without a texture).
AnisotropySample anisotropy_from_texel(const Anisotropy& anisotropy, Vec3 rgb);
// The ground truth's sample: the texture's level 0, bilinear (as the normal map's).
AnisotropySample anisotropy_level0(const Anisotropy& anisotropy, Vec2 uv);
// A GPU's sample: trilinear at the texture's implicit LOD from the quad's uv derivatives.
AnisotropySample anisotropy_trilinear(const Anisotropy& anisotropy, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy);

// Turns the hit's geometric frame to t_g' = d.x t_g + s d.y b_g, b_g' = n_g x t_g', and its
// shading frame to t' = normalize(t_g' - (t_g'.n) n), b' = n x t' (s = hit.bitangent_sign).
void apply_anisotropy_frame(SurfaceHit& hit, Vec2 direction);

// (alpha_t^2, alpha_b^2) with alpha_t = mix(alpha, 1, s^2), alpha_b = alpha.
Vec2 anisotropic_alpha2(double alpha, double strength);

// A symmetric matrix given in the texture's tangent frame (x along t_g, y along s b_g, as a LEAN
// covariance of the normal map) expressed in the turned frame (t_g', b_g'): M m M^T with
// M = [d.x, d.y; -s d.y, s d.x].
ref::Sym2 to_anisotropy_frame(ref::Sym2 m, Vec2 direction, double bitangent_sign);

}  // namespace saagen::measure

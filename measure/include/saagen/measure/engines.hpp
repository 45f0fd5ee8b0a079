// saagen ground-truth renderer: the geometric specular AA that engines ship, as trade baselines.
//
// Each function returns the filtered GGX alpha^2 an engine's shipped form produces from the
// material's alpha and the screen-space derivatives of the world-space normal it feeds
// (engine_feed() in renderer.hpp). Forms and constants as read from the engines' own sources
// (shared/REFERENCES.md, "What engines ship"), at the values they use when the feature is on.
// Notation: S = |dn/dx|^2 + |dn/dy|^2, Smax = max(|dn/dx|^2, |dn/dy|^2), a = alpha^2,
// r = perceptual roughness with alpha = r^2.
//
//   HDRP (CommonMaterial.hlsl)      a' = sat(a + min(2 v S, t^2)), v = 0.1, t = 0.2; vertex normal
//   Filament (surface_shading_lit)  a' = sat(a + min(2 V S, T)),   V = 0.15, T = 0.04; geometric
//   Godot 4 (scene_forward_*)       alpha' = min(1, alpha + min(2 amount S, limit)),
//                                   amount 0.25, limit 0.18: the kernel goes to alpha, not a;
//                                   shading normal after normal maps
//   Unreal (NormalCurvatureToRoughness)  r' = max(r, sat(scale Smax^exp + bias)), scale 1,
//                                   exp 0.333, bias 0; vertex normal
//   three.js (lights_physical_fragment)  r' = min(max(r, 0.0525) + g, 1), g the largest
//                                   |component| of dn/dx and dn/dy; geometry normal
//   Babylon.js (PBR, direct lights) r' = max(r, sat(Smax)^0.333); bumped normal
//
// These are reference-renderer rows only: saagen emits none of them.
#pragma once

#include "saagen/reference/math.hpp"

namespace saagen::measure {

double hdrp_alpha2(double alpha, ref::Vec3 dndx, ref::Vec3 dndy);
double filament_alpha2(double alpha, ref::Vec3 dndx, ref::Vec3 dndy);
double godot_alpha2(double alpha, ref::Vec3 dndx, ref::Vec3 dndy);
double unreal_alpha2(double alpha, ref::Vec3 dndx, ref::Vec3 dndy);
double threejs_alpha2(double alpha, ref::Vec3 dndx, ref::Vec3 dndy);
double babylon_alpha2(double alpha, ref::Vec3 dndx, ref::Vec3 dndy);

}  // namespace saagen::measure

// The engines' shipped specular AA forms in float64, written from each engine's own shader source
// (shared/REFERENCES.md names the files), not from saagen's templates: the independent side of
// the preset checks (test_presets.cpp on the reference, test_engines_gpu.cpp on the devices).
#pragma once

#include "saagen/reference/saa.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>

namespace saagen::test {

using ref::Vec3;

inline double clamp01(double x) { return std::min(std::max(x, 0.0), 1.0); }
inline double dot3(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// The engines' forms, as their shader sources write them (shared/REFERENCES.md lists the files).
// Unity HDRP, CommonMaterial.hlsl GeometricNormalFiltering: smoothness in and out.
inline double hdrp(double smoothness, Vec3 du, Vec3 dv) {
  const double screen_space_variance = 0.1, threshold = 0.2;
  const double variance = screen_space_variance * (dot3(du, du) + dot3(dv, dv));
  const double perceptual_roughness = 1.0 - smoothness;
  const double roughness = perceptual_roughness * perceptual_roughness;
  const double squared_roughness = clamp01(roughness * roughness + std::min(2.0 * variance, threshold * threshold));
  return 1.0 - std::sqrt(std::sqrt(squared_roughness));
}

// Filament, surface_shading_lit.fs normalFiltering: perceptual roughness in and out; the
// material's threshold is stored squared; under TAA upscaling the variance is scaled by d^2.
inline double filament(double perceptual_roughness, Vec3 du, Vec3 dv, double taa_scale) {
  const double specular_anti_aliasing_variance = 0.15 * taa_scale * taa_scale;
  const double specular_anti_aliasing_threshold = 0.2 * 0.2;
  const double variance = specular_anti_aliasing_variance * (dot3(du, du) + dot3(dv, dv));
  const double roughness = perceptual_roughness * perceptual_roughness;
  const double kernel_roughness = std::min(2.0 * variance, specular_anti_aliasing_threshold);
  const double square_roughness = clamp01(roughness * roughness + kernel_roughness);
  return std::sqrt(std::sqrt(square_roughness));
}

// O3DE, PBR/SpecularAA.azsli: alpha^2 in and out, 2 * 0.25 S capped at 0.18.
inline double o3de(double alpha2, Vec3 du, Vec3 dv) {
  const double variance = 0.25 * (dot3(du, du) + dot3(dv, dv));
  return clamp01(alpha2 + std::min(2.0 * variance, 0.18));
}

// Bevy's proposal: alpha^2 + min(sigma^2 S, kappa), sigma = 0.5, kappa = 0.18.
inline double bevy(double alpha2, Vec3 du, Vec3 dv) {
  const double sigma = 0.5;
  return clamp01(alpha2 + std::min(sigma * sigma * (dot3(du, du) + dot3(dv, dv)), 0.18));
}

// Tokuyoshi's VSGL code (NDFFiltering.hlsli): alpha^2 + min(S / (2 pi), 0.18).
inline double vsgl(double alpha2, Vec3 du, Vec3 dv) {
  const double pi = 3.14159265358979323846;
  return clamp01(alpha2 + std::min((dot3(du, du) + dot3(dv, dv)) / (2.0 * pi), 0.18));
}

using EngineForm = std::function<double(double, Vec3, Vec3)>;

inline std::map<std::string, EngineForm> engine_forms() {
  return {{"hdrp", hdrp},
          {"filament", [](double r, Vec3 du, Vec3 dv) { return filament(r, du, dv, 1.0); }},
          {"filament-taa", [](double r, Vec3 du, Vec3 dv) { return filament(r, du, dv, 0.5); }},
          {"o3de", o3de},
          {"bevy", bevy},
          {"vsgl", vsgl}};
}

}  // namespace saagen::test

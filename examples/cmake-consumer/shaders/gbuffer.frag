#version 450
// G-buffer pass of a deferred renderer (gbuffer_default in scene.saagen.toml): saagen's advice for
// normal-mapped content (`saagen plan`) gives deferred-sum fed the geometric normal, with the
// normal map baked into the roughness. The half vector is unknown here, so the roughness is
// widened from the screen derivatives of the normal and stored filtered; the lighting pass shades
// it with the tail-preserving filtered GGX.
#include "saa_scene.glsl"

layout(location = 0) in vec3 in_normal_ws;
layout(location = 1) in vec4 in_tangent_ws;
layout(location = 2) in vec2 in_uv;

layout(set = 1, binding = 0) uniform MaterialParameters {
  float alpha;  // GGX alpha, the normal map's variance baked in (saagen texture prefilter --method hdrp)
} material;
layout(set = 1, binding = 1) uniform sampler2D normal_map;

layout(location = 0) out vec4 out_normal_ws;  // xyz: unit normal
layout(location = 1) out vec4 out_alpha2;     // x: filtered alpha^2

void main() {
  vec3 geometric = normalize(in_normal_ws);
  vec3 t = normalize(in_tangent_ws.xyz - geometric * dot(geometric, in_tangent_ws.xyz));
  vec3 b = cross(geometric, t) * in_tangent_ws.w;
  // One MIP level coarser than the implicit LOD, as the bake (saagen's advice: docs/PREFILTER.md,
  // "The LOD bias"; a baked roughness texture is sampled with the same bias).
  vec3 mapped = texture(normal_map, in_uv, 1.0).xyz * 2.0 - 1.0;
  vec3 n = normalize(t * mapped.x + b * mapped.y + geometric * mapped.z);

  out_normal_ws = vec4(n, 0.0);
  out_alpha2 = vec4(saa_deferred_sum_fragment(material.alpha * material.alpha, geometric));
}

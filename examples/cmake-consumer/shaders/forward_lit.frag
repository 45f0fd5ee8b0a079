#version 450
// Forward pass of an anisotropic, normal-mapped material (car_paint in scene.saagen.toml): saagen's
// advice for normal-mapped content (`saagen plan`) gives an anisotropic material the matrix form,
// forward-aniso-projected, fed the geometric normal (its kernel added to the anisotropic roughness
// matrix), the normal map baked into the roughness, and the tail-preserving filtered GGX.
#include "saa_scene.glsl"

layout(location = 0) in vec3 in_position_ws;
layout(location = 1) in vec3 in_normal_ws;
layout(location = 2) in vec4 in_tangent_ws;  // xyz: tangent, w: bitangent sign
layout(location = 3) in vec2 in_uv;

layout(set = 0, binding = 0) uniform Frame {
  vec4 camera_position_ws;
  vec4 light_direction_ws;  // towards the light
  vec4 light_radiance;
} frame;
layout(set = 1, binding = 0) uniform MaterialParameters {
  // GGX alpha along the tangent and the bitangent, with the normal map's variance baked in
  // (`saagen texture prefilter NORMAL_MAP -o OUT.ktx2 --method hdrp --roughness R --gltf`).
  vec2 alpha;
} material;
layout(set = 1, binding = 1) uniform sampler2D normal_map;  // tangent space

layout(location = 0) out vec4 out_radiance;

void main() {
  // The filter measures the geometric frame (the map's detail is in the baked roughness); the
  // BRDF shades in the frame of the normal-mapped normal.
  vec3 l = normalize(frame.light_direction_ws.xyz);
  vec3 v = normalize(frame.camera_position_ws.xyz - in_position_ws);
  vec3 n = normalize(in_normal_ws);
  vec3 t = normalize(in_tangent_ws.xyz - n * dot(n, in_tangent_ws.xyz));
  vec3 b = cross(n, t) * in_tangent_ws.w;
  // The filter reads the world-space half vector in the geometric frame (the transported wrapper,
  // as saagen plans it: the frame's turn about the normal between pixels is not read as curvature).
  vec3 filtered = saa_forward_aniso_projected_transported_fragment(material.alpha * material.alpha, normalize(l + v), n, t, b);
  // One MIP level coarser than the implicit LOD, as the bake (saagen's advice: docs/PREFILTER.md,
  // "The LOD bias"; a baked roughness texture is sampled with the same bias).
  vec3 mapped = texture(normal_map, in_uv, 1.0).xyz * 2.0 - 1.0;
  n = normalize(t * mapped.x + b * mapped.y + n * mapped.z);
  t = normalize(t - n * dot(n, t));
  b = cross(n, t) * in_tangent_ws.w;
  vec3 i_ts = vec3(dot(l, t), dot(l, b), dot(l, n));
  vec3 o_ts = vec3(dot(v, t), dot(v, b), dot(v, n));

  vec2 alpha2 = material.alpha * material.alpha;
  float specular = saa_ggx_brdf_filtered_matrix(i_ts, o_ts, filtered, alpha2);
  out_radiance = vec4(frame.light_radiance.rgb * specular * max(i_ts.z, 0.0), 1.0);
}

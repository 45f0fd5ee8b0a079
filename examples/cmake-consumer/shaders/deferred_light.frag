#version 450
// Lighting pass of the deferred renderer (gbuffer_default in scene.saagen.toml): one directional
// light over the G-buffer that gbuffer.frag wrote, shaded with the tail-preserving filtered GGX of
// the stored filtered alpha^2 (`saagen plan`: the BRDF planned with deferred-sum). The tangent
// frame is built from the stored normal alone, as the isotropic lobe allows.
#include "saa_scene.glsl"

layout(location = 0) in vec2 in_screen_uv;

layout(set = 0, binding = 0) uniform Frame {
  vec4 camera_position_ws;
  vec4 light_direction_ws;  // towards the light
  vec4 light_radiance;
} frame;
layout(set = 1, binding = 0) uniform sampler2D gbuffer_normal;    // xyz: unit normal
layout(set = 1, binding = 1) uniform sampler2D gbuffer_alpha2;    // x: filtered alpha^2
layout(set = 1, binding = 2) uniform sampler2D gbuffer_position;  // xyz: world position
layout(set = 1, binding = 3) uniform MaterialParameters {
  float alpha;  // the material's GGX alpha, the normal map's variance baked in
} material;

layout(location = 0) out vec4 out_radiance;

void main() {
  vec3 n = normalize(texture(gbuffer_normal, in_screen_uv).xyz);
  float filtered = texture(gbuffer_alpha2, in_screen_uv).x;
  vec3 position = texture(gbuffer_position, in_screen_uv).xyz;
  vec3 l = normalize(frame.light_direction_ws.xyz);
  vec3 v = normalize(frame.camera_position_ws.xyz - position);
  vec3 t = normalize(abs(n.z) < 0.999 ? cross(vec3(0.0, 0.0, 1.0), n) : cross(vec3(1.0, 0.0, 0.0), n));
  vec3 b = cross(n, t);
  vec3 i_ts = vec3(dot(l, t), dot(l, b), dot(l, n));
  vec3 o_ts = vec3(dot(v, t), dot(v, b), dot(v, n));
  float alpha2 = material.alpha * material.alpha;
  float specular = saa_ggx_brdf_filtered_axis(i_ts, o_ts, vec2(filtered), vec2(alpha2));
  out_radiance = vec4(frame.light_radiance.rgb * specular * max(i_ts.z, 0.0), 1.0);
}

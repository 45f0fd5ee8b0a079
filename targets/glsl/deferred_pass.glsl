// GLSL skeleton of the deferred roughness-limiter compute pass (saagen/deferred_pass.hpp):
// prologue before the emitted file, resources and main after it, tangent_resources only for
// passes that read the tangent G-buffer. Placeholders: {prefix}, {output_format}, {plain_ddx},
// {plain_ddy} and {body}, the statements that read the G-buffer, call the filter and store.
// baseline: a whole pass with the passes' interface (deferred_pass_abi) that copies the roughness
// (the normal is read and enters the result through a term that cannot be folded away), which
// `saagen bench --isa` measures every pass against.
// saagen-section: prologue
#version 450
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_quad : require
#extension GL_EXT_samplerless_texture_functions : require

// A compute shader has no dFdx/dFdy: lanes form 2x2 pixel quads (four consecutive subgroup
// invocations) and the derivatives of the included file become subgroup quad operations.
float saagen_quad_sign_x;
float saagen_quad_sign_y;
#define dFdxCoarse(v) (subgroupQuadBroadcast((v), 1u) - subgroupQuadBroadcast((v), 0u))
#define dFdyCoarse(v) (subgroupQuadBroadcast((v), 2u) - subgroupQuadBroadcast((v), 0u))
#define dFdxFine(v) ((subgroupQuadSwapHorizontal(v) - (v)) * saagen_quad_sign_x)
#define dFdyFine(v) ((subgroupQuadSwapVertical(v) - (v)) * saagen_quad_sign_y)
#define dFdx(v) {plain_ddx}(v)
#define dFdy(v) {plain_ddy}(v)
// saagen-section: resources
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform texture2D {prefix}pass_normal;
layout(set = 0, binding = 1) uniform texture2D {prefix}pass_roughness;
layout(set = 0, binding = 2, {output_format}) uniform writeonly image2D {prefix}pass_output;
layout(push_constant) uniform {prefix}pass_constants_block
{
    uvec2 size;              // image size in pixels
    uint roughness_channel;  // 0..3: the roughness G-buffer channel read
    uint flags;              // bits 0-1: domain (0 alpha^2, 1 alpha, 2 perceptual r = sqrt(alpha), 3 smoothness 1 - r); 4: normal unorm; 8: tangent unorm
} {prefix}pass_constants;
#define SAAGEN_NORMAL_TEXEL texelFetch({prefix}pass_normal, saagen_source, 0)
#define SAAGEN_ROUGHNESS texelFetch({prefix}pass_roughness, saagen_source, 0)[{prefix}pass_constants.roughness_channel & 3u]
#define SAAGEN_DOMAIN int({prefix}pass_constants.flags & 3u)
#define SAAGEN_NORMAL_UNORM (({prefix}pass_constants.flags & 4u) != 0u)
#define SAAGEN_TANGENT_UNORM (({prefix}pass_constants.flags & 8u) != 0u)
#define SAAGEN_STORE(v) if (saagen_inside) imageStore({prefix}pass_output, ivec2(saagen_pixel), vec4((v), 0.0, 0.0, 1.0))
// saagen-section: tangent_resources
layout(set = 0, binding = 3) uniform texture2D {prefix}pass_tangent;
#define SAAGEN_TANGENT_TEXEL texelFetch({prefix}pass_tangent, saagen_source, 0)
// saagen-section: main
void main()
{
    // Consecutive subgroup lanes in fours are Vulkan's quads; the 16 quads of a workgroup tile
    // 8 x 8 pixels (4 x 4 quads of 2 x 2 pixels).
    uint saagen_lane = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
    uint saagen_quad = saagen_lane >> 2u;
    uvec2 saagen_pixel = gl_WorkGroupID.xy * 8u + 2u * uvec2(saagen_quad & 3u, saagen_quad >> 2u) + uvec2(saagen_lane & 1u, (saagen_lane >> 1u) & 1u);
    // Lanes past the right or bottom edge read the edge texel and write nothing.
    ivec2 saagen_source = ivec2(min(saagen_pixel, {prefix}pass_constants.size - 1u));
    bool saagen_inside = all(lessThan(saagen_pixel, {prefix}pass_constants.size));
    vec2 saagen_frag_coord = vec2(saagen_pixel) + vec2(0.5);
    saagen_quad_sign_x = (gl_SubgroupInvocationID & 1u) == 0u ? 1.0 : -1.0;
    saagen_quad_sign_y = (gl_SubgroupInvocationID & 2u) == 0u ? 1.0 : -1.0;
{body}}
// saagen-section: baseline
#version 450
#extension GL_EXT_samplerless_texture_functions : require
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform texture2D normal_gbuffer;
layout(set = 0, binding = 1) uniform texture2D roughness_gbuffer;
layout(set = 0, binding = 2, r32f) uniform writeonly image2D filtered;
layout(push_constant) uniform Constants { uvec2 size; uint roughness_channel; uint flags; } constants;
void main()
{
    uint lane = gl_LocalInvocationIndex;
    uvec2 pixel = gl_WorkGroupID.xy * 8u + uvec2(lane & 7u, lane >> 3u);
    ivec2 source = ivec2(min(pixel, constants.size - 1u));
    vec3 n = texelFetch(normal_gbuffer, source, 0).xyz;
    float r = texelFetch(roughness_gbuffer, source, 0)[constants.roughness_channel & 3u];
    if (all(lessThan(pixel, constants.size))) imageStore(filtered, ivec2(pixel), vec4(min(r, r + abs(n.x) * 1e-30)));
}

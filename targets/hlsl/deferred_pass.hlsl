// HLSL skeleton of the deferred roughness-limiter compute pass (saagen/deferred_pass.hpp):
// prologue before the emitted file, resources and main after it, tangent_resources only for
// passes that read the tangent G-buffer. Placeholders: {prefix}, {output_format}, {plain_ddx},
// {plain_ddy} and {body}, the statements that read the G-buffer, call the filter and store.
// baseline: a whole pass with the passes' interface (deferred_pass_abi) that copies the roughness
// (the normal is read and enters the result through a term that cannot be folded away), which
// `saagen bench --isa` measures every pass against.
// saagen-section: prologue
// A compute shader has no ddx/ddy: lanes form 2x2 pixel quads (four consecutive wave lanes)
// and the derivatives of the included file become quad wave operations (SM 6.0).
static float saagen_quad_sign_x;
static float saagen_quad_sign_y;
#define ddx_coarse(v) (QuadReadLaneAt((v), 1) - QuadReadLaneAt((v), 0))
#define ddy_coarse(v) (QuadReadLaneAt((v), 2) - QuadReadLaneAt((v), 0))
#define ddx_fine(v) ((QuadReadAcrossX(v) - (v)) * saagen_quad_sign_x)
#define ddy_fine(v) ((QuadReadAcrossY(v) - (v)) * saagen_quad_sign_y)
#define ddx(v) {plain_ddx}(v)
#define ddy(v) {plain_ddy}(v)
// saagen-section: resources
[[vk::binding(0, 0)]] Texture2D<float4> {prefix}pass_normal : register(t0);
[[vk::binding(1, 0)]] Texture2D<float4> {prefix}pass_roughness : register(t1);
// DXC reads vk::image_format; glslang ignores it and declares R32f.
[[vk::binding(2, 0)]] [[vk::image_format("{output_format}")]] RWTexture2D<float> {prefix}pass_output : register(u0);
struct {prefix}pass_constants_block
{
    uint2 size;              // image size in pixels
    uint roughness_channel;  // 0..3: the roughness G-buffer channel read
    uint flags;              // bits 0-1: domain (0 alpha^2, 1 alpha, 2 perceptual r = sqrt(alpha), 3 smoothness 1 - r); 4: normal unorm; 8: tangent unorm
};
[[vk::push_constant]] ConstantBuffer<{prefix}pass_constants_block> {prefix}pass_constants;
#define SAAGEN_NORMAL_TEXEL {prefix}pass_normal.Load(int3(saagen_source, 0))
#define SAAGEN_ROUGHNESS {prefix}pass_roughness.Load(int3(saagen_source, 0))[{prefix}pass_constants.roughness_channel & 3]
#define SAAGEN_DOMAIN int({prefix}pass_constants.flags & 3)
#define SAAGEN_NORMAL_UNORM (({prefix}pass_constants.flags & 4) != 0)
#define SAAGEN_TANGENT_UNORM (({prefix}pass_constants.flags & 8) != 0)
#define SAAGEN_STORE(v) if (saagen_inside) {prefix}pass_output[saagen_pixel] = (v)
// saagen-section: tangent_resources
[[vk::binding(3, 0)]] Texture2D<float4> {prefix}pass_tangent : register(t2);
#define SAAGEN_TANGENT_TEXEL {prefix}pass_tangent.Load(int3(saagen_source, 0))
// saagen-section: main
[numthreads(64, 1, 1)]
void main(uint3 saagen_group : SV_GroupID, uint saagen_group_index : SV_GroupIndex)
{
    // Consecutive wave lanes in fours are quads (waves assumed to hold consecutive group
    // indices); the 16 quads of a group tile 8 x 8 pixels (4 x 4 quads of 2 x 2 pixels).
    uint saagen_lane_count = WaveGetLaneCount();
    uint saagen_lane = (saagen_group_index / saagen_lane_count) * saagen_lane_count + WaveGetLaneIndex();
    uint saagen_quad = saagen_lane >> 2;
    uint2 saagen_pixel = saagen_group.xy * 8 + 2 * uint2(saagen_quad & 3, saagen_quad >> 2) + uint2(saagen_lane & 1, (saagen_lane >> 1) & 1);
    // Lanes past the right or bottom edge read the edge texel and write nothing.
    int2 saagen_source = int2(min(saagen_pixel, {prefix}pass_constants.size - 1));
    bool saagen_inside = all(saagen_pixel < {prefix}pass_constants.size);
    float2 saagen_frag_coord = float2(saagen_pixel) + float2(0.5, 0.5);
    saagen_quad_sign_x = (WaveGetLaneIndex() & 1) == 0 ? 1.0 : -1.0;
    saagen_quad_sign_y = (WaveGetLaneIndex() & 2) == 0 ? 1.0 : -1.0;
{body}}
// saagen-section: baseline
[[vk::binding(0, 0)]] Texture2D<float4> normal_gbuffer : register(t0);
[[vk::binding(1, 0)]] Texture2D<float4> roughness_gbuffer : register(t1);
[[vk::binding(2, 0)]] RWTexture2D<float> filtered : register(u0);
struct Constants { uint2 size; uint roughness_channel; uint flags; };
[[vk::push_constant]] ConstantBuffer<Constants> constants;
[numthreads(64, 1, 1)]
void main(uint3 group : SV_GroupID, uint lane : SV_GroupIndex)
{
    uint2 pixel = group.xy * 8 + uint2(lane & 7, lane >> 3);
    int2 source = int2(min(pixel, constants.size - 1));
    float3 n = normal_gbuffer.Load(int3(source, 0)).xyz;
    float r = roughness_gbuffer.Load(int3(source, 0))[constants.roughness_channel & 3];
    if (all(pixel < constants.size)) filtered[pixel] = min(r, r + abs(n.x) * 1e-30);
}

// HLSL skeleton of a "quad_compute" kernel that runs emitted functions over buffers (saagen/kernels.hpp).
// Section prologue goes before the emitted file, epilogue after it. Placeholders: {workgroup_size},
// {input_stride}, {output_stride}, {width}, {plain_ddx}, {plain_ddy}, {core_only_macro}, and {body},
// the statements that load the inputs, call the functions and store the results.
// saagen-section: prologue
static float saagen_quad_sign_x;
static float saagen_quad_sign_y;
#define ddx_coarse(v) (QuadReadLaneAt((v), 1) - QuadReadLaneAt((v), 0))
#define ddy_coarse(v) (QuadReadLaneAt((v), 2) - QuadReadLaneAt((v), 0))
#define ddx_fine(v) ((QuadReadAcrossX(v) - (v)) * saagen_quad_sign_x)
#define ddy_fine(v) ((QuadReadAcrossY(v) - (v)) * saagen_quad_sign_y)
#define ddx(v) {plain_ddx}(v)
#define ddy(v) {plain_ddy}(v)
// saagen-section: epilogue
[[vk::binding(0, 0)]] StructuredBuffer<float> saagen_in;
[[vk::binding(1, 0)]] RWStructuredBuffer<float> saagen_out;
#define SAAGEN_LOAD(i) saagen_in[uint(i)]
#define SAAGEN_STORE(i, v) saagen_out[saagen_index * {output_stride} + uint(i)] = (v)
[numthreads({workgroup_size}, 1, 1)]
void main(uint3 saagen_id : SV_DispatchThreadID)
{
    uint saagen_lane = saagen_id.x;
    uint saagen_quad = saagen_lane >> 2;
    uint2 saagen_pixel = 2 * uint2(saagen_quad % ({width} / 2), saagen_quad / ({width} / 2)) + uint2(saagen_lane & 1, (saagen_lane >> 1) & 1);
    uint saagen_index = saagen_pixel.y * {width} + saagen_pixel.x;
    float2 saagen_frag_coord = float2(saagen_pixel) + float2(0.5, 0.5);
    saagen_quad_sign_x = (saagen_lane & 1) == 0 ? 1.0 : -1.0;
    saagen_quad_sign_y = (saagen_lane & 2) == 0 ? 1.0 : -1.0;
{body}}

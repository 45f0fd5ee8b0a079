// GLSL skeleton of a "quad_compute" kernel that runs emitted functions over buffers (saagen/kernels.hpp).
// Section prologue goes before the emitted file, epilogue after it. Placeholders: {workgroup_size},
// {input_stride}, {output_stride}, {width}, {plain_ddx}, {plain_ddy}, {core_only_macro}, and {body},
// the statements that load the inputs, call the functions and store the results.
// saagen-section: prologue
#version 450
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_quad : require
float saagen_quad_sign_x;
float saagen_quad_sign_y;
#define dFdxCoarse(v) (subgroupQuadBroadcast((v), 1u) - subgroupQuadBroadcast((v), 0u))
#define dFdyCoarse(v) (subgroupQuadBroadcast((v), 2u) - subgroupQuadBroadcast((v), 0u))
#define dFdxFine(v) ((subgroupQuadSwapHorizontal(v) - (v)) * saagen_quad_sign_x)
#define dFdyFine(v) ((subgroupQuadSwapVertical(v) - (v)) * saagen_quad_sign_y)
#define dFdx(v) {plain_ddx}(v)
#define dFdy(v) {plain_ddy}(v)
// saagen-section: epilogue
layout(local_size_x = {workgroup_size}) in;
layout(std430, binding = 0) readonly buffer SaagenIn { float data[]; } saagen_in;
layout(std430, binding = 1) writeonly buffer SaagenOut { float data[]; } saagen_out;
#define SAAGEN_LOAD(i) saagen_in.data[uint(i)]
#define SAAGEN_STORE(i, v) saagen_out.data[saagen_index * {output_stride}u + uint(i)] = (v)
void main()
{
    uint saagen_lane = gl_GlobalInvocationID.x;
    uint saagen_quad = saagen_lane >> 2u;
    uvec2 saagen_pixel = 2u * uvec2(saagen_quad % ({width}u / 2u), saagen_quad / ({width}u / 2u)) + uvec2(saagen_lane & 1u, (saagen_lane >> 1u) & 1u);
    uint saagen_index = saagen_pixel.y * {width}u + saagen_pixel.x;
    vec2 saagen_frag_coord = vec2(saagen_pixel) + vec2(0.5);
    saagen_quad_sign_x = (saagen_lane & 1u) == 0u ? 1.0 : -1.0;
    saagen_quad_sign_y = (saagen_lane & 2u) == 0u ? 1.0 : -1.0;
{body}}

// HLSL skeleton of a "fragment" kernel that runs emitted functions over buffers (saagen/kernels.hpp).
// Section prologue goes before the emitted file, epilogue after it. Placeholders: {workgroup_size},
// {input_stride}, {output_stride}, {width}, {plain_ddx}, {plain_ddy}, {core_only_macro}, and {body},
// the statements that load the inputs, call the functions and store the results.
// saagen-section: prologue
// saagen-section: epilogue
[[vk::binding(0, 0)]] StructuredBuffer<float> saagen_in;
[[vk::binding(1, 0)]] RWStructuredBuffer<float> saagen_out;
#define SAAGEN_LOAD(i) saagen_in[uint(i)]
#define SAAGEN_STORE(i, v) saagen_out[saagen_index * {output_stride} + uint(i)] = (v)
float4 main(float4 saagen_position : SV_Position) : SV_Target0
{
    float2 saagen_frag_coord = saagen_position.xy;
    uint saagen_index = uint(saagen_frag_coord.y) * {width} + uint(saagen_frag_coord.x);
{body}    return float4(0.0, 0.0, 0.0, 0.0);
}

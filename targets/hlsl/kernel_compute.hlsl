// HLSL skeleton of a "compute" kernel that runs emitted functions over buffers (saagen/kernels.hpp).
// Section prologue goes before the emitted file, epilogue after it. Placeholders: {workgroup_size},
// {input_stride}, {output_stride}, {width}, {plain_ddx}, {plain_ddy}, {core_only_macro}, and {body},
// the statements that load the inputs, call the functions and store the results.
// saagen-section: prologue
#define {core_only_macro}
// saagen-section: epilogue
[[vk::binding(0, 0)]] StructuredBuffer<float> saagen_in;
[[vk::binding(1, 0)]] RWStructuredBuffer<float> saagen_out;
#define SAAGEN_LOAD(i) saagen_in[saagen_index * {input_stride} + uint(i)]
#define SAAGEN_STORE(i, v) saagen_out[saagen_index * {output_stride} + uint(i)] = (v)
[numthreads({workgroup_size}, 1, 1)]
void main(uint3 saagen_id : SV_DispatchThreadID)
{
    uint saagen_index = saagen_id.x;
{body}}

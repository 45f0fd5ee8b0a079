// GLSL skeleton of a "compute" kernel that runs emitted functions over buffers (saagen/kernels.hpp).
// Section prologue goes before the emitted file, epilogue after it. Placeholders: {workgroup_size},
// {input_stride}, {output_stride}, {width}, {plain_ddx}, {plain_ddy}, {core_only_macro}, and {body},
// the statements that load the inputs, call the functions and store the results.
// saagen-section: prologue
#version 450
#define {core_only_macro}
// saagen-section: epilogue
layout(local_size_x = {workgroup_size}) in;
layout(std430, binding = 0) readonly buffer SaagenIn { float data[]; } saagen_in;
layout(std430, binding = 1) writeonly buffer SaagenOut { float data[]; } saagen_out;
#define SAAGEN_LOAD(i) saagen_in.data[saagen_index * {input_stride}u + uint(i)]
#define SAAGEN_STORE(i, v) saagen_out.data[saagen_index * {output_stride}u + uint(i)] = (v)
void main()
{
    uint saagen_index = gl_GlobalInvocationID.x;
{body}}

// GLSL skeleton of a "fragment" kernel that runs emitted functions over buffers (saagen/kernels.hpp).
// Section prologue goes before the emitted file, epilogue after it. Placeholders: {workgroup_size},
// {input_stride}, {output_stride}, {width}, {plain_ddx}, {plain_ddy}, {core_only_macro}, and {body},
// the statements that load the inputs, call the functions and store the results.
// saagen-section: prologue
#version 450
// saagen-section: epilogue
layout(std430, binding = 0) readonly buffer SaagenIn { float data[]; } saagen_in;
layout(std430, binding = 1) writeonly buffer SaagenOut { float data[]; } saagen_out;
layout(location = 0) out vec4 saagen_color;
#define SAAGEN_LOAD(i) saagen_in.data[uint(i)]
#define SAAGEN_STORE(i, v) saagen_out.data[saagen_index * {output_stride}u + uint(i)] = (v)
void main()
{
    vec2 saagen_frag_coord = gl_FragCoord.xy;
    uint saagen_index = uint(saagen_frag_coord.y) * {width}u + uint(saagen_frag_coord.x);
{body}    saagen_color = vec4(0.0);
}

// WGSL skeleton of a "fragment" kernel that runs emitted functions over buffers (saagen/kernels.hpp):
// one fragment per pixel of a full-screen triangle, real dpdx/dpdy. The inputs are shared by all
// pixels; each pixel writes {output_stride} floats at (y * {width} + x) * {output_stride}.
// Placeholders as in kernel_compute.wgsl, and {real2}, the precision's 2-vector type.
// saagen-section: prologue
// saagen-section: epilogue
@group(0) @binding(0) var<storage, read> saagen_input: array<f32>;
@group(0) @binding(1) var<storage, read_write> saagen_output: array<f32>;
var<private> saagen_element: u32;

fn saagen_load(i: i32) -> {real} {
    return {real}(saagen_input[u32(i)]);
}

fn saagen_store(i: i32, v: {real}) {
    saagen_output[saagen_element * {output_stride}u + u32(i)] = f32(v);
}

@fragment
fn fs(@builtin(position) saagen_position: vec4<f32>) -> @location(0) vec4<f32> {
    saagen_element = u32(saagen_position.y) * {width}u + u32(saagen_position.x);
    let saagen_index = i32(saagen_element);
    let saagen_frag_coord = {real2}(saagen_position.xy);
{body}    return vec4<f32>(0.0);
}

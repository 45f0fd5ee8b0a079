// WGSL skeleton of a "compute" kernel that runs emitted functions over buffers (saagen/kernels.hpp):
// one invocation per element. Placeholders: {workgroup_size}, {input_stride}, {output_stride},
// {real} (the emission precision's scalar type) and {body}, the statements that load the inputs,
// call the functions and store the results (SAAGEN_LOAD and SAAGEN_STORE print as saagen_load and
// saagen_store).
// saagen-section: prologue
// saagen-section: epilogue
@group(0) @binding(0) var<storage, read> saagen_input: array<f32>;
@group(0) @binding(1) var<storage, read_write> saagen_output: array<f32>;
var<private> saagen_element: u32;

fn saagen_load(i: i32) -> {real} {
    return {real}(saagen_input[saagen_element * {input_stride}u + u32(i)]);
}

fn saagen_store(i: i32, v: {real}) {
    saagen_output[saagen_element * {output_stride}u + u32(i)] = f32(v);
}

@compute @workgroup_size({workgroup_size})
fn main(@builtin(global_invocation_id) saagen_id: vec3<u32>) {
    saagen_element = saagen_id.x;
    let saagen_index = i32(saagen_id.x);
{body}}

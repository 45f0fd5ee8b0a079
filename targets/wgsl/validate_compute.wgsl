// WGSL skeleton that validates an emitted module in a compute entry point (saagen validate; see
// generator/validate/validation.cpp): the calls leave out the [fragment] functions, which WGSL allows
// in a module used by compute entry points as long as none of them calls one.
// saagen-section: prologue
// saagen-section: epilogue
@group(0) @binding(0) var<storage, read_write> saagen_io: array<vec4<f32>, 2>;

@compute @workgroup_size(1)
fn saagen_validate_compute() {
    let saagen_seed = {real4}(saagen_io[0]);
    var acc: {real} = {real}(0.0);
{calls}    saagen_io[1] = vec4<f32>(f32(acc));
}

// WGSL skeleton that validates an emitted module in a fragment entry point (saagen validate; see
// generator/validate/validation.cpp). WGSL has no includes: the module is compiled as prologue + the
// emitted module + epilogue, one WGSL module. {calls} is one statement per public function;
// The seed is the pixel position, which no compiler can fold; {real} and {real4} spell the emission precision's scalar and vector types.
// saagen-section: prologue
// saagen-section: epilogue
@fragment
fn saagen_validate_fragment(@builtin(position) saagen_position: vec4<f32>) -> @location(0) vec4<f32> {
    let saagen_seed = {real4}(saagen_position);
    var acc: {real} = {real}(0.0);
{calls}    return vec4<f32>(f32(acc));
}

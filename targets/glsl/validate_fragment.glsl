// GLSL skeleton that validates an emitted file in a fragment shader (saagen validate; see
// generator/validate/validation.cpp). Section prologue goes before the emitted file, epilogue after it;
// {core_only_macro} is the CORE_ONLY macro of the emission and {calls} one statement per function.
// saagen-section: prologue
#version 450
// saagen-section: epilogue
layout(location = 0) in vec4 saagen_seed;
layout(location = 0) out vec4 saagen_result;
void main()
{
    float acc = 0.0;
{calls}    saagen_result = vec4(acc);
}

// GLSL ES 3.00 skeleton that validates an emitted file in a fragment shader (saagen validate; see
// generator/validate/validation.cpp). Section prologue goes before the emitted file, epilogue after it;
// {core_only_macro} is the CORE_ONLY macro of the emission and {calls} one statement per function.
// saagen-section: prologue
#version 300 es
// saagen-section: epilogue
in highp vec4 saagen_seed;
layout(location = 0) out highp vec4 saagen_result;
void main()
{
    highp float acc = 0.0;
{calls}    saagen_result = vec4(acc);
}

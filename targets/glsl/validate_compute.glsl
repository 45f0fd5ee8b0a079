// GLSL skeleton that validates an emitted file in a compute shader (saagen validate; see
// generator/validate/validation.cpp). Section prologue goes before the emitted file, epilogue after it;
// {core_only_macro} is the CORE_ONLY macro of the emission and {calls} one statement per function.
// saagen-section: prologue
#version 450
#define {core_only_macro}
// saagen-section: epilogue
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer SaagenIo { vec4 seed; float result; } saagen_io;
void main()
{
    vec4 saagen_seed = saagen_io.seed;
    float acc = 0.0;
{calls}    saagen_io.result = acc;
}

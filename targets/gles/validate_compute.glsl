// GLSL ES 3.00 skeleton that validates an emitted file under CORE_ONLY in a vertex shader (ES 3.00
// has no compute stage; the table's core_stage; saagen validate, generator/validate/validation.cpp). Section
// prologue goes before the emitted file, epilogue after it; {core_only_macro} is the CORE_ONLY macro
// of the emission and {calls} one statement per function.
// saagen-section: prologue
#version 300 es
#define {core_only_macro}
// saagen-section: epilogue
in highp vec4 saagen_seed;
out highp float saagen_result;
void main()
{
    highp float acc = 0.0;
{calls}    saagen_result = acc;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}

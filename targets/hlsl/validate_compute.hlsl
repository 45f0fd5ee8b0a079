// HLSL skeleton that validates an emitted file in a compute shader (saagen validate; see
// generator/validate/validation.cpp). Section prologue goes before the emitted file, epilogue after it;
// {core_only_macro} is the CORE_ONLY macro of the emission and {calls} one statement per function.
// saagen-section: prologue
#define {core_only_macro}
// saagen-section: epilogue
RWStructuredBuffer<float4> saagen_io : register(u0);
[numthreads(1, 1, 1)]
void main()
{
    float4 saagen_seed = saagen_io[0];
    float acc = 0.0;
{calls}    saagen_io[1] = float4(acc, acc, acc, acc);
}

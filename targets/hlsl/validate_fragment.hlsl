// HLSL skeleton that validates an emitted file in a fragment shader (saagen validate; see
// generator/validate/validation.cpp). Section prologue goes before the emitted file, epilogue after it;
// {core_only_macro} is the CORE_ONLY macro of the emission and {calls} one statement per function.
// saagen-section: prologue
// saagen-section: epilogue
float4 main(float4 saagen_seed : TEXCOORD0) : SV_Target0
{
    float acc = 0.0;
{calls}    return float4(acc, acc, acc, acc);
}

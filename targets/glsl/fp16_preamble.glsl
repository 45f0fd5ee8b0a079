// GLSL preamble of fp16 emissions: written once before the constants and functions of every
// emitted file. {prefix} and {macro_prefix} are those of the emission.
// saagen-section: preamble
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#ifndef {macro_prefix}CORE_ONLY
#ifndef {macro_prefix}FP16_DERIVATIVES
#define {macro_prefix}FP16_DERIVATIVES
// Vulkan SPIR-V takes derivatives of 32-bit values only: half values are differentiated in fp32.
float16_t {prefix}ddx_fp16(float16_t v) { return float16_t(dFdx(float(v))); }
f16vec2 {prefix}ddx_fp16(f16vec2 v) { return f16vec2(dFdx(vec2(v))); }
f16vec3 {prefix}ddx_fp16(f16vec3 v) { return f16vec3(dFdx(vec3(v))); }
float16_t {prefix}ddy_fp16(float16_t v) { return float16_t(dFdy(float(v))); }
f16vec2 {prefix}ddy_fp16(f16vec2 v) { return f16vec2(dFdy(vec2(v))); }
f16vec3 {prefix}ddy_fp16(f16vec3 v) { return f16vec3(dFdy(vec3(v))); }
float16_t {prefix}ddx_fine_fp16(float16_t v) { return float16_t(dFdxFine(float(v))); }
f16vec2 {prefix}ddx_fine_fp16(f16vec2 v) { return f16vec2(dFdxFine(vec2(v))); }
f16vec3 {prefix}ddx_fine_fp16(f16vec3 v) { return f16vec3(dFdxFine(vec3(v))); }
float16_t {prefix}ddy_fine_fp16(float16_t v) { return float16_t(dFdyFine(float(v))); }
f16vec2 {prefix}ddy_fine_fp16(f16vec2 v) { return f16vec2(dFdyFine(vec2(v))); }
f16vec3 {prefix}ddy_fine_fp16(f16vec3 v) { return f16vec3(dFdyFine(vec3(v))); }
float16_t {prefix}ddx_coarse_fp16(float16_t v) { return float16_t(dFdxCoarse(float(v))); }
f16vec2 {prefix}ddx_coarse_fp16(f16vec2 v) { return f16vec2(dFdxCoarse(vec2(v))); }
f16vec3 {prefix}ddx_coarse_fp16(f16vec3 v) { return f16vec3(dFdxCoarse(vec3(v))); }
float16_t {prefix}ddy_coarse_fp16(float16_t v) { return float16_t(dFdyCoarse(float(v))); }
f16vec2 {prefix}ddy_coarse_fp16(f16vec2 v) { return f16vec2(dFdyCoarse(vec2(v))); }
f16vec3 {prefix}ddy_coarse_fp16(f16vec3 v) { return f16vec3(dFdyCoarse(vec3(v))); }
#endif
#endif

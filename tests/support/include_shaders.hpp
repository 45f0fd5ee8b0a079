// User shaders that include saagen snippets by name, and the two compilers' include paths, for
// the include-handler tests and the overhead benchmark.
#pragma once

#include "saagen/integrate/glslang_includer.hpp"
#include "saagen/integrate/shaderc_includer.hpp"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <cstdint>
#include <memory>
#include <shaderc/shaderc.hpp>
#include <string>
#include <vector>

namespace saagen::test {

// A compute shader reading (value, dn_dx, dn_dy) as 7 floats per element and writing the
// filtered value: `include` is the #include line, `call` the function it calls.
inline std::string glsl_user_shader(const std::string& include, const std::string& call, bool include_extension,
                                    const std::string& core_only_macro = "SAA_CORE_ONLY") {
  return std::string("#version 450\n") + (include_extension ? "#extension GL_GOOGLE_include_directive : require\n" : "") + "#define " +
         core_only_macro + "\n" + include + "\n" +
         "layout(local_size_x = 64) in;\n"
         "layout(std430, set = 0, binding = 0) readonly buffer Inputs { float values[]; } inputs;\n"
         "layout(std430, set = 0, binding = 1) writeonly buffer Outputs { float values[]; } outputs;\n"
         "void main() {\n"
         "  uint i = gl_GlobalInvocationID.x;\n"
         "  float value = inputs.values[7u * i];\n"
         "  vec3 dn_dx = vec3(inputs.values[7u * i + 1u], inputs.values[7u * i + 2u], inputs.values[7u * i + 3u]);\n"
         "  vec3 dn_dy = vec3(inputs.values[7u * i + 4u], inputs.values[7u * i + 5u], inputs.values[7u * i + 6u]);\n"
         "  outputs.values[i] = " +
         call +
         "(value, dn_dx, dn_dy);\n"
         "}\n";
}

inline std::string hlsl_user_shader(const std::string& include, const std::string& call,
                                    const std::string& core_only_macro = "SAA_CORE_ONLY") {
  return "#define " + core_only_macro + "\n" + include + "\n" +
         "[[vk::binding(0, 0)]] StructuredBuffer<float> inputs;\n"
         "[[vk::binding(1, 0)]] RWStructuredBuffer<float> outputs;\n"
         "[numthreads(64, 1, 1)]\n"
         "void main(uint3 id : SV_DispatchThreadID) {\n"
         "  uint i = id.x;\n"
         "  float3 dn_dx = float3(inputs[7 * i + 1], inputs[7 * i + 2], inputs[7 * i + 3]);\n"
         "  float3 dn_dy = float3(inputs[7 * i + 4], inputs[7 * i + 5], inputs[7 * i + 6]);\n"
         "  outputs[i] = " +
         call +
         "(inputs[7 * i], dn_dx, dn_dy);\n"
         "}\n";
}

struct Compiled {
  bool ok = false;
  std::string log;
  std::vector<std::uint32_t> spirv;
};

// glslang with saagen's includer (or, `includer` null, none: names resolve against nothing).
inline Compiled compile_with_glslang(const std::string& source, bool hlsl, glslang::TShader::Includer& includer) {
  static const bool initialised = glslang::InitializeProcess();
  (void)initialised;
  glslang::TShader shader(EShLangCompute);
  const char* text = source.c_str();
  const char* name = hlsl ? "user.hlsl" : "user.comp";
  shader.setStringsWithLengthsAndNames(&text, nullptr, &name, 1);
  shader.setEnvInput(hlsl ? glslang::EShSourceHlsl : glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_0);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
  if (hlsl) shader.setEntryPoint("main");
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules | (hlsl ? static_cast<int>(EShMsgReadHlsl) : 0));
  Compiled compiled;
  compiled.ok = shader.parse(GetDefaultResources(), hlsl ? 100 : 450, false, messages, includer);
  compiled.log = shader.getInfoLog();
  if (!compiled.ok) return compiled;
  glslang::TProgram program;
  program.addShader(&shader);
  compiled.ok = program.link(messages);
  compiled.log += program.getInfoLog();
  if (compiled.ok) glslang::GlslangToSpv(*program.getIntermediate(EShLangCompute), compiled.spirv);
  return compiled;
}

inline Compiled compile_with_shaderc(const std::string& source, bool hlsl,
                                     std::unique_ptr<shaderc::CompileOptions::IncluderInterface> includer) {
  shaderc::Compiler compiler;
  shaderc::CompileOptions options;
  if (includer) options.SetIncluder(std::move(includer));
  options.SetTargetEnvironment(shaderc_target_env_vulkan, shaderc_env_version_vulkan_1_0);
  if (hlsl) options.SetSourceLanguage(shaderc_source_language_hlsl);
  const auto result = compiler.CompileGlslToSpv(source, shaderc_compute_shader, hlsl ? "user.hlsl" : "user.comp", "main", options);
  Compiled compiled;
  compiled.ok = result.GetCompilationStatus() == shaderc_compilation_status_success;
  compiled.log = result.GetErrorMessage();
  if (compiled.ok) compiled.spirv.assign(result.cbegin(), result.cend());
  return compiled;
}

}  // namespace saagen::test

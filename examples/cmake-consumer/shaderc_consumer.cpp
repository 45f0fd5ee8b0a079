// An engine that compiles shaders with shaderc at run time: `#include <saagen/filament.glsl>`
// resolved by saagen's include handler, the snippet generated in memory.
#include <iostream>
#include <memory>
#include <saagen/integrate/shaderc_includer.hpp>

int main() {
  const char* source =
      "#version 450\n"
      "#include <saagen/filament.glsl>\n"
      "layout(location = 0) in vec3 geometric_normal;\n"
      "layout(location = 0) out vec4 colour;\n"
      "void main() { colour = vec4(saa_deferred_sum_fragment_perceptual(0.3, normalize(geometric_normal))); }\n";
  shaderc::Compiler compiler;
  shaderc::CompileOptions options;
  options.SetIncluder(std::make_unique<saagen::ShadercIncluder>());
  const auto result = compiler.CompileGlslToSpv(source, shaderc_fragment_shader, "material.frag", options);
  if (result.GetCompilationStatus() != shaderc_compilation_status_success) {
    std::cerr << "shaderc_consumer: " << result.GetErrorMessage();
    return 1;
  }
  std::cout << "shaderc_consumer: " << (result.cend() - result.cbegin()) << " SPIR-V words\n";
  return 0;
}

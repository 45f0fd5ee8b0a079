// glslang's include interface for saagen snippets (the name grammar: saagen/integrate/include_handler.hpp).
// Pass it to glslang::TShader::parse (GL_GOOGLE_include_directive in GLSL; #include in HLSL):
//
//   saagen::GlslangIncluder includer({.domain = "perceptual"});
//   shader.parse(resources, 450, false, messages, includer);
//
// Names outside saagen/ go to `fallback` (e.g. glslang's DirStackFileIncluder), else fail. Link
// glslang::glslang (the package finds it).
#pragma once

#include "saagen/integrate/include_handler.hpp"

#include <glslang/Public/ShaderLang.h>

#include <set>

namespace saagen {

class GlslangIncluder : public glslang::TShader::Includer {
 public:
  explicit GlslangIncluder(IncludeOptions defaults = {}, glslang::TShader::Includer* fallback = nullptr);

  IncludeResult* includeSystem(const char* header_name, const char* includer_name, size_t depth) override;
  IncludeResult* includeLocal(const char* header_name, const char* includer_name, size_t depth) override;
  void releaseInclude(IncludeResult* result) override;

 private:
  IncludeResult* resolve(const char* header_name);
  IncludeOptions defaults_;
  glslang::TShader::Includer* fallback_;
  std::set<IncludeResult*> owned_;
};

}  // namespace saagen

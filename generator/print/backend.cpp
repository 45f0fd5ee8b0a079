#include "saagen/print/backend.hpp"

#include "saagen/error.hpp"
#include "saagen/target/target.hpp"

namespace saagen {
namespace {

std::string print_c_like_body(const dialect::Body& body, const TargetSyntax& target, const dialect::PrintOptions& options) {
  return dialect::print_c_like(body, target, *options.names, options.guarded);
}

// One entry per language. GLSL ES is GLSL's front end on the OpenGL ES client (its tables say).
const LanguageBackend backends[] = {
    {SourceLanguage::glsl, print_c_like_body, GlslangFrontEnd{.hlsl = false, .default_version = 450, .named_entry_points = false}},
    {SourceLanguage::hlsl, print_c_like_body, GlslangFrontEnd{.hlsl = true, .default_version = 100, .named_entry_points = true}},
    {SourceLanguage::wgsl, dialect::print_wgsl, std::nullopt},
};

}  // namespace

const GlslangFrontEnd& LanguageBackend::front_end() const {
  if (!glslang) throw Error("this language is not compiled by glslang; Tint validates it through the WebGPU runner");
  return *glslang;
}

const LanguageBackend& language_backend(SourceLanguage language) {
  for (const LanguageBackend& backend : backends) {
    if (backend.language == language) return backend;
  }
  throw Error("no backend for this source language");
}

}  // namespace saagen

namespace saagen::dialect {

std::string print_body(const Body& body, const TargetSyntax& target, const PrintOptions& options) {
  return language_backend(target.language).print_body(body, target, options);
}

}  // namespace saagen::dialect

// Convenience layer over saagen's in-process compiler: GLSL/HLSL source -> SPIR-V words for
// harness descriptions, throwing with the compiler log on failure.
#pragma once

#include <cstdint>
#include <saagen/harness/description.hpp>
#include <saagen/target/language.hpp>
#include <string>
#include <vector>

namespace saagen::harness {

// The languages glslang compiles, as the harness's callers name them (their tables:
// targets/glsl/language.json and targets/hlsl/language.json).
struct Language {
  static inline const saagen::SourceLanguage glsl = saagen::SourceLanguage::named("glsl");
  static inline const saagen::SourceLanguage hlsl = saagen::SourceLanguage::named("hlsl");
};
enum class Stage { vertex, fragment, compute };

// Compiles one source string for Vulkan (SPIR-V 1.3, validated). Throws std::runtime_error
// with the compiler/validator log when it fails.
std::vector<std::uint32_t> compile_shader(saagen::SourceLanguage language, Stage stage, const std::string& source,
                                          const std::string& entry_point = "main", const std::string& name = "shader");

// compile_shader wrapped into a ShaderDesc with the same entry point.
ShaderDesc shader_desc(saagen::SourceLanguage language, Stage stage, const std::string& source, const std::string& entry_point = "main");

// GLSL of the built-in full-screen-triangle vertex shader, and its SPIR-V (compiled once).
const std::string& fullscreen_vertex_glsl();
const std::vector<std::uint32_t>& fullscreen_vertex_spirv();

}  // namespace saagen::harness

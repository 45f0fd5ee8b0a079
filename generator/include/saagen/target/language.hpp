// The source languages, shader stages and client APIs that target tables name and the compiler
// (saagen/validate/compiler.hpp) takes.
#pragma once

namespace saagen {

// WGSL is not compiled here: Tint (Dawn) validates it; see saagen/validate/validation.hpp.
enum class SourceLanguage { glsl, hlsl, wgsl };
enum class ShaderStage { vertex, fragment, compute };
// The API that consumes the SPIR-V. GLSL can target both; HLSL targets Vulkan only.
// opengl_es is source-level only: GLSL ES 3.00 (WebGL2, OpenGL ES 3.0) has no SPIR-V form, so
// glslang's ES front end parses and links it, and no module is produced.
enum class ClientApi { vulkan, opengl, opengl_es };

}  // namespace saagen

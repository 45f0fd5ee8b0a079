#include "saagen/harness/shader.hpp"

#include <saagen/validate/compiler.hpp>
#include <stdexcept>

namespace saagen::harness {
namespace {

saagen::ShaderStage to_compiler_stage(Stage stage) {
  switch (stage) {
    case Stage::vertex:
      return saagen::ShaderStage::vertex;
    case Stage::fragment:
      return saagen::ShaderStage::fragment;
    case Stage::compute:
      return saagen::ShaderStage::compute;
  }
  return saagen::ShaderStage::compute;
}

}  // namespace

std::vector<std::uint32_t> compile_shader(saagen::SourceLanguage language, Stage stage, const std::string& source,
                                          const std::string& entry_point, const std::string& name) {
  saagen::CompileRequest request;
  request.language = language;
  request.stage = to_compiler_stage(stage);
  request.client = saagen::ClientApi::vulkan;
  request.sources = {{name, source}};
  request.entry_point = entry_point;
  saagen::CompileResult result = saagen::compile_to_spirv(request);
  if (!result.ok) throw std::runtime_error("cannot compile " + name + ":\n" + result.log);
  return std::move(result.spirv);
}

ShaderDesc shader_desc(saagen::SourceLanguage language, Stage stage, const std::string& source, const std::string& entry_point) {
  return ShaderDesc{compile_shader(language, stage, source, entry_point), entry_point, {}};
}

const std::string& fullscreen_vertex_glsl() {
  // One triangle covering the viewport: vertices (-1,-1), (3,-1), (-1,3) in clip space. uv is
  // 0 at the top-left framebuffer corner and 1 at the bottom-right.
  static const std::string source = R"(#version 450
layout(location = 0) out vec2 uv;
void main() {
  vec2 corner = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
  uv = corner;
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";
  return source;
}

const std::vector<std::uint32_t>& fullscreen_vertex_spirv() {
  static const std::vector<std::uint32_t> spirv =
      compile_shader(Language::glsl, Stage::vertex, fullscreen_vertex_glsl(), "main", "harness_fullscreen.vert");
  return spirv;
}

}  // namespace saagen::harness

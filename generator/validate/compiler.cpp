#include "saagen/validate/compiler.hpp"

#include "saagen/target/language.hpp"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>

#include <memory>
#include <mutex>

namespace saagen {
namespace {

// glslang needs one process-wide initialisation; FinalizeProcess is left to process exit so
// that the library can be used from several call sites without reference counting.
void ensure_glslang_initialised() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

EShLanguage to_glslang_stage(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::vertex:
      return EShLangVertex;
    case ShaderStage::fragment:
      return EShLangFragment;
    case ShaderStage::compute:
      return EShLangCompute;
  }
  return EShLangFragment;
}

spv_target_env to_spirv_env(ClientApi client) {
  return client == ClientApi::vulkan ? SPV_ENV_VULKAN_1_1 : SPV_ENV_OPENGL_4_5;  // opengl_es produces no module
}

void configure_environment(glslang::TShader& shader, const CompileRequest& request) {
  const EShLanguage stage = to_glslang_stage(request.stage);
  const glslang::EShSource source = request.language->front_end().hlsl ? glslang::EShSourceHlsl : glslang::EShSourceGlsl;
  if (request.client == ClientApi::opengl_es) {
    // No client: glslang checks the source against the ES profile its #version line names
    // (300 es), as an OpenGL ES / WebGL2 driver's front end does, and generates no SPIR-V.
    shader.setEnvInput(source, stage, glslang::EShClientNone, 0);
  } else if (request.client == ClientApi::vulkan) {
    shader.setEnvInput(source, stage, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_1);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_3);
  } else {
    shader.setEnvInput(source, stage, glslang::EShClientOpenGL, 100);
    shader.setEnvClient(glslang::EShClientOpenGL, glslang::EShTargetOpenGL_450);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
  }
  shader.setEntryPoint(request.entry_point.c_str());
}

EShMessages message_flags(const CompileRequest& request) {
  if (request.client == ClientApi::opengl_es) return EShMsgDefault;
  int flags = EShMsgSpvRules;
  if (request.client == ClientApi::vulkan) flags |= EShMsgVulkanRules;
  if (request.language->front_end().hlsl) {
    flags |= EShMsgReadHlsl;
    if (request.hlsl_native_16bit) flags |= EShMsgHlslEnable16BitTypes;
  }
  return static_cast<EShMessages>(flags);
}

}  // namespace

CompileResult compile_to_spirv(const CompileRequest& request) {
  ensure_glslang_initialised();
  CompileResult result;

  std::vector<const char*> texts;
  std::vector<int> lengths;
  std::vector<const char*> names;
  for (const SourcePiece& piece : request.sources) {
    texts.push_back(piece.text.c_str());
    lengths.push_back(static_cast<int>(piece.text.size()));
    names.push_back(piece.name.c_str());
  }

  const EShLanguage stage = to_glslang_stage(request.stage);
  auto shader = std::make_unique<glslang::TShader>(stage);
  shader->setStringsWithLengthsAndNames(texts.data(), lengths.data(), names.data(), static_cast<int>(texts.size()));
  configure_environment(*shader, request);

  const EShMessages messages = message_flags(request);
  const int default_version = request.language->front_end().default_version;
  if (!shader->parse(GetDefaultResources(), default_version, false, messages)) {
    result.log = shader->getInfoLog();
    return result;
  }

  glslang::TProgram program;
  program.addShader(shader.get());
  if (!program.link(messages)) {
    result.log = program.getInfoLog();
    return result;
  }
  if (request.client == ClientApi::opengl_es) {
    result.ok = true;  // parsed and linked; an ES 3.00 shader has no SPIR-V form
    return result;
  }
  // glslang's HLSL front end links a missing entry function as an empty one, with a warning.
  if (const std::string link_log = program.getInfoLog(); link_log.find("Entry point not found") != std::string::npos) {
    result.log = "ERROR: entry point '" + request.entry_point + "' not found; pass --entry with the name of the entry function\n";
    return result;
  }

  glslang::SpvOptions options;
  options.validate = false;  // validated below with the client's rules
  options.disableOptimizer = true;
  spv::SpvBuildLogger logger;
  glslang::GlslangToSpv(*program.getIntermediate(stage), result.spirv, &logger, &options);
  const std::string build_messages = logger.getAllMessages();

  result.log = validate_spirv(result.spirv, request.client);
  if (!result.log.empty()) {
    result.log = "spirv-val: " + result.log + build_messages;
    return result;
  }
  result.ok = true;
  return result;
}

std::string validate_spirv(const std::vector<std::uint32_t>& spirv, ClientApi client) {
  spvtools::SpirvTools tools(to_spirv_env(client));
  std::string messages;
  tools.SetMessageConsumer([&messages](spv_message_level_t, const char*, const spv_position_t& position, const char* message) {
    messages += "word " + std::to_string(position.index) + ": " + message + "\n";
  });
  if (tools.Validate(spirv)) return {};
  return messages.empty() ? std::string("invalid module\n") : messages;
}

std::size_t count_spirv_instructions(const std::vector<std::uint32_t>& spirv) {
  constexpr std::size_t header_words = 5;
  std::size_t count = 0;
  for (std::size_t word = header_words; word < spirv.size();) {
    const std::uint32_t length = spirv[word] >> 16;
    if (length == 0) break;  // malformed; stop rather than loop forever
    word += length;
    ++count;
  }
  return count;
}

std::vector<std::uint32_t> optimize_spirv(const std::vector<std::uint32_t>& spirv, ClientApi client) {
  spvtools::Optimizer optimizer(to_spirv_env(client));
  optimizer.RegisterPerformancePasses();
  std::vector<std::uint32_t> optimized;
  if (!optimizer.Run(spirv.data(), spirv.size(), &optimized)) return {};
  return optimized;
}

std::string joined_source(const std::vector<SourcePiece>& pieces) {
  std::string text;
  for (const SourcePiece& piece : pieces) text += piece.text + (piece.text.ends_with('\n') ? "" : "\n");
  return text;
}

}  // namespace saagen

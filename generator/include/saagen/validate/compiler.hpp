// In-process shader compilation (glslang, GLSL and HLSL front ends) and SPIR-V validation
// (SPIRV-Tools). No external processes are started.
#pragma once

#include "saagen/target/language.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace saagen {

// One named piece of source text. Pieces are concatenated in order; the names appear in
// diagnostics so that an error points at the emitted file, not at the generated harness.
struct SourcePiece {
  std::string name;
  std::string text;
};

// The pieces as one text, each ending with a line break (a WGSL module handed to Tint).
std::string joined_source(const std::vector<SourcePiece>& pieces);

struct CompileRequest {
  SourceLanguage language = SourceLanguage::named("glsl");
  ShaderStage stage = ShaderStage::fragment;
  ClientApi client = ClientApi::vulkan;
  std::vector<SourcePiece> sources;
  std::string entry_point = "main";
  // Enable 16-bit storage/arithmetic extensions in the HLSL front end (min16float maps to fp16).
  bool hlsl_native_16bit = false;
};

struct CompileResult {
  bool ok = false;
  std::vector<std::uint32_t> spirv;
  std::string log;  // glslang's info log, or the validator's message, on failure
};

// Compiles to SPIR-V and validates the module with spirv-val rules for the client API
// (Vulkan 1.1 / SPIR-V 1.3, or OpenGL 4.5 / SPIR-V 1.0). ok is true only when both succeed.
CompileResult compile_to_spirv(const CompileRequest& request);

// Validates a SPIR-V module for the client API; returns an empty string when it is valid.
std::string validate_spirv(const std::vector<std::uint32_t>& spirv, ClientApi client);

// Number of instructions (not words) in a SPIR-V module, after the header.
std::size_t count_spirv_instructions(const std::vector<std::uint32_t>& spirv);

// Runs SPIRV-Tools' performance passes (spirv-opt -O) on the module. Returns an empty vector
// when the optimizer fails.
std::vector<std::uint32_t> optimize_spirv(const std::vector<std::uint32_t>& spirv, ClientApi client);

}  // namespace saagen

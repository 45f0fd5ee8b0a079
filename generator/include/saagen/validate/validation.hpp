// In-process validation of emitted files: each file is compiled by glslang inside a generated
// fragment shader that calls every function and a compute shader that calls every function
// without derivatives, for every client API the target supports, and checked with spirv-val.
#pragma once

#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/compiler.hpp"

#include <nlohmann/json_fwd.hpp>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace saagen {

struct ValidationCheck {
  std::string name;  // e.g. "vulkan fragment"
  bool ok = false;
  std::string log;
  std::size_t spirv_words = 0;
};

struct FileValidation {
  std::string file_name;
  std::vector<ValidationCheck> checks;
  bool ok() const;
  std::string summary() const;  // one line: "OK  saa_deferred_sum.glsl  (vulkan fragment, ...)" or the first error
};

// The shader source that validation compiles for `content` (an emitted file described by
// `marker`) in the given stage: prologue + the file + calls to its functions.
std::vector<SourcePiece> validation_sources(const Catalogue& catalogue, const EmissionMarker& marker, const std::string& file_name,
                                            const std::string& content, ShaderStage stage);

// Validates emitted WGSL files with Tint: each file inside a fragment and a compute entry point
// that call its public functions (the compute one leaves the [fragment] functions out), compiled
// by the installed WebGPU runner in one run for all files. A check passes with zero errors and
// zero warnings. Throws saagen::Error when no runner is installed or it cannot run (no Node.js,
// no npm packages, no Vulkan ICD).
std::vector<FileValidation> validate_wgsl_files(const Catalogue& catalogue, const std::vector<std::pair<std::string, std::string>>& files);

// Runs the jobs of a WebGPU run (compile a WGSL module: {"id", "kind": "compile", "code",
// "entry_points"}) and returns their results ({"results": [...], "features": [...]}); throws
// saagen::Error when it cannot run. The harness provides one (saagen/harness/webgpu.hpp: Dawn for
// Node through harness/webgpu/run.mjs); a program that validates WGSL installs it first.
using WebGpuRunner = std::function<nlohmann::json(const nlohmann::json& jobs)>;
void install_webgpu_runner(WebGpuRunner runner);

// Validates an emitted file's content. Throws saagen::Error when the content has no saagen
// marker or names an unknown target/variant.
FileValidation validate_file(const Catalogue& catalogue, const std::string& file_name, const std::string& content);

}  // namespace saagen

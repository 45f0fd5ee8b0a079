// The WebGPU runner (harness/webgpu/run.mjs: Dawn for Node on SwiftShader's Vulkan): `node RUNNER
// DIR` runs the jobs of DIR/jobs.json (compile a WGSL module, run a compute or fragment pass) and
// writes DIR/results.json. The library's WGSL validation calls it through the runner a program
// installs (saagen::install_webgpu_runner, saagen/validate/validation.hpp): install_webgpu_runner()
// installs this one.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace saagen::harness {

// The command: `$SAAGEN_NODE` (node) and `$SAAGEN_WEBGPU_RUNNER` (this checkout's run.mjs by
// default), shell-quoted. Throws saagen::Error when the runner is not there.
std::string webgpu_runner_command();

// Writes `jobs` to `directory`/jobs.json, runs them and returns the parsed results; throws
// saagen::Error with the runner's first line when it fails.
nlohmann::json run_webgpu_jobs(const nlohmann::json& jobs, const std::filesystem::path& directory);

// Installs run_webgpu_jobs, in a temporary directory of its own per run, as the runner of the
// library's WGSL validation.
void install_webgpu_runner();

}  // namespace saagen::harness

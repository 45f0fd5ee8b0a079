#include "saagen/harness/webgpu.hpp"

#include "saagen/error.hpp"
#include "saagen/validate/validation.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>

#include <unistd.h>

namespace saagen::harness {
namespace {

std::string shell_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string environment_or(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value && *value ? value : fallback;
}

// A temporary directory removed when the object goes.
struct ScratchDirectory {
  std::filesystem::path path;
  ScratchDirectory() {
    std::string pattern = (std::filesystem::temp_directory_path() / "saagen-wgsl-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw Error("WGSL validation: cannot create a temporary directory; set TMPDIR to a writable one");
    path = pattern;
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

}  // namespace

std::string webgpu_runner_command() {
  const std::string node = environment_or("SAAGEN_NODE", "node");
  const std::string runner = environment_or("SAAGEN_WEBGPU_RUNNER", SAAGEN_WEBGPU_RUNNER);
  if (!std::filesystem::is_regular_file(runner)) {
    throw Error(
        fmt::format("WGSL validation needs the WebGPU runner {} (Dawn for Node); set SAAGEN_WEBGPU_RUNNER to harness/webgpu/run.mjs "
                    "of a saagen checkout whose `scripts/install-deps.sh` has run",
                    runner));
  }
  return shell_quoted(node) + " " + shell_quoted(runner);
}

nlohmann::json run_webgpu_jobs(const nlohmann::json& jobs, const std::filesystem::path& directory) {
  std::ofstream(directory / "jobs.json") << jobs.dump();
  const std::filesystem::path log = directory / "runner.log";
  const std::string command =
      fmt::format("{} {} > {} 2>&1", webgpu_runner_command(), shell_quoted(directory.string()), shell_quoted(log.string()));
  const int status = std::system(command.c_str());
  std::ifstream results(directory / "results.json");
  if (status != 0 || !results) {
    std::stringstream text;
    text << std::ifstream(log).rdbuf();
    std::string first_line = text.str().substr(0, text.str().find('\n'));
    throw Error(
        fmt::format("the WebGPU runner (Dawn for Node) failed: {}; run scripts/install-deps.sh (Node.js, npm ci) and check the Vulkan ICD",
                    first_line.empty() ? "no output" : first_line));
  }
  try {
    return nlohmann::json::parse(results);
  } catch (const nlohmann::json::exception& error) {
    throw Error(fmt::format("the WebGPU runner wrote an unreadable results.json: {}", error.what()));
  }
}

void install_webgpu_runner() {
  saagen::install_webgpu_runner([](const nlohmann::json& jobs) {
    const ScratchDirectory directory;
    return run_webgpu_jobs(jobs, directory.path);
  });
}

}  // namespace saagen::harness

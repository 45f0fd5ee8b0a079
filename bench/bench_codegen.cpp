// Codegen time for all variants x targets. Goals: emission alone <= 50 ms and with
// in-process validation <= 2 s, whole process, on the 2-core CI machine.
//   build/bench/bench_codegen --benchmark_min_time=0.5
#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/validation.hpp"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

std::vector<saagen::EmittedFile> emit_everything() {
  std::vector<saagen::EmittedFile> files;
  for (const std::string& target : saagen::builtin_target_names()) {
    saagen::EmitOptions options;
    options.target = target;
    for (auto& file : saagen::emit_variants(saagen::Catalogue::builtin(), options)) files.push_back(std::move(file));
  }
  return files;
}

void BM_EmitAllVariantsAllTargets(benchmark::State& state) {
  std::size_t bytes = 0;
  for (auto _ : state) {
    const auto files = emit_everything();
    bytes = 0;
    for (const auto& file : files) bytes += file.content.size();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["files"] = static_cast<double>(emit_everything().size());
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_EmitAllVariantsAllTargets)->Unit(benchmark::kMillisecond);

void BM_EmitAndValidateAllVariantsAllTargets(benchmark::State& state) {
  std::size_t compiled = 0;
  for (auto _ : state) {
    compiled = 0;
    for (const auto& file : emit_everything()) {
      const auto validation = saagen::validate_file(saagen::Catalogue::builtin(), file.file_name, file.content);
      if (!validation.ok()) state.SkipWithError(validation.summary().c_str());
      compiled += validation.checks.size();
    }
  }
  state.counters["shaders_compiled"] = static_cast<double>(compiled);
}
BENCHMARK(BM_EmitAndValidateAllVariantsAllTargets)->Unit(benchmark::kMillisecond);

// Whole processes, as a build step runs them: start-up, catalogue parsing, emission, writing.
void run_cli(benchmark::State& state, const std::string& arguments) {
  const std::string command = std::string("( '") + SAAGEN_CLI_PATH + "' " + arguments + " ) > /dev/null";
  for (auto _ : state) {
    if (std::system(command.c_str()) != 0) state.SkipWithError(("failed: " + command).c_str());
  }
}

void BM_ProcessEmitAllVariantsAllTargets(benchmark::State& state) {
  const auto directory = std::filesystem::temp_directory_path() / "saagen-bench-emit";
  std::filesystem::remove_all(directory);
  // Both targets in one process would need a new CLI flag; two processes are what a build runs.
  run_cli(state, "emit -t glsl -o '" + directory.string() + "' && '" + SAAGEN_CLI_PATH + "' emit -t hlsl -o '" + directory.string() + "'");
  std::filesystem::remove_all(directory);
}
BENCHMARK(BM_ProcessEmitAllVariantsAllTargets)->Unit(benchmark::kMillisecond);

void BM_ProcessValidateAllVariantsAllTargets(benchmark::State& state) { run_cli(state, "validate"); }
BENCHMARK(BM_ProcessValidateAllVariantsAllTargets)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

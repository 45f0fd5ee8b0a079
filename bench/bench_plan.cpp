// `saagen plan` of a large scene: a 10,000-material manifest (every combination of path,
// anisotropy, tangents, NDF, normal maps, precision and preference, repeated under new names),
// parsed, planned, costed (optimized SPIR-V instruction counts of the cost kernels, one compile
// per distinct configuration) and formatted. Goal: under 10 s on the 2-core CI machine.
//   build/bench/bench_plan
#include "support/material_combinations.hpp"

#include "saagen/front/catalogue.hpp"
#include "saagen/scene/manifest.hpp"
#include "saagen/scene/planner.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <string>
#include <vector>

namespace {

void BM_PlanLargeManifest(benchmark::State& state) {
  const saagen::Catalogue& catalogue = saagen::Catalogue::builtin();
  const std::string text = saagen::test::manifest_of_materials(static_cast<std::size_t>(state.range(0)), "large");
  std::size_t bytes = 0;
  for (auto _ : state) {
    const saagen::Manifest manifest = saagen::parse_manifest(text, "large.saagen.toml", catalogue);
    saagen::ScenePlan plan = saagen::plan_scene(catalogue, manifest);
    saagen::measure_costs(catalogue, manifest, plan);
    bytes = saagen::format_plan(catalogue, manifest, plan).size();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["materials"] = static_cast<double>(state.range(0));
  state.counters["manifest_bytes"] = static_cast<double>(text.size());
  state.counters["plan_bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_PlanLargeManifest)->Arg(1000)->Arg(10000)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();

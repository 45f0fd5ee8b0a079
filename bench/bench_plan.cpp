// `saagen plan` of a large scene: a 10,000-material manifest (every combination of path,
// anisotropy, tangents, NDF, normal maps, precision and preference, repeated under new names),
// parsed, planned, costed (optimized SPIR-V instruction counts of the cost kernels, one compile
// per distinct configuration) and formatted. Goal: under 10 s on the 2-core CI machine.
//   build/bench/bench_plan
#include "saagen/front/catalogue.hpp"
#include "saagen/scene/manifest.hpp"
#include "saagen/scene/planner.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <string>
#include <vector>

namespace {

// A manifest of `count` materials cycling through every valid combination of the material keys
// (defaults left out, so that 10,000 materials stay under the 1 MiB manifest limit).
std::string large_manifest(int count) {
  std::vector<std::string> materials;
  for (const char* path : {"forward", "deferred"})
    for (const bool anisotropic : {false, true})
      for (const bool tangents : {false, true}) {
        if (anisotropic && !tangents) continue;
        for (const char* ndf : {"ggx", "beckmann"})
          for (const bool normal_maps : {false, true})
            for (const char* precision : {"fp32", "fp16"})
              for (const char* prefer : {"accuracy", "speed"}) {
                std::string keys = fmt::format("path=\"{}\"\n", path);
                if (anisotropic) keys += "anisotropic=true\n";
                if (tangents) keys += "tangents=true\n";
                if (std::string(ndf) != "ggx") keys += fmt::format("ndf=\"{}\"\n", ndf);
                if (normal_maps) keys += "normal_maps=true\n";
                if (std::string(precision) != "fp32") keys += fmt::format("precision=\"{}\"\n", precision);
                if (std::string(prefer) != "accuracy") keys += fmt::format("prefer=\"{}\"\n", prefer);
                materials.push_back(keys);
              }
      }
  std::string text = "name = \"large\"\ntargets = [\"glsl\", \"hlsl\"]\n";
  for (int index = 0; index < count; ++index) {
    text += fmt::format("[[material]]\nname=\"m{}\"\n{}", index, materials[static_cast<std::size_t>(index) % materials.size()]);
  }
  return text;
}

void BM_PlanLargeManifest(benchmark::State& state) {
  const saagen::Catalogue& catalogue = saagen::Catalogue::builtin();
  const std::string text = large_manifest(static_cast<int>(state.range(0)));
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

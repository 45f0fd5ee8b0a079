// CPU cost of the double-precision side: the default glint dictionary's generation and the
// supersampled ground truth's throughput (Msamples/s, extrapolated to the trade's 256 x 256 x
// 1024 spp). Timing lives here, never in the unit tests.
#include "saagen/products/glints.hpp"
#include "saagen/reference/render/render.hpp"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace {

void BM_GlintDictionaryDefaults(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(saagen::glints::generate_dictionary({}));
}
BENCHMARK(BM_GlintDictionaryDefaults)->Unit(benchmark::kMillisecond);

// The sphere at 64 x 64 x 1024 spp, four alphas sharing one set of rays.
void BM_GroundTruthSphere64(benchmark::State& state) {
  namespace render = saagen::render;
  const render::Scene scene = render::make_scene(render::SceneId::sphere);
  const std::vector<render::Material> materials{{0.01, false}, {0.05, false}, {0.1, false}, {0.3, false}};
  render::GroundTruthSettings settings;
  settings.width = settings.height = 64;
  for (auto _ : state) benchmark::DoNotOptimize(render::render_ground_truth(scene, settings, materials));
  const double samples = 64.0 * 64.0 * 1024.0;
  state.counters["Msamples/s"] = benchmark::Counter(samples * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["s_at_256x256"] =
      benchmark::Counter(1.0 / 16.0, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_GroundTruthSphere64)->Unit(benchmark::kSecond)->UseRealTime();

// The trade's cost per content scene (normal-mapped spheres, torus knot): 256 x 256 x 1024 spp,
// the trade's eight materials (target: 60 s each on 2 threads). About a minute per scene.
void BM_GroundTruthContent(benchmark::State& state) {
  namespace render = saagen::render;
  const render::SceneId id = render::content_scenes()[static_cast<std::size_t>(state.range(0))];
  const render::Scene scene = render::make_scene(id);
  std::vector<render::Material> materials;
  for (double alpha : {0.01, 0.05, 0.1, 0.3})
    for (bool fresnel : {false, true}) materials.push_back({alpha, fresnel});
  render::GroundTruthSettings settings;
  settings.threads = 2;
  for (auto _ : state) benchmark::DoNotOptimize(render::render_ground_truth(scene, settings, materials));
  state.SetLabel(std::string(render::scene_name(id)));
}
BENCHMARK(BM_GroundTruthContent)->DenseRange(0, 2)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();

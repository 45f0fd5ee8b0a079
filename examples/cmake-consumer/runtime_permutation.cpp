// Run-time generation with the installed library (saagen::saagen): an engine that builds shader
// permutations on demand describes the material, plans it, emits the bundle in memory and
// (optionally) validates it with the in-process compiler. Exits non-zero on any failure.
#include <cstdio>
#include <saagen/error.hpp>
#include <saagen/front/catalogue.hpp>
#include <saagen/scene/manifest.hpp>
#include <saagen/scene/planner.hpp>
#include <saagen/validate/validation.hpp>

int main() {
  const char* description = R"(targets = ["glsl", "hlsl"]
prefix = "rt_"
[[material]]
name = "permutation"
path = "forward"
tangents = true
prefer = "speed"
)";
  try {
    const saagen::Catalogue& catalogue = saagen::Catalogue::builtin();
    const saagen::Manifest manifest = saagen::parse_manifest(description, "runtime-permutation", catalogue);
    const saagen::ScenePlan plan = saagen::plan_scene(catalogue, manifest);
    int failures = 0;
    for (const saagen::EmittedFile& file : saagen::emit_scene(catalogue, manifest, plan)) {
      const saagen::FileValidation validation = saagen::validate_file(catalogue, file.file_name, file.content);
      std::printf("%s  (%s, %zu bytes)\n", validation.summary().c_str(), plan.materials.front().variant.c_str(), file.content.size());
      failures += validation.ok() ? 0 : 1;
    }
    return failures == 0 ? 0 : 1;
  } catch (const saagen::Error& error) {
    std::fprintf(stderr, "runtime_permutation: %s\n", error.what());
    return 1;
  }
}

#!/usr/bin/env bash
# The main job: install what is missing, build, emit every variant for every target and validate
# them, measure each variant's cost on lavapipe, print the speed/accuracy trade table and its
# verdict, then plan and emit the bundled example scene with that table (the same decision as the
# verdict); the full report goes to out/report/index.html.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
saagen=./build/cli/saagen

for target in glsl hlsl; do
  "$saagen" emit --target "$target" -o out/snippets > /dev/null
done
"$saagen" validate out/snippets | tail -n 1

# Cost: lavapipe time ratio and optimized SPIR-V delta per variant (about 15 s).
./build/bench/bench_shading --json out/cost.json > out/cost.txt
head -n 1 out/cost.txt
# Accuracy against supersampled ground truths, in linear and display-referred metrics, with the
# engines' shipped forms as baselines; one measurement gives the table, its JSON and the report.
# The default medium preset takes about 35 minutes on 2 cores the first time and 18 once its ground
# truths are cached in out/cache; SAAGEN_PRESET=full (256 px, 1024 spp, Fresnel) takes hours
# (docs/GUIDE.md, "The main job"; docs/GLTF_SCENES.md, "In the presets").
preset=${SAAGEN_PRESET:-medium}
"$saagen" bench --preset "$preset" --cost out/cost.json --cache out/cache --json out/trade.json --report out/report
# One answer: the example scene planned and emitted with the table just measured, by the same
# decision as the verdict above (saagen/decision.hpp), so each material's plan is that verdict's
# line for its path and content.
echo
"$saagen" plan examples/scene.saagen.toml --no-cost --trade-table out/trade.json
"$saagen" emit --manifest examples/scene.saagen.toml --trade-table out/trade.json -o out/scene
if [ -d out/scene ]; then "$saagen" validate out/scene; fi

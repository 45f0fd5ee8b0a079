#!/usr/bin/env bash
# The main job: install what is missing, build, emit the bundled example scene's snippets (and
# every variant for every target), validate them, measure each variant's cost on lavapipe, and
# print the speed/accuracy trade table; the full report goes to out/report/index.html.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
saagen=./build/cli/saagen

"$saagen" plan examples/scene.saagen.toml --no-cost
"$saagen" emit --manifest examples/scene.saagen.toml -o out/scene
for target in glsl hlsl; do
  "$saagen" emit --target "$target" -o out/snippets > /dev/null
done
"$saagen" validate out/scene
"$saagen" validate out/snippets | tail -n 1

# Cost: lavapipe time ratio and optimized SPIR-V delta per variant (about 15 s).
./build/bench/bench_shading --json out/cost.json > out/cost.txt
head -n 1 out/cost.txt
# Accuracy against supersampled ground truths, in linear and display-referred metrics, with the
# engines' shipped forms as baselines; one measurement gives the table, its JSON and the report.
# SAAGEN_PRESET=full (256 px, 1024 spp, Fresnel: about 21 minutes on 2 cores the first time) gives
# the figures in the README; the default medium preset takes about 2 minutes (ground truths are
# cached in out/cache; docs/GLTF_SCENES.md, "In the presets").
preset=${SAAGEN_PRESET:-medium}
"$saagen" bench --preset "$preset" --cost out/cost.json --cache out/cache --json out/trade.json --report out/report

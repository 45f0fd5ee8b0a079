#!/usr/bin/env bash
# The main job: install what is missing, build, emit every variant for every target into out/,
# and validate what was written (glslang + spirv-val, in-process).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
for target in glsl hlsl; do
  ./build/generator/saagen emit --target "$target" -o out/snippets
done
./build/generator/saagen validate out/snippets

#!/usr/bin/env bash
# Emits every output of the generator that comes from the templates into one directory, so that
# two builds can be compared byte for byte (`diff -r OLD NEW`): every variant x target x
# precision (guarded and unguarded), every roughness domain and preset, a named WGSL module,
# SPIR-V library modules, the three example manifests' bundles and plans, the deferred pass
# skeletons, the glint snippets, `list --json` and the `validate` report.
#
# Usage: scripts/emit_corpus.sh SAAGEN_BINARY OUTPUT_DIRECTORY
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: $0 SAAGEN_BINARY OUTPUT_DIRECTORY" >&2
  exit 2
fi
saagen=$(realpath "$1")
out=$2
root=$(cd "$(dirname "$0")/.." && pwd)
rm -rf "$out"
mkdir -p "$out"
out=$(realpath "$out")

emit_forms() {  # target precision...
  local target=$1
  shift
  for precision in "$@"; do
    "$saagen" emit --target "$target" --precision "$precision" -o "$out/emit/$target/$precision"
    "$saagen" emit --target "$target" --precision "$precision" --unguarded -o "$out/emit/$target/$precision-unguarded"
  done
}

emit_forms glsl fp32 fp16
emit_forms gles fp32 fp16
emit_forms hlsl fp32 min16
emit_forms wgsl fp32 fp16
for domain in alpha perceptual smoothness; do
  for target in glsl gles hlsl wgsl; do
    "$saagen" emit --target "$target" --domain "$domain" -o "$out/emit/$target/domain-$domain"
  done
done
for preset in hdrp filament filament-taa o3de bevy vsgl; do
  "$saagen" emit --target glsl --preset "$preset" -o "$out/emit/glsl/preset-$preset"
done
"$saagen" emit --target wgsl --variant forward-aniso-slope --variant brdf-ggx --import-path saa::gsaa --module gsaa \
  -o "$out/emit/wgsl/module"
"$saagen" emit --target spirv -o "$out/emit/spirv/fp32"
"$saagen" emit --target glsl --prefix my_ --sigma2 0.5 --kappa 0.3 -o "$out/emit/glsl/options"
"$saagen" emit --target gles --prefix my_ --sigma2 0.5 --kappa 0.3 -o "$out/emit/gles/options"

(cd "$root/examples" && "$saagen" emit --manifest scene.saagen.toml -o "$out/manifest")
(cd "$root/examples/webgpu" && "$saagen" emit --manifest scene.saagen.toml -o "$out/manifest-webgpu")
(cd "$root/examples/cmake-consumer" && "$saagen" emit --manifest scene.saagen.toml -o "$out/manifest-cmake-consumer")
for manifest in scene webgpu/scene cmake-consumer/scene; do
  "$saagen" plan "$root/examples/$manifest.saagen.toml" > "$out/plan-${manifest//\//-}.txt"
done

"$saagen" pass -o "$out/pass/fine"
"$saagen" pass --derivatives coarse --output-format r16f -o "$out/pass/coarse"
"$saagen" pass --unguarded -o "$out/pass/unguarded"
"$saagen" pass --preset hdrp -o "$out/pass/hdrp"

for target in glsl hlsl; do
  "$saagen" glints emit --target "$target" -o "$out/glints/$target/fp32"
  "$saagen" glints emit --target "$target" --unguarded -o "$out/glints/$target/fp32-unguarded"
done

"$saagen" list > "$out/list.txt"
"$saagen" list --json > "$out/list.json"
"$saagen" validate > "$out/validate.txt" 2>&1
(cd "$out" && "$saagen" validate emit/glsl/fp16 > validate-glsl-fp16.txt 2>&1)
(cd "$out" && "$saagen" validate emit/gles/fp16 > validate-gles-fp16.txt 2>&1)
"$saagen" glints validate > "$out/glints-validate.txt" 2>&1
echo "corpus written to $out: $(find "$out" -type f | wc -l) files"

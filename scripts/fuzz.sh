#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (libFuzzer + ASan + UBSan) in ./build-fuzz and runs
# each: by default 1 000 000 executions from its seed corpus (fuzz/README.md).
#   bash scripts/fuzz.sh                                # every target, -runs=1000000 each
#   FUZZ_TARGETS="ktx2 template" bash scripts/fuzz.sh   # some targets
#   bash scripts/fuzz.sh -max_total_time=150            # any libFuzzer flags, for every target
# New inputs are kept in build-fuzz/corpus_<target>, crashes in build-fuzz/artifacts. Exits
# non-zero on the first crash; prints each target's executions, coverage and time.
# The gltf target's seeds are packed at run time from Debian's assimp-testmodels
# (/usr/share/assimp/models/glTF2, or GLTF_SAMPLES=DIR) into build-fuzz/seeds_gltf, plus the
# committed fuzz/corpus_gltf; nothing of the samples is copied into the repository.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ is needed (Debian: apt-get install clang)"; exit 1; }
targets=(${FUZZ_TARGETS:-manifest ktx2 ppm_lean template png include gltf cache})
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# vptr is off: Debian's glslang is built without RTTI.
sanitizers="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=vptr -fno-sanitize-recover=undefined"
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="$sanitizers -fno-omit-frame-pointer" \
  -DSAAGEN_BUILD_FUZZ=ON -DSAAGEN_BUILD_TESTS=OFF -DSAAGEN_BUILD_BENCH=OFF -DSAAGEN_BUILD_HARNESS=OFF > "$log" 2>&1 || { cat "$log"; exit 1; }
cmake --build build-fuzz --target "${targets[@]/#/saagen_fuzz_}" -j "$(nproc)"
mkdir -p build-fuzz/artifacts
args=("$@")
[[ " ${args[*]-} " == *" -runs="* || " ${args[*]-} " == *" -max_total_time="* ]] || args+=(-runs=1000000)
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
for target in "${targets[@]}"; do
  case "$target" in
    manifest) seeds=fuzz/corpus; extra=(-dict=fuzz/manifest.dict -max_len=262144) ;;  # reaches depth attacks
    ktx2) seeds=fuzz/corpus_ktx2; extra=(-max_len=65536) ;;
    ppm_lean) seeds=fuzz/corpus_ppm_lean; extra=(-max_len=65536) ;;
    template) seeds=fuzz/corpus_template; extra=(-dict=fuzz/template.dict -max_len=65536) ;;
    png) seeds=fuzz/corpus_png; extra=(-max_len=4096) ;;  # deflate expands ~1000x: 4 MB of pixels at most
    include) seeds=fuzz/corpus_include; extra=(-dict=fuzz/include.dict -max_len=65536) ;;
    # An asset and the files its URIs name, packed (fuzz/gltf_fuzzer.cpp). 32 KiB: about 1 ms an
    # input under the sanitizers (128 KiB JSON takes 5 ms); 43 of the 46 packaged samples fit.
    gltf) seeds="build-fuzz/seeds_gltf fuzz/corpus_gltf"; extra=(-dict=fuzz/gltf.dict -max_len=32768)
          python3 scripts/gltf_fuzz_seeds.py "${GLTF_SAMPLES:-/usr/share/assimp/models/glTF2}" build-fuzz/seeds_gltf 32768 ;;
    cache) seeds=fuzz/corpus_cache; extra=(-max_len=4096) ;;  # the entry is 192 bytes of pixels and its header
    *) echo "fuzz.sh: unknown target '$target' (manifest, ktx2, ppm_lean, template, png, include, gltf, cache)"; exit 2 ;;
  esac
  mkdir -p "build-fuzz/corpus_$target"
  start=$(date +%s)
  status=0
  "./build-fuzz/fuzz/saagen_fuzz_$target" "${extra[@]}" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
    -artifact_prefix=build-fuzz/artifacts/ "${args[@]}" "build-fuzz/corpus_$target" $seeds > "build-fuzz/$target.log" 2>&1 || status=$?
  grep -E "^#[0-9]+ +(DONE|INITED)|stat::number_of_executed_units|ERROR|SUMMARY|Test unit written" "build-fuzz/$target.log" || true
  echo "fuzz.sh: $target: exit $status in $(( $(date +%s) - start )) s ($(grep -oE 'cov: [0-9]+ ft: [0-9]+' "build-fuzz/$target.log" | tail -1))"
  [[ $status -eq 0 ]] || exit "$status"
done
echo "fuzz.sh: no crash"

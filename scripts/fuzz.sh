#!/usr/bin/env bash
# Builds the libFuzzer target for scene manifests with clang (ASan + libFuzzer) in ./build-fuzz
# and runs it: by default 1 000 000 executions from fuzz/corpus with fuzz/manifest.dict.
# Extra arguments go to libFuzzer (e.g. -runs=10000, -max_total_time=60). New inputs are kept in
# build-fuzz/corpus, crashes in build-fuzz/artifacts. Exits non-zero on a crash.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ is needed (Debian: apt-get install clang)"; exit 1; }
log=$(mktemp)
trap 'rm -f "$log"' EXIT
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address -fno-omit-frame-pointer" \
  -DSAAGEN_BUILD_FUZZ=ON -DSAAGEN_BUILD_TESTS=OFF -DSAAGEN_BUILD_BENCH=OFF -DSAAGEN_BUILD_HARNESS=OFF > "$log" 2>&1 || { cat "$log"; exit 1; }
cmake --build build-fuzz --target saagen_fuzz_manifest -j "$(nproc)"
mkdir -p build-fuzz/corpus build-fuzz/artifacts
args=("$@")
[[ " ${args[*]-} " == *" -runs="* || " ${args[*]-} " == *" -max_total_time="* ]] || args+=(-runs=1000000)
start=$(date +%s)
./build-fuzz/fuzz/saagen_fuzz_manifest -dict=fuzz/manifest.dict -max_len=4096 -timeout=10 -print_final_stats=1 \
  -artifact_prefix=build-fuzz/artifacts/ "${args[@]}" build-fuzz/corpus fuzz/corpus
echo "fuzz.sh: done in $(( $(date +%s) - start )) s, no crash"

#!/usr/bin/env bash
# ASan + UBSan run of the suites that need no Vulkan device, plus every fuzz corpus replayed
# under the sanitizers. Not part of the default CI (616 tests; on one core about 64 minutes from
# scratch: the build, then 36 minutes of tests): run it after changes to readers, writers or the emitter.
#   bash scripts/sanitize.sh                 # every non-GPU suite
#   bash scripts/sanitize.sh -R 'Cli|Safety' # a ctest subset (any ctest arguments)
#   SANITIZE_TARGETS="saagen_cli test_cli" bash scripts/sanitize.sh -R '^Cli'  # build only these
# Builds in ./build-sanitize (no Vulkan harness) with clang when available, else g++. vptr checks are off: Debian's
# glslang is built without RTTI. Any sanitizer report fails the test that triggered it.
set -euo pipefail
cd "$(dirname "$0")/.."
compiler=$(command -v clang++ || command -v g++)
# The C API's test is C: the same compiler family, or the binary loads two ASan runtimes.
c_compiler=$(command -v clang || command -v gcc)
[[ $(basename "$compiler") == g++ ]] && c_compiler=$(command -v gcc)
# The WebGPU and WebGL2 suites (and WGSL validation) run node with the project's npm packages.
[[ -d node_modules ]] || PUPPETEER_SKIP_DOWNLOAD=1 npm ci --ignore-scripts --no-audit --no-fund > /dev/null
log=$(mktemp)
trap 'rm -f "$log"' EXIT
flags="-fsanitize=address,undefined -fno-sanitize=vptr -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$compiler" \
  -DCMAKE_C_COMPILER="$c_compiler" -DCMAKE_C_FLAGS="$flags" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DSAAGEN_BUILD_BENCH=OFF -DSAAGEN_BUILD_HARNESS=OFF > "$log" 2>&1 || { cat "$log"; exit 1; }
targets=()
for target in ${SANITIZE_TARGETS:-}; do targets+=(--target "$target"); done
cmake --build build-sanitize "${targets[@]}" -j "$(nproc)"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
start=$(date +%s)
args=("$@")
[[ ${#args[@]} -gt 0 ]] || args=(-LE "vulkan|package|bench")
status=0
ctest --test-dir build-sanitize "${args[@]}" -j "$(nproc)" --output-on-failure || status=$?
if [[ $status -ne 0 ]]; then
  echo "sanitize.sh: a test failed (above) after $(( $(date +%s) - start )) s"
  exit "$status"
fi
echo "sanitize.sh: done in $(( $(date +%s) - start )) s, no sanitizer report"

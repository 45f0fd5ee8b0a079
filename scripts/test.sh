#!/usr/bin/env bash
# Install what is missing, build, and run every test. Fails when any test fails or none ran.
# Every GPU suite runs on lavapipe and on SwiftShader with the Vulkan validation layer on
# (tests/CMakeLists.txt); the per suite x device table (run / passed / unsupported, worst error
# as a fraction of its bound, validation messages) is printed at the end.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
# The library and the CLI compiled with clang as well (compile only: nothing runs the binary, so it
# is built without optimisation, -O0 with Release's -DNDEBUG, about 60 % less compile time than
# -O3): the sanitizer and fuzz scripts build with clang, whose C++20 differs from GCC's in places.
clang_log=$(mktemp)
trap 'rm -f "$clang_log"' EXIT
if ! { CC=clang CXX=clang++ cmake -S . -B build-clang -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O0 -DNDEBUG" &&
       cmake --build build-clang --target saagen_cli -j "$(nproc)"; } > "$clang_log" 2>&1; then
  grep -E "error|Error" "$clang_log" | head -n 20
  echo "test: the library or the CLI does not compile with clang"
  exit 1
fi
echo "test: the library and the CLI compile with clang"
status=0
start=$(date +%s)
ctest --test-dir build --output-on-failure --no-tests=error -j "$(nproc)" --output-junit ctest-junit.xml || status=$?
echo "ctest: $(( $(date +%s) - start )) s on $(nproc) cores"
python3 scripts/gpu_table.py build/ctest-junit.xml || true
exit "$status"

#!/usr/bin/env bash
# Install what is missing, build, and run every test. Fails when any test fails or none ran.
# Every GPU suite runs on lavapipe and on SwiftShader with the Vulkan validation layer on
# (tests/CMakeLists.txt); the per suite x device table (run / passed / unsupported, worst error
# as a fraction of its bound, validation messages) is printed at the end.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
status=0
start=$(date +%s)
ctest --test-dir build --output-on-failure --no-tests=error -j "$(nproc)" --output-junit ctest-junit.xml || status=$?
echo "ctest: $(( $(date +%s) - start )) s on $(nproc) cores"
python3 scripts/gpu_table.py build/ctest-junit.xml || true
exit "$status"

#!/usr/bin/env bash
# Install what is missing, build, and run every test. Fails when any test fails or none ran.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
ctest --test-dir build --output-on-failure --no-tests=error -j "$(nproc)"

#!/usr/bin/env bash
# Configures and builds saagen in ./build (Release, Ninja). Used by run.sh and test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
log=$(mktemp)
trap 'rm -f "$log"' EXIT
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" > "$log" 2>&1 || { cat "$log"; exit 1; }
cmake --build build -j "$(nproc)"

#!/usr/bin/env bash
# Set up, build and run every test with a CMake preset (default or asan).
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-default}"
bash scripts/build.sh "$preset"
ctest --preset "$preset" -j "$(nproc)"

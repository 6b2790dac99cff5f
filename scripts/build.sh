#!/usr/bin/env bash
# Set-up and build with a CMake preset (default: Release; asan: sanitizers).
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-default}"
bash scripts/setup.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)"

#!/usr/bin/env bash
# Set-up and build with a CMake preset (default: Release; asan: sanitizers), everything or
# only the targets named after the preset.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-default}"
shift || true
bash scripts/setup.sh
cmake --preset "$preset" >/dev/null
if (($# > 0)); then
  cmake --build --preset "$preset" -j "$(nproc)" --target "$@"
else
  cmake --build --preset "$preset" -j "$(nproc)"
fi

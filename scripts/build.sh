#!/usr/bin/env bash
# Set-up and build with a CMake preset (default: the host parts, Release; full: everything;
# asan: everything under sanitizers), everything or only the targets named after the preset.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-default}"
shift || true
if [ "$preset" = default ]; then bash scripts/setup.sh host; else bash scripts/setup.sh full; fi
cmake --preset "$preset" >/dev/null
if (($# > 0)); then
  cmake --build --preset "$preset" -j "$(nproc)" --target "$@"
else
  cmake --build --preset "$preset" -j "$(nproc)"
fi

#!/usr/bin/env bash
# Set-up and build with a CMake preset (default: the host parts, Release; full: everything;
# asan: everything under sanitizers), everything or only the targets named after the preset.
#
# Compiles through ccache when it is installed (scripts/setup.sh installs it), with the checkout's
# root as its base directory and without the working directory in the hash, so that a fresh clone
# in another folder of the same machine (CI's) reuses what this checkout compiled. The launcher
# is stored in the build folder's cache, so a later `cmake --build` by hand uses it the same way.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-default}"
shift || true
if [ "$preset" = default ]; then bash scripts/setup.sh host; else bash scripts/setup.sh full; fi
launcher=""
if command -v ccache >/dev/null; then
  launcher="/usr/bin/env;CCACHE_BASEDIR=$PWD;CCACHE_NOHASHDIR=true;$(command -v ccache)"
fi
cmake --preset "$preset" -DCMAKE_C_COMPILER_LAUNCHER="$launcher" \
  -DCMAKE_CXX_COMPILER_LAUNCHER="$launcher" >/dev/null
if (($# > 0)); then
  cmake --build --preset "$preset" -j "$(nproc)" --target "$@"
else
  cmake --build --preset "$preset" -j "$(nproc)"
fi

#!/usr/bin/env bash
# Set up, build and run every test: the full preset (host, hardware, embedded, Python, the
# install-and-consume test), or `asan` for the same under ASan + UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-full}"
bash scripts/build.sh "$preset"
ctest --preset "$preset" -j "$(nproc)"

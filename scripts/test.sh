#!/usr/bin/env bash
# Set up, build and run tests:
#   test.sh [full]  every test: host, hardware, embedded, Python, the install-and-consume test
#   test.sh asan    the same under ASan + UBSan, without the label long (the full benchmark
#                   segments and real-log SLAM runs; short segments of them run instead) and
#                   without what has nothing to sanitize (CMakePresets.json, preset asan)
#   test.sh quick   the inner loop: the default preset (host parts) and the label unit alone
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-full}"
case "$preset" in
  quick)
    bash scripts/build.sh default
    ctest --preset default -L '^unit$' -j "$(nproc)"
    ;;
  *)
    bash scripts/build.sh "$preset"
    ctest --preset "$preset" -j "$(nproc)"
    ;;
esac

#!/usr/bin/env bash
# Set up, build and run tests:
#   test.sh [full]  every test: host, hardware, embedded, Python, the install-and-consume test
#   test.sh asan    the same under ASan + UBSan, without the label long (the full benchmark
#                   segments and real-log SLAM runs; short segments of them run instead) and
#                   without what has nothing to sanitize (CMakePresets.json, preset asan)
#   test.sh quick   the inner loop: the default preset (host parts) and the label unit alone
#   test.sh fuzz    the readers' libFuzzer targets (preset fuzz, clang), 20 s each; full runs
#                   them too, after its own tests
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-full}"
case "$preset" in
  quick)
    bash scripts/build.sh default
    ctest --preset default -L '^unit$' -j "$(nproc)"
    ;;
  fuzz)
    bash scripts/build.sh fuzz intgrid_fuzz_targets
    ctest --preset fuzz -j "$(nproc)"
    ;;
  full)
    bash scripts/build.sh full
    ctest --preset full -j "$(nproc)"
    bash "$0" fuzz
    ;;
  *)
    bash scripts/build.sh "$preset"
    ctest --preset "$preset" -j "$(nproc)"
    ;;
esac

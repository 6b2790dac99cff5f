#!/usr/bin/env bash
# Long fuzzing runs of the readers' libFuzzer targets (tests/fuzz), beyond the 20 s each that
# `bash scripts/test.sh fuzz` gives them:
#   fuzz.sh [SECONDS] [TARGET...]   each TARGET (default: all four) for SECONDS (default 600),
#                                   one after the other, on all cores (-fork), growing the corpus
#                                   in build/fuzz/tests/fuzz/corpus/<reader>; a crash is written
#                                   to build/fuzz/crashes/ and ends the run with its status.
# Targets: fuzz_log_reader fuzz_carmen_reader fuzz_ros_map_reader fuzz_relations_reader.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
shift || true
targets=("$@")
((${#targets[@]} > 0)) || targets=(fuzz_log_reader fuzz_carmen_reader fuzz_ros_map_reader fuzz_relations_reader)
bash scripts/build.sh fuzz intgrid_fuzz_targets
mkdir -p build/fuzz/crashes
for target in "${targets[@]}"; do
  reader="${target#fuzz_}"
  reader="${reader%_reader}"
  echo "fuzz: $target for $seconds s"
  build/fuzz/tests/fuzz/"$target" -max_total_time="$seconds" -fork="$(nproc)" \
    -rss_limit_mb=2048 -timeout=10 -create_missing_dirs=1 \
    -artifact_prefix=build/fuzz/crashes/"$target"- \
    build/fuzz/tests/fuzz/corpus/"$reader" tests/fuzz/seeds/"$reader"
done

#!/usr/bin/env bash
# The SLAM on the Freiburg benchmark logs and the bundled log, both arithmetics, one default
# command line each, scored inside the tool. Prints a Markdown table of what metrics.json holds.
#   benchmark_slam.sh [BENCHMARK_DIR] [OUT_DIR]
# One thread (--threads 1): the speed targets are one core's; the result is the same for any
# count. BENCHMARK_DIR holds intel.clf, intel.relations, aces.clf, aces.relations (default
# ../shared/data/benchmark beside the checkout); the runs go to OUT_DIR (default
# build/benchmark_slam). Uses build/default/bin/intgrid, building it if missing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bench="${1:-$root/../shared/data/benchmark}"
out="${2:-$root/build/benchmark_slam}"
bin="$root/build/default/bin/intgrid"
[ -x "$bin" ] || { cmake --preset default -S "$root" >/dev/null && cmake --build "$root/build/default" -j"$(nproc)" --target intgrid >/dev/null; }
mkdir -p "$out"
runs=()
for log in intel aces; do
  if [ ! -f "$bench/$log.clf" ]; then
    echo "benchmark_slam: $bench/$log.clf absent, skipping $log" >&2
    continue
  fi
  for arith in int float; do
    "$bin" slam --log "$bench/$log.clf" --relations "$bench/$log.relations" --arith "$arith" \
      --threads 1 --out "$out/$log-$arith" >/dev/null
    runs+=("$log-$arith")
  done
done
for arith in int float; do
  "$bin" slam --log "$root/data/malaga_telecom_loop.log" \
    --reference "$root/data/malaga_telecom_loop_reference.log" --arith "$arith" \
    --threads 1 --out "$out/telecom-$arith" >/dev/null
  runs+=("telecom-$arith")
done
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
python3 - "$out" "${runs[@]}" <<'PY'
import json, sys
out, runs = sys.argv[1], sys.argv[2:]
print("| run | relation error (m) | rotation (deg) | odometry (m) | ATE (m) | loop closures | SLAM s | x real time | peak MB |")
print("|---|---|---|---|---|---|---|---|---|")
for r in runs:
    m = json.load(open(f"{out}/{r}/metrics.json"))
    rel, odo = m.get("relations"), m.get("odometry_relations")
    ate = m.get("ate", {}) or {}
    cell = lambda d, k, s: (f"{d[k]:.3f} ± {d[s]:.3f}" if d else "")
    print(f"| {r} | {cell(rel, 'trans_mean', 'trans_std')} | {cell(rel, 'rot_mean_deg', 'rot_std_deg')} | "
          f"{cell(odo, 'trans_mean', 'trans_std')} | {'%.3f' % ate['rmse_m'] if ate else ''} | "
          f"{m.get('loop_closures', '')} | {m['seconds']:.1f} | {m.get('real_time_factor', 0):.1f} | "
          f"{m.get('peak_memory_bytes', 0) / 1e6:.0f} |")
PY

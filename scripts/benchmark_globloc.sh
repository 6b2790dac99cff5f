#!/usr/bin/env bash
# Global localization on real scans, the pose grid beside its strongest baseline on the same maps
# and scans, one default command line each (docs/results.md#global-localization). Prints a
# Markdown table of what each run's metrics.json holds.
#   benchmark_globloc.sh [BENCHMARK_DIR] [OUT_DIR]
# Sets: the bundled log's scans in the bundled map, each on its own; the Freiburg benchmark logs'
# every 25th scan in the SLAM's own final map, against the SLAM's pose at that scan (within
# 0.3 m and 5 degrees), each on its own and with --track 10; the likelihood field on every 100th
# benchmark scan and on the bundled scans. BENCHMARK_DIR holds intel.clf and aces.clf (default
# ../shared/data/benchmark beside the checkout); OUT_DIR defaults to build/benchmark_globloc. One
# thread a run. Uses build/default/bin/intgrid, building it if missing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bench="${1:-$root/../shared/data/benchmark}"
out="${2:-$root/build/benchmark_globloc}"
bin="$root/build/default/bin/intgrid"
[ -x "$bin" ] || { cmake --preset default -S "$root" >/dev/null && cmake --build "$root/build/default" -j"$(nproc)" --target intgrid >/dev/null; }
mkdir -p "$out"
runs=()
globloc() {  # NAME ARGS...: one run, its metrics in OUT_DIR/NAME
  local name="$1"
  shift
  echo "benchmark_globloc: $name" >&2
  "$bin" globloc --threads 1 --out "$out/$name" "$@" >/dev/null
  runs+=("$name")
}
telecom=(--map "$root/data/malaga_telecom_map.yaml" --log "$root/data/malaga_telecom_loop.log"
  --reference "$root/data/malaga_telecom_loop_reference.log")
globloc telecom-pog "${telecom[@]}"
globloc telecom-pog-track "${telecom[@]}" --track 10
globloc telecom-likelihood "${telecom[@]}" --method likelihood-field
for log in aces intel; do
  if [ ! -f "$bench/$log.clf" ]; then
    echo "benchmark_globloc: $bench/$log.clf absent, skipping $log" >&2
    continue
  fi
  [ -f "$out/slam-$log/map.yaml" ] || "$bin" slam --log "$bench/$log.clf" --out "$out/slam-$log" >/dev/null
  set=(--map "$out/slam-$log/map.yaml" --log "$bench/$log.clf"
    --reference-trajectory "$out/slam-$log/trajectory.txt" --tolerance 0.3 5)
  globloc "$log-pog" "${set[@]}" --every 25
  globloc "$log-pog-track" "${set[@]}" --every 25 --track 10
  globloc "$log-pog-every100" "${set[@]}" --every 100
  globloc "$log-likelihood-every100" "${set[@]}" --every 100 --method likelihood-field
done
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), one thread a run"
python3 - "$out" "${runs[@]}" <<'PY'
import json, sys
out, runs = sys.argv[1], sys.argv[2:]
print("| run | found | share | median error (m) | flagged ambiguous | misses flagged | pose grid scores the answer higher | endpoints fit the reference better | scans fused (mean / most) | s a localization |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for r in runs:
    m = json.load(open(f"{out}/{r}/metrics.json"))
    ref = m["reference"]
    misses = ref["misses"]
    flagged = sum(1 for x in misses if x["ambiguous"])
    prefers = ref.get("misses_where_the_pose_grid_scores_the_answer_higher")
    fits = ref["misses_where_the_endpoints_fit_the_reference_better"]
    track = m.get("track")
    print(f"| {r} | {ref['within']} / {ref['matched']} | {100.0 * ref['within'] / ref['matched']:.1f}% | "
          f"{ref['median_position_error_m']:.3f} | {m['ambiguous_scans']} | {flagged} of {len(misses)} | "
          f"{'' if prefers is None else f'{prefers} of {len(misses)}'} | {fits} of {len(misses)} | "
          f"{'' if not track else '%.2f / %d' % (track['mean_scans'], track['most_scans'])} | "
          f"{m['seconds_per_scan']:.3f} |")
PY

#!/usr/bin/env bash
# The SLAM's default on variants of the benchmark logs that no setting was chosen on: the log
# started later (100 s to 1600 s in: another first submap, another first turn), without its ODOM
# records (odometry only inside FLASER, as other logs of the benchmark carry it), and resampled
# to 360 beams (neighbouring readings within 5% of each other averaged between them, a jump
# written as no return) and to 90 beams (every other reading).
#   held_out_variants.sh [BENCHMARK_DIR] [OUT_DIR] [sparse]
# With `sparse`, the 90-beam set instead: each log at every other reading from the first and from
# the second (the latter a sensor turned by one degree), started 0, 100, 200, 300, 400 and 600 s
# in; twelve runs a log. A run at a quarter of the hits is sensitive to small changes anywhere
# before it, so one 90-beam run says little about a change; the set's count of broken runs does.
# Integer, one thread (the x real time column is one core's), every option at its default.
# BENCHMARK_DIR as in benchmark_slam.sh (default ../shared/data/benchmark beside the checkout);
# the variant logs and the runs go to OUT_DIR (default build/held_out_variants). Prints a
# Markdown table of what each run's metrics.json holds. Uses build/default/bin/intgrid, building
# it if missing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bench="${1:-$root/../shared/data/benchmark}"
out="${2:-$root/build/held_out_variants}"
set_name="${3:-held-out}"
case "$set_name" in held-out | sparse) ;; *) echo "held_out_variants: unknown set '$set_name' (held-out or sparse)" >&2; exit 2 ;; esac
bin="$root/build/default/bin/intgrid"
[ -x "$bin" ] || { cmake --preset default -S "$root" >/dev/null && cmake --build "$root/build/default" -j"$(nproc)" --target intgrid >/dev/null; }
mkdir -p "$out"

# variant SOURCE.clf DEST.clf KIND [START] [FIRST]: the records from START seconds after the first
# laser record on (default 0); KIND start (no other change), no-odom, beams-up, beams-down (every
# other reading from reading FIRST, 0 or 1).
variant() {
  python3 - "$@" <<'PY'
import sys
src, dst, kind = sys.argv[1], sys.argv[2], sys.argv[3]
start = float(sys.argv[4]) if len(sys.argv) > 4 else 0.0
first_reading = int(sys.argv[5]) if len(sys.argv) > 5 else 0
lines = open(src).read().splitlines()
stamp = lambda l: float(l.split()[-3])  # ipc_timestamp
lasers = [l for l in lines if l.startswith("FLASER")]
first = min(stamp(l) for l in lasers)
saturation = max(max(map(float, l.split()[2:2 + int(l.split()[1])])) for l in lasers)
def resampled(line):
    f = line.split()
    n = int(f[1])
    r, rest = list(map(float, f[2:2 + n])), f[2 + n:]
    if kind == "beams-down":
        out = r[first_reading::2]
    else:  # beams-up: 2n beams over the same 180 degrees
        out = []
        for i in range(n):
            a, b = r[i], r[i + 1] if i + 1 < n else saturation
            near = a < saturation and b < saturation and abs(a - b) <= 0.05 * max(1.0, min(a, b))
            out += [a, 0.5 * (a + b) if near else saturation]
    return "FLASER %d %s %s" % (len(out), " ".join("%.3f" % x for x in out), " ".join(rest))
with open(dst, "w") as g:
    for l in lines:
        key = l.split(" ", 1)[0]
        if start > 0 and key in ("FLASER", "ODOM") and stamp(l) < first + start:
            continue
        if kind == "no-odom" and key == "ODOM":
            continue
        if kind.startswith("beams") and key == "FLASER":
            l = resampled(l)
        g.write(l + "\n")
PY
}

runs=()
for log in intel aces; do
  [ -f "$bench/$log.clf" ] || { echo "held_out_variants: $bench/$log.clf absent, skipping $log" >&2; continue; }
  kinds=()
  if [ "$set_name" = sparse ]; then
    for reading in even odd; do
      for start in 0 100 200 300 400 600; do kinds+=("beams-down-$reading-$start"); done
    done
  else
    kinds=(default no-odom beams-up beams-down start-100 start-400 start-800)
    [ "$log" = intel ] && kinds+=(start-1600)
  fi
  for kind in "${kinds[@]}"; do
    name="$log-$kind"
    if [ "$kind" = default ]; then
      clf="$bench/$log.clf"
    else
      clf="$out/$name.clf"
      case "$kind" in
        start-*) variant "$bench/$log.clf" "$clf" start "${kind#start-}" ;;
        beams-down-even-*) variant "$bench/$log.clf" "$clf" beams-down "${kind##*-}" 0 ;;
        beams-down-odd-*) variant "$bench/$log.clf" "$clf" beams-down "${kind##*-}" 1 ;;
        *) variant "$bench/$log.clf" "$clf" "$kind" ;;
      esac
    fi
    echo "held_out_variants: $name" >&2
    "$bin" slam --log "$clf" --relations "$bench/$log.relations" --threads 1 --out "$out/$name" >/dev/null
    runs+=("$name")
  done
done
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
python3 - "$out" "${runs[@]}" <<'PY'
import json, sys
out, runs = sys.argv[1], sys.argv[2:]
print("| run | relations scored | translation (m) | rotation (deg) | off by > 0.3 m or 5 deg | loop closures (rejected, switched off) | x real time |")
print("|---|---|---|---|---|---|---|")
for r in runs:
    m = json.load(open(f"{out}/{r}/metrics.json"))
    rel = m["relations"]
    print(f"| {r} | {rel['matched']} | {rel['trans_mean']:.4f} ± {rel['trans_std']:.4f} | "
          f"{rel['rot_mean_deg']:.2f} ± {rel['rot_std_deg']:.2f} | {rel['off']} ({100 * rel['off_fraction']:.1f}%) | "
          f"{m['loop_closures']} ({m['rejected_closures']}, {m['switched_off_closures']}) | "
          f"{m['real_time_factor']:.0f} |")
PY

#!/usr/bin/env bash
# Localization in a known map on the Freiburg benchmark logs, as issue 36's targets put it: each
# log's first half mapped by `intgrid slam`, its second half localized in that map by `intgrid
# localize` from no initial pose, scored on the relations whose two ends lie in the second half;
# beside it the SLAM of the whole log on the same relations. Prints a Markdown table.
#   benchmark_localize.sh [BENCHMARK_DIR] [OUT_DIR]
# One thread (--threads 1): the speed targets are one core's. BENCHMARK_DIR holds intel.clf,
# intel.relations, aces.clf, aces.relations (default ../shared/data/benchmark beside the
# checkout); the halves and runs go to OUT_DIR (default build/benchmark_localize). Uses
# build/default/bin/intgrid, building it if missing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bench="${1:-$root/../shared/data/benchmark}"
out="${2:-$root/build/benchmark_localize}"
bin="$root/build/default/bin/intgrid"
[ -x "$bin" ] || { cmake --preset default -S "$root" >/dev/null && cmake --build "$root/build/default" -j"$(nproc)" --target intgrid >/dev/null; }
mkdir -p "$out"
logs=()
for log in intel aces; do
  if [ ! -f "$bench/$log.clf" ]; then
    echo "benchmark_localize: $bench/$log.clf absent, skipping $log" >&2
    continue
  fi
  # The halves at the middle of the laser records' times (CARMEN: the ipc timestamp is the
  # third field from the end), and the relations of the second half.
  python3 - "$bench/$log.clf" "$bench/$log.relations" "$out/$log" <<'PY'
import sys
clf, relations, stem = sys.argv[1:]
lines = open(clf).read().splitlines()
stamp = lambda l: float(l.split()[-3])
lasers = [stamp(l) for l in lines if l.startswith(("FLASER", "ROBOTLASER1"))]
middle = 0.5 * (lasers[0] + lasers[-1])
timed = ("FLASER", "ROBOTLASER1", "ODOM")
with open(stem + "-first.clf", "w") as f:
    f.writelines(l + "\n" for l in lines if not l.startswith(timed) or stamp(l) < middle)
with open(stem + "-second.clf", "w") as f:
    f.writelines(l + "\n" for l in lines if not l.startswith(timed) or stamp(l) >= middle)
with open(stem + "-second.relations", "w") as f:
    for l in open(relations):
        v = l.split()
        if len(v) >= 2 and float(v[0]) >= middle and float(v[1]) >= middle:
            f.write(l)
PY
  "$bin" slam --log "$out/$log-first.clf" --threads 1 --out "$out/$log-first-half-map" >/dev/null
  "$bin" slam --log "$bench/$log.clf" --relations "$out/$log-second.relations" --threads 1 \
    --out "$out/$log-slam" >/dev/null
  "$bin" localize --map "$out/$log-first-half-map/map.yaml" --log "$out/$log-second.clf" \
    --relations "$out/$log-second.relations" --threads 1 --out "$out/$log-localize" >/dev/null
  logs+=("$log")
done
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
python3 - "$out" "${logs[@]}" <<'PY'
import json, sys
out, logs = sys.argv[1], sys.argv[2:]
print("| log | second half's relations | SLAM of the whole log (m, deg) | localize (m, deg) | localize / SLAM | off by > 0.3 m or 5 deg | scans tracked | first pose at scan | lost | x real time |")
print("|---|---|---|---|---|---|---|---|---|---|")
for log in logs:
    s = json.load(open(f"{out}/{log}-slam/metrics.json"))["relations"]
    m = json.load(open(f"{out}/{log}-localize/metrics.json"))
    l = m["relations"]
    print(f"| {log} | {l['matched']} of {l['matched'] + l['unmatched']} | "
          f"{s['trans_mean']:.4f}, {s['rot_mean_deg']:.2f} | {l['trans_mean']:.4f}, {l['rot_mean_deg']:.2f} | "
          f"{l['trans_mean'] / s['trans_mean']:.2f} | {l['off']} | {m['tracked_scans']} of {m['scans']} | "
          f"{m['first_pose_scan']} | {m['lost']} | {m['real_time_factor']:.0f} |")
PY

#!/usr/bin/env bash
# Localization in a known map on the Freiburg benchmark logs, as issue 36's targets put it: each
# log's first half mapped by `intgrid slam`, its second half localized in that map by `intgrid
# localize` from no initial pose, scored on the relations whose two ends lie in the second half;
# beside it the SLAM of the whole log on the same relations; and the second half carried off
# (cut after a third of its scans and rejoined at two thirds, the odometry going on as if the
# robot had not moved): when it is declared lost and found again. Prints two Markdown tables.
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
# The second half carried off: its laser records up to a third of them, then from two thirds on
# with both poses (laser and odometry) moved so that the odometry goes on from the last one
# before the cut as if the robot had not moved; ODOM records after the cut dropped.
import math
second = [l for l in lines if l.startswith("FLASER") and stamp(l) >= middle]
cut, rejoin = len(second) // 3, 2 * len(second) // 3
def pose(v, k):
    return float(v[k]), float(v[k + 1]), float(v[k + 2])
def compose(a, b):
    c, s = math.cos(a[2]), math.sin(a[2])
    return a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2]
def relative(a, b):
    c, s = math.cos(a[2]), math.sin(a[2])
    dx, dy = b[0] - a[0], b[1] - a[1]
    return c * dx + s * dy, -s * dx + c * dy, b[2] - a[2]
before, after = second[cut - 1].split(), second[rejoin].split()
odometry = -6  # odom_x odom_y odom_theta, then three timestamps and host fields
with open(stem + "-carried-off.clf", "w") as f:
    f.writelines(l + "\n" for l in second[:cut])
    for l in second[rejoin:]:
        v = l.split()
        for k in (odometry - 3, odometry):  # laser pose, odometry pose
            p = compose(pose(before, odometry), relative(pose(after, odometry), pose(v, k)))
            v[k:k + 3] = [f"{p[0]:.6f}", f"{p[1]:.6f}", f"{math.remainder(p[2], 2 * math.pi):.6f}"]
        f.write(" ".join(v) + "\n")
with open(stem + "-carried-off.cut", "w") as f:
    f.write(f"{cut} {stamp(second[cut - 1])} {stamp(second[rejoin])}\n")
PY
  "$bin" slam --log "$out/$log-first.clf" --threads 1 --out "$out/$log-first-half-map" >/dev/null
  "$bin" slam --log "$bench/$log.clf" --relations "$out/$log-second.relations" --threads 1 \
    --out "$out/$log-slam" >/dev/null
  "$bin" localize --map "$out/$log-first-half-map/map.yaml" --log "$out/$log-second.clf" \
    --relations "$out/$log-second.relations" --threads 1 --out "$out/$log-localize" >/dev/null
  "$bin" localize --map "$out/$log-first-half-map/map.yaml" --log "$out/$log-carried-off.clf" \
    --threads 1 --out "$out/$log-carried-off" >/dev/null
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
# Carried off: when the robot was declared lost and tracked again after the cut, and how far the
# poses tracked from then on lie from the whole log's SLAM at the same times (median).
import csv, math, statistics
print()
print("| log, second half carried off after a third to two thirds | cut after scan | lost at scan | tracked again at scan | its median distance from the SLAM's poses since (m) |")
print("|---|---|---|---|---|")
for log in logs:
    cut, t_cut, _ = open(f"{out}/{log}-carried-off.cut").read().split()
    cut = int(cut)
    rows = list(csv.DictReader(open(f"{out}/{log}-carried-off/fit.csv")))
    lost = next((i for i in range(cut, len(rows)) if rows[i]["state"] == "lost"), None)
    found = next((i for i in range(lost, len(rows)) if rows[i]["state"] == "tracking"), None) if lost is not None else None
    slam = {round(float(l.split()[0]), 4): list(map(float, l.split()[1:]))
            for l in open(f"{out}/{log}-slam/trajectory.txt") if not l.startswith("#")}
    dist = []
    for l in open(f"{out}/{log}-carried-off/trajectory.txt"):
        if l.startswith("#"):
            continue
        t, x, y, _ = map(float, l.split())
        if found is not None and t >= float(rows[found]["t"]) and round(t, 4) in slam:
            s = slam[round(t, 4)]
            dist.append(math.hypot(x - s[0], y - s[1]))
    print(f"| {log} | {cut - 1} | {lost} | {found} | {statistics.median(dist) if dist else float('nan'):.3f} |")
PY

#!/usr/bin/env bash
# Leave one log out: what a SLAM setting chosen on one benchmark log gives on the other.
#   leave_one_out.sh OPTION VALUE... [-- BENCHMARK_DIR [OUT_DIR]]
# Runs `intgrid slam --OPTION VALUE` (integer, every other option at its default) on each
# benchmark log (intel, aces) for each value, then, holding each log out in turn, takes the
# value the other log scores best (least mean relation translation error) and prints what
# that value gives on the held-out log beside the default's and the held-out log's own best.
# A default that only one log would choose shows here as a held-out error above the best.
# BENCHMARK_DIR as in benchmark_slam.sh (default ../shared/data/benchmark beside the checkout);
# runs go to OUT_DIR/OPTION/LOG-VALUE, the default's to OUT_DIR/default/LOG (OUT_DIR default
# build/leave_one_out); a run already there with its metrics.json is not run again (remove
# OUT_DIR after changing the code). The runs use a copy of the binary taken at the start, so
# that a build during a sweep does not mix two revisions. Uses build/default/bin/intgrid, building it if missing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
[ $# -ge 2 ] || { echo "usage: leave_one_out.sh OPTION VALUE... [-- BENCHMARK_DIR [OUT_DIR]]" >&2; exit 2; }
option="${1#--}"
shift
values=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do values+=("$1"); shift; done
[ $# -gt 0 ] && shift
bench="${1:-$root/../shared/data/benchmark}"
out="${2:-$root/build/leave_one_out}/$option"
bin="$root/build/default/bin/intgrid"
[ -x "$bin" ] || { cmake --preset default -S "$root" >/dev/null && cmake --build "$root/build/default" -j"$(nproc)" --target intgrid >/dev/null; }
copy="$(mktemp)"
trap 'rm -f "$copy"' EXIT
cp "$bin" "$copy" && chmod +x "$copy"
bin="$copy"
# The default as the help prints it: TYPE=DEFAULT (an "=" after "<" or ">" belongs to the
# type's range), or "(default: submaps D, grid G)" on its line.
default="$("$bin" slam --help | python3 -c '
import re, sys
m = re.search(r"^\s*--" + re.escape(sys.argv[1]) + r" (\S.*?)(?<![<>])=(\S+)|^\s*--" + re.escape(sys.argv[1]) +
              r" .*?\(default: submaps ([^,)]+)", sys.stdin.read(), re.M)
print(m.group(2) or m.group(3) if m else "")' "$option")"
[ -n "$default" ] || { echo "leave_one_out: no default found for --$option in 'intgrid slam --help'" >&2; exit 2; }
mkdir -p "$out"
logs=()
for log in intel aces; do
  [ -f "$bench/$log.clf" ] || { echo "leave_one_out: $bench/$log.clf absent" >&2; exit 2; }
  logs+=("$log")
  # The default's run, shared by every option swept into the same OUT_DIR.
  [ -f "$out/../default/$log/metrics.json" ] ||
    "$bin" slam --log "$bench/$log.clf" --relations "$bench/$log.relations" \
      --out "$out/../default/$log" >/dev/null 2>&1
  for v in "${values[@]}"; do
    run="$out/$log-$v"
    [ "$v" = "$default" ] || [ -f "$run/metrics.json" ] && continue
    echo "leave_one_out: $log --$option $v" >&2
    "$bin" slam --log "$bench/$log.clf" --relations "$bench/$log.relations" "--$option" "$v" \
      --out "$run" >/dev/null 2>&1
  done
done
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
python3 - "$out" "$option" "$default" "${values[*]}" "${logs[@]}" <<'PY'
import json, sys
out, option, default, values, logs = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4].split(), sys.argv[5:]
values = sorted(set(values) | {default}, key=float)
def metrics(log, v):
    run = f"{out}/../default/{log}" if v == default else f"{out}/{log}-{v}"
    m = json.load(open(f"{run}/metrics.json"))
    r = m["relations"]
    return r["trans_mean"], r["rot_mean_deg"], 100.0 * r["off"] / max(1, r["matched"])
runs = {(log, v): metrics(log, v) for log in logs for v in values}
fmt = lambda t: f"{t[0]:.4f} m, {t[1]:.2f} deg, {t[2]:.1f}% off"
print(f"--{option} (default {default}): mean relation error on each log")
print("| value | " + " | ".join(logs) + " |")
print("|---|" + "---|" * len(logs))
for v in values:
    print(f"| {v}{' (default)' if v == default else ''} | " + " | ".join(fmt(runs[(l, v)]) for l in logs) + " |")
print()
print("| held out | chosen on the other log | held-out error with it | with the default | held-out log's own best |")
print("|---|---|---|---|---|")
for held in logs:
    other = [l for l in logs if l != held]
    chosen = min(values, key=lambda v: sum(runs[(l, v)][0] for l in other))
    own = min(values, key=lambda v: runs[(held, v)][0])
    print(f"| {held} | {chosen} | {fmt(runs[(held, chosen)])} | {fmt(runs[(held, default)])} | "
          f"{own}: {fmt(runs[(held, own)])} |")
PY

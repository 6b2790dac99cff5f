#!/usr/bin/env bash
# Long hardware runs that CI does not do (docs/hardware.md, "Nightly runs"): the Verilator tests
# and the SystemC co-simulations of both kernels, and the ISM sub-module unit tests, once per seed
# over many seeds. Every program checks against golden itself; this script only runs them, prints
# one summary line per seed, keeps each run's output, and exits non-zero if any run failed.
#
#   bash scripts/hw_nightly.sh                      seeds 1..20, building the programs first
#   bash scripts/hw_nightly.sh --first 100 --count 50
#   bash scripts/hw_nightly.sh --no-build           uses build/full as it is
#   bash scripts/hw_nightly.sh --logs DIR           keeps the logs in DIR (default
#                                                   build/full/hw_nightly)
#
# How a seed reaches each program (none takes a seed argument; all read it from the environment):
#   index_fusion_rtl_test, index_fusion_cosim    INTGRID_TB_SEED (each test derives its own)
#   sectoral_ism_rtl_test, sectoral_ism_cosim,   INTGRID_ISM_SEED (replaces each test's fixed
#   sectoral_ism_units_test                      default seed)
set -uo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build="$root/build/full"
logs="$build/hw_nightly"
first=1
count=20
do_build=1

say() { printf 'hw_nightly: %s\n' "$*"; }
die() {
  printf 'hw_nightly: error: %s\n' "$*" >&2
  exit 2
}
usage="usage: bash scripts/hw_nightly.sh [--first N] [--count N] [--no-build] [--logs DIR]"
while [ $# -gt 0 ]; do
  case "$1" in
    --first) first=${2:?$usage}; shift ;;
    --count) count=${2:?$usage}; shift ;;
    --logs) logs=${2:?$usage}; shift ;;
    --no-build) do_build=0 ;;
    -h | --help)
      sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    *) die "unknown argument '$1' ($usage)" ;;
  esac
  shift
done
[[ "$first" =~ ^[0-9]+$ && "$count" =~ ^[0-9]+$ ]] || die "--first and --count take numbers"

# program|seed variable|directory under build/full
runs=(
  "index_fusion_rtl_test|INTGRID_TB_SEED|testbench"
  "index_fusion_cosim|INTGRID_TB_SEED|testbench"
  "sectoral_ism_rtl_test|INTGRID_ISM_SEED|testbench"
  "sectoral_ism_cosim|INTGRID_ISM_SEED|testbench"
  "sectoral_ism_units_test|INTGRID_ISM_SEED|testbench"
)
targets=()
for run in "${runs[@]}"; do targets+=("${run%%|*}"); done

if [ "$do_build" -eq 1 ]; then
  mkdir -p "$logs"
  say "building ${targets[*]} (log in $logs/build.log)"
  if ! bash scripts/build.sh full "${targets[@]}" >"$logs/build.log" 2>&1; then
    tail -n 40 "$logs/build.log" >&2
    die "the build failed (last lines above)"
  fi
fi
for run in "${runs[@]}"; do
  IFS='|' read -r prog _ dir <<<"$run"
  [ -x "$build/$dir/$prog" ] || die "$build/$dir/$prog is not built (run without --no-build)"
done
mkdir -p "$logs"

failed_seeds=0
start_all=$(date +%s)
for ((seed = first; seed < first + count; ++seed)); do
  line="seed $seed:"
  seed_ok=1
  for run in "${runs[@]}"; do
    IFS='|' read -r prog var dir <<<"$run"
    log="$logs/seed_${seed}_$prog.log"
    t0=$(date +%s.%N)
    env "$var=$seed" "$build/$dir/$prog" >"$log" 2>&1
    rc=$?
    t1=$(date +%s.%N)
    secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
    if [ "$rc" -eq 0 ]; then
      line+=" $prog ok ${secs}s,"
    else
      line+=" $prog FAILED (exit $rc, $log),"
      seed_ok=0
    fi
  done
  if [ "$seed_ok" -eq 1 ]; then
    say "${line%,} -> pass"
  else
    say "${line%,} -> FAIL"
    failed_seeds=$((failed_seeds + 1))
  fi
done
say "$count seeds from $first, $failed_seeds failed, $(($(date +%s) - start_all)) s; logs in $logs"
[ "$failed_seeds" -eq 0 ]

#!/usr/bin/env bash
# The hardware kernels' reports (docs/hardware.md, "What each kernel reports"), measured, not computed:
#   - cycles per cell and latency, back-pressure off and on, and Verilator's simulation speed:
#     the testbenches' report modes, run from build/full (the default preset has no hardware);
#   - Yosys synth_ice40 resources (LUT4, carry, DFF, BRAM) of each kernel configuration, and
#     nextpnr-ice40 Fmax on an iCE40 HX8K (ct256) of the same configuration with every port
#     registered (a timing harness, so that every path of the kernel is register to register);
#   - Yosys generic `synth` cell counts (technology-neutral);
#   - the same for a plain registered 8-bit saturating adder, the reference point of docs/hardware.md;
#   - the targets, and whether each is met.
# Writes docs/hardware_report.md and docs/hardware_report.json (each atomically), deterministic
# apart from timings and the date. `intgrid demo` prints the JSON's "summary" rows.
#
#   bash scripts/hw_reports.sh              builds what it runs first (bash scripts/build.sh full
#                                           <its programs>), then measures
#   bash scripts/hw_reports.sh --no-build   uses build/full as it is
#
# Adding a kernel: one entry in `benches` (its report program, also in `build_targets`, and the
# parser of its JSON lines in scripts/hw_report_write.py, `SIM`), entries in `designs`, and a
# harness in testbench/hw_report/ (or in write_harnesses, if it takes a configuration's widths).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build="$root/build/full"
config="$root/rtl/config"  # the sectoral ISM's committed configurations (intgrid hw-config)
docs="$root/docs"
seed=1
start_s=$(date +%s)

say() { printf 'hw_reports: %s\n' "$*"; }
die() {
  printf 'hw_reports: error: %s\n' "$*" >&2
  exit 1
}

do_build=1
for arg in "$@"; do
  case "$arg" in
    --no-build) do_build=0 ;;
    -h | --help)
      sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    *) die "unknown argument '$arg' (usage: bash scripts/hw_reports.sh [--no-build])" ;;
  esac
done

for tool in yosys nextpnr-ice40 verilator lscpu python3 cmake; do
  command -v "$tool" >/dev/null 2>&1 ||
    die "'$tool' not found on PATH (bash scripts/setup.sh installs the project's tools)"
done

tmp=$(mktemp -d "${TMPDIR:-/tmp}/intgrid_hw_reports.XXXXXX")
cleanup() {
  rm -rf "$tmp"
  rm -f "$docs"/.hardware_report.*.tmp.$$
}
trap cleanup EXIT

# --- Build -------------------------------------------------------------------------------------
# The report programs below and the ISM's tables (ROM files and parameters), of the full preset.
build_targets=(index_fusion_rtl_test sectoral_ism_report sectoral_ism_tables)
if [ "$do_build" -eq 1 ]; then
  say "building (bash scripts/build.sh full ${build_targets[*]}; log in $tmp/build.log while it runs)"
  if ! bash scripts/build.sh full "${build_targets[@]}" >"$tmp/build.log" 2>&1; then
    tail -n 40 "$tmp/build.log" >&2
    die "the build failed (last lines above)"
  fi
fi

# --- Machine and tools -------------------------------------------------------------------------
cpu=$(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -n 1)
cores=$(nproc)
v_yosys=$(yosys -V 2>&1 | head -n 1)
v_nextpnr=$(nextpnr-ice40 --version 2>&1 | head -n 1)
v_verilator=$(verilator --version 2>&1 | head -n 1)
say "machine: $cpu, $cores cores"
say "tools: $v_yosys; $v_nextpnr; $v_verilator"

# --- Simulation: the testbenches' report modes -------------------------------------------------
# kernel|program (under build/full)|arguments: each prints one JSON line per configuration.
# INTGRID_TB_SEED fixes the random traffic of the testbenches that draw it, so reruns compare.
benches=(
  "index_fusion|testbench/index_fusion_rtl_test|--report"
  "sectoral_ism|testbench/sectoral_ism_report|1000"
)
: >"$tmp/sim.jsonl"
for entry in "${benches[@]}"; do
  IFS='|' read -r kernel program args <<<"$entry"
  [ -x "$build/$program" ] || die "$build/$program missing: build it with bash scripts/build.sh full"
  say "simulating $kernel: $program $args"
  # shellcheck disable=SC2086  # the arguments are words
  if ! INTGRID_TB_SEED=$seed "$build/$program" $args >"$tmp/sim_$kernel.out" \
    2>"$tmp/sim_$kernel.err"; then
    cat "$tmp/sim_$kernel.err" >&2
    die "$program $args failed"
  fi
  lines=$(grep -c '^{' "$tmp/sim_$kernel.out" || true)
  [ "$lines" -gt 0 ] || die "$program $args printed no JSON line"
  grep '^{' "$tmp/sim_$kernel.out" >>"$tmp/sim.jsonl"
done

# --- Synthesis and place and route -------------------------------------------------------------
for cfg in cone16 cone12; do
  { [ -f "$config/$cfg/sectoral_ism_$cfg.ys" ] && [ -f "$config/$cfg/sectoral_ism_${cfg}_log_add.mem" ]; } ||
    die "$config/$cfg/sectoral_ism_$cfg.* missing (ROM files and parameters of the ISM)"
done

# Timing harnesses: the kernel with a register on every input and every output port, so that
# nextpnr's Fmax covers every path of the kernel (unregistered ports are only I/O delays).
# The fixed ones are files (testbench/hw_report/); the sectoral ISM's, which take its
# configuration's widths, are written here.
write_harnesses() {
  mkdir -p "$tmp/harness"
  cp "$root"/testbench/hw_report/*.sv "$tmp/harness/"
  local cfg upper zw iw
  for cfg in cone16 cone12; do
    upper=$(printf '%s' "$cfg" | tr '[:lower:]' '[:upper:]')
    zw=$(sed -n 's/^chparam -set READING_W \([0-9]*\) .*/\1/p' "$config/$cfg/sectoral_ism_$cfg.ys")
    iw=$(sed -n 's/^chparam -set IDX_W \([0-9]*\) .*/\1/p' "$config/$cfg/sectoral_ism_$cfg.ys")
    { [ -n "$zw" ] && [ -n "$iw" ]; } || die "no READING_W / IDX_W in $config/$cfg/sectoral_ism_$cfg.ys"
    cat >"$tmp/harness/sectoral_ism_${cfg}_timing.sv" <<EOF
// sectoral_ism, configuration $cfg, with every port registered (timing harness only).
\`include "sectoral_ism_$cfg.svh"
module sectoral_ism_${cfg}_timing (
  input  logic          clk_i,
  input  logic          rst_ni,
  input  logic          z_valid_i,
  output logic          z_ready_o,
  input  logic [$zw-1:0] z_data_i,
  input  logic          z_last_i,
  output logic          y_valid_o,
  input  logic          y_ready_i,
  output logic [$iw-1:0] y_data_o,
  output logic          y_last_o
);
  logic          z_valid_q, z_last_q, y_ready_q, z_ready_d, y_valid_d, y_last_d;
  logic [$zw-1:0] z_data_q;
  logic [$iw-1:0] y_data_d;
  always_ff @(posedge clk_i) begin
    z_valid_q <= z_valid_i;
    z_last_q  <= z_last_i;
    z_data_q  <= z_data_i;
    y_ready_q <= y_ready_i;
    z_ready_o <= z_ready_d;
    y_valid_o <= y_valid_d;
    y_data_o  <= y_data_d;
    y_last_o  <= y_last_d;
  end
  sectoral_ism #(\`SECTORAL_ISM_${upper}_PARAMS) i_dut (
    .clk_i, .rst_ni,
    .z_valid_i(z_valid_q), .z_ready_o(z_ready_d), .z_data_i(z_data_q), .z_last_i(z_last_q),
    .y_valid_o(y_valid_d), .y_ready_i(y_ready_q), .y_data_o(y_data_d), .y_last_o(y_last_d));
endmodule
EOF
  done
}
write_harnesses

# id|kernel|parameters (matched against the simulation's JSON)|top|Yosys set-up of the top|
#   harness|Yosys set-up of the harness|Fmax target in MHz (- none)|must fit the part (yes/-)|
#   more seeds to place with, to show how much Fmax moves with the placement (- none)
# Resources are those of `top`; Fmax that of the harness. The Fmax target is also nextpnr's
# --freq (100 MHz where there is none). The reference point is the registered adder itself.
seeds_small="2 3 4 5 6 7 8"  # a second or less each
seeds_large="2 3 4"          # about 10 s each
designs=(
  "reference_b8|reference|B=8|saturating_add_reg|chparam -set B 8 saturating_add_reg|saturating_add_reg|chparam -set B 8 saturating_add_reg|-|-|$seeds_small"
  "index_fusion_b8_l1|index_fusion|B=8,LANES=1|index_fusion|chparam -set B 8 -set LANES 1 index_fusion|index_fusion_timing|chparam -set B 8 -set LANES 1 index_fusion_timing|80|-|$seeds_small"
  "index_fusion_b8_l8|index_fusion|B=8,LANES=8|index_fusion|chparam -set B 8 -set LANES 8 index_fusion|index_fusion_timing|chparam -set B 8 -set LANES 8 index_fusion_timing|-|yes|$seeds_small"
  "index_fusion_b8_l16|index_fusion|B=8,LANES=16|index_fusion|chparam -set B 8 -set LANES 16 index_fusion|index_fusion_timing|chparam -set B 8 -set LANES 16 index_fusion_timing|-|yes|-"
  "sectoral_ism_cone16|sectoral_ism|config=cone16|sectoral_ism|script $config/cone16/sectoral_ism_cone16.ys|sectoral_ism_cone16_timing||40|yes|$seeds_large"
  "sectoral_ism_cone12|sectoral_ism|config=cone12|sectoral_ism|script $config/cone12/sectoral_ism_cone12.ys|sectoral_ism_cone12_timing||40|yes|$seeds_large"
)

# Every run reads every file of rtl/ (the package first) and every harness; `-top` keeps what the
# design uses. The configurations name their ROM files relative to rtl/, where Yosys finds them.
rtl_read="read_verilog -sv $root/rtl/sectoral_ism_pkg.sv $(ls "$root"/rtl/*.sv | grep -v '_pkg\.sv$' | tr '\n' ' ');"
rtl_read+=" read_verilog -sv -I$config/cone16 -I$config/cone12 $tmp/harness/*.sv"

# place DIR FREQ SEED NAME: nextpnr on DIR/harness.json, log DIR/NAME.log, status DIR/NAME.rc.
place() {
  local rc=0
  nextpnr-ice40 --hx8k --package ct256 --json "$1/harness.json" --pcf-allow-unconstrained \
    --freq "$2" --seed "$3" --timing-allow-fail -l "$1/$4.log" >/dev/null 2>&1 || rc=$?
  echo "$rc" >"$1/$4.rc"
}
# The final (post-route) "Max frequency for clock" figure of a nextpnr log, or nothing.
last_fmax() {
  sed -n "s/.*Max frequency for clock '[^']*': \([0-9.]*\) MHz.*/\1/p" "$1" | tail -n 1
}
yosys_run() {
  local log=$1 what=$2
  shift 2
  if ! yosys -q -l "$log" "$@" >/dev/null 2>&1; then
    tail -n 15 "$log" >&2
    die "Yosys failed: $what (the end of its log is above)"
  fi
}

: >"$tmp/designs.tsv"
n=${#designs[@]}
i=0
for entry in "${designs[@]}"; do
  i=$((i + 1))
  IFS='|' read -r id kernel params top setup harness hsetup target fit more_seeds <<<"$entry"
  d="$tmp/designs/$id"
  mkdir -p "$d"
  freq=$target
  [ "$freq" = "-" ] && freq=100
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$id" "$kernel" "$params" "$top" "$harness" "$target" \
    "$fit" >>"$tmp/designs.tsv"

  say "[$i/$n] $id: Yosys synth_ice40 of $top"
  yosys_run "$d/ice40.log" "synth_ice40 $id" -p \
    "$rtl_read; $setup; synth_ice40 -top $top; tee -q -o $d/ice40.stat stat"

  say "[$i/$n] $id: Yosys generic synth of $top"
  yosys_run "$d/generic.log" "synth $id" -p \
    "$rtl_read; $setup; synth -flatten -top $top -run :fine; design -save coarse; memory_unpack; tee -q -o $d/memories.stat stat; design -load coarse; synth -flatten -top $top -run fine:; tee -q -o $d/generic.stat stat"

  say "[$i/$n] $id: Yosys synth_ice40 of the timing harness $harness"
  yosys_run "$d/harness.log" "synth_ice40 $harness" -p \
    "$rtl_read; ${hsetup:+$hsetup; }synth_ice40 -top $harness -json $d/harness.json"

  say "[$i/$n] $id: nextpnr-ice40 --hx8k --package ct256 --freq $freq --seed $seed"
  place "$d" "$freq" "$seed" pnr
  fmax=$(last_fmax "$d/pnr.log")
  if [ -n "$fmax" ]; then
    say "[$i/$n] $id: Fmax $fmax MHz"
  else
    say "[$i/$n] $id: not placed: $(grep -m 1 'ERROR' "$d/pnr.log" || echo 'see the nextpnr log')"
  fi
  if [ "$more_seeds" != - ] && [ -n "$fmax" ]; then
    spread=()
    for s in $more_seeds; do
      place "$d" "$freq" "$s" "pnr_seed$s"
      spread+=("$(last_fmax "$d/pnr_seed$s.log")")
    done
    say "[$i/$n] $id: Fmax with seeds $more_seeds: ${spread[*]} MHz"
  fi
done

# --- The report --------------------------------------------------------------------------------
say "writing docs/hardware_report.md and docs/hardware_report.json"
mkdir -p "$docs"
md_tmp="$docs/.hardware_report.md.tmp.$$"
json_tmp="$docs/.hardware_report.json.tmp.$$"
end_s=$(date +%s)
python3 "$root/scripts/hw_report_write.py" "$tmp" "$md_tmp" "$json_tmp" "$cpu" "$cores" "$v_yosys" "$v_nextpnr" \
  "$v_verilator" "$seed" "$(date -u +%Y-%m-%d)" "$(date -u +%Y-%m-%dT%H:%M:%SZ)" \
  "$((end_s - start_s))" || die "writing the report failed"
mv -f "$json_tmp" "$docs/hardware_report.json"
mv -f "$md_tmp" "$docs/hardware_report.md"
say "wrote docs/hardware_report.md and docs/hardware_report.json in $((end_s - start_s)) s"

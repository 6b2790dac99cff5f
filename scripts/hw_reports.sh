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
# parser of its JSON lines in the Python part below, `SIM`), entries in `designs`, and a harness
# in write_harnesses.
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
write_harnesses() {
  mkdir -p "$tmp/harness"
  cat >"$tmp/harness/saturating_add_reg.sv" <<'EOF'
// The reference point of docs/hardware.md: a plain B-bit saturating adder, inputs and output registered.
module saturating_add_reg #(
  parameter int unsigned B = 8
) (
  input  logic         clk_i,
  input  logic [B-1:0] a_i,
  input  logic [B-1:0] b_i,
  output logic [B-1:0] y_o
);
  logic [B-1:0] a_q, b_q, y_d;
  always_ff @(posedge clk_i) begin
    a_q <= a_i;
    b_q <= b_i;
    y_o <= y_d;
  end
  saturating_add #(.B(B)) i_add (.a_i(a_q), .b_i(b_q), .y_o(y_d));
endmodule
EOF
  cat >"$tmp/harness/index_fusion_timing.sv" <<'EOF'
// index_fusion inside a design (timing harness only): every port of the kernel between
// registers, its two data buses filled one bit a cycle from a pin each through shift registers,
// its output folded to one pin through two registered stages (a parity a lane, then their
// parity), so that any lane count fits the part's pins and only kernel paths limit Fmax.
module index_fusion_timing #(
  parameter int unsigned B     = 8,
  parameter int unsigned LANES = 8
) (
  input  logic clk_i,
  input  logic rst_ni,
  input  logic a_valid_i,
  output logic a_ready_o,
  input  logic a_bit_i,
  input  logic a_last_i,
  input  logic b_valid_i,
  output logic b_ready_o,
  input  logic b_bit_i,
  input  logic b_last_i,
  output logic y_valid_o,
  input  logic y_ready_i,
  output logic y_parity_o,
  output logic y_last_o
);
  logic               a_valid_q, b_valid_q, a_last_q, b_last_q, y_ready_q;
  logic [LANES*B-1:0] a_data_q, b_data_q, y_data_d, y_data_q;
  logic [LANES-1:0]   lane_parity_q;
  logic               a_ready_d, b_ready_d, y_valid_d, y_last_d;
  always_ff @(posedge clk_i) begin
    a_valid_q <= a_valid_i;
    b_valid_q <= b_valid_i;
    a_last_q  <= a_last_i;
    b_last_q  <= b_last_i;
    a_data_q  <= {a_data_q[LANES*B-2:0], a_bit_i};
    b_data_q  <= {b_data_q[LANES*B-2:0], b_bit_i};
    y_ready_q <= y_ready_i;
    a_ready_o <= a_ready_d;
    b_ready_o <= b_ready_d;
    y_valid_o <= y_valid_d;
    y_last_o  <= y_last_d;
    y_data_q  <= y_data_d;
    for (int unsigned l = 0; l < LANES; l++) lane_parity_q[l] <= ^y_data_q[l*B +: B];
    y_parity_o <= ^lane_parity_q;
  end
  index_fusion #(.B(B), .LANES(LANES)) i_dut (
    .clk_i, .rst_ni,
    .a_valid_i(a_valid_q), .a_ready_o(a_ready_d), .a_data_i(a_data_q), .a_last_i(a_last_q),
    .b_valid_i(b_valid_q), .b_ready_o(b_ready_d), .b_data_i(b_data_q), .b_last_i(b_last_q),
    .y_valid_o(y_valid_d), .y_ready_i(y_ready_q), .y_data_o(y_data_d), .y_last_o(y_last_d));
endmodule
EOF
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
cat >"$tmp/report.py" <<'PY'
# Reads what the script collected in TMP and writes the Markdown and JSON reports.
import glob
import json
import re
import sys

(tmp, md_path, json_path, cpu, cores, v_yosys, v_nextpnr, v_verilator, seed, date, stamp,
 run_seconds) = sys.argv[1:13]

PART = {"family": "iCE40", "device": "HX8K", "package": "ct256", "lut4": 7680, "bram": 32}
NEXTPNR = ("nextpnr-ice40 --hx8k --package ct256 --pcf-allow-unconstrained --timing-allow-fail "
           "--seed %s --freq <target, else 100>" % seed)
# docs/hardware.md's figure for the reference point, shown beside our measurement of it.
QUOTED_REFERENCE = {"fmax_mhz": 93, "lut4": 31}
KERNEL_TITLES = {
    "index_fusion": "Kernel 1: index fusion (S_eps)",
    "sectoral_ism": "Kernel 2: sectoral ISM (integer)",
    "reference": "Reference point: a registered 8-bit saturating adder",
}


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def stat_cells(text):
    """Cell type -> count of the last `Number of cells` block of a Yosys `stat` (flattened)."""
    blocks = re.split(r"Number of cells:\s+\d+\n", text)
    if len(blocks) < 2:
        raise SystemExit("hw_reports: error: no cell counts in a Yosys stat")
    cells = {}
    for line in blocks[-1].splitlines():
        m = re.match(r"^\s+(\S+)\s+(\d+)\s*$", line)
        if not m:
            break
        cells[m.group(1)] = int(m.group(2))
    return cells


def stat_number(text, what):
    found = re.findall(r"Number of %s:\s+(\d+)" % what, text)
    return int(found[-1]) if found else 0


def ice40_resources(design_dir):
    cells = stat_cells(read(design_dir + "/ice40.stat"))
    lut4 = cells.get("SB_LUT4", 0)
    bram = cells.get("SB_RAM40_4K", 0)
    return {
        "lut4": lut4,
        "carry": cells.get("SB_CARRY", 0),
        "dff": sum(n for t, n in cells.items() if t.startswith("SB_DFF")),
        "bram": bram,
        "lut4_utilisation_percent": round(100.0 * lut4 / PART["lut4"], 2),
        "bram_utilisation_percent": round(100.0 * bram / PART["bram"], 2),
        "cells": dict(sorted(cells.items())),
    }


def generic_resources(design_dir):
    cells = stat_cells(read(design_dir + "/generic.stat"))
    coarse = read(design_dir + "/memories.stat")
    flops = sum(n for t, n in cells.items() if re.search(r"DFF|DLATCH|\$_SR_", t))
    return {
        "cells": sum(cells.values()),
        "flip_flops": flops,
        "gates": sum(cells.values()) - flops,
        "memories_before_mapping": stat_number(coarse, "memories"),
        "memory_bits_before_mapping": stat_number(coarse, "memory bits"),
        "by_type": dict(sorted(cells.items())),
    }


def place_and_route(design_dir, freq):
    log = read(design_dir + "/pnr.log")
    rc = int(read(design_dir + "/pnr.rc").strip())
    fmax = re.findall(r"Max frequency for clock '[^']*': ([\d.]+) MHz", log)
    use = {}
    for m in re.finditer(r"^Info:\s+(\w+):\s+(\d+)/\s*(\d+)\s+\d+%", log, re.M):
        use.setdefault(m.group(1), {"used": int(m.group(2)), "available": int(m.group(3))})
    error = re.search(r"^ERROR: (.*)$", log, re.M)
    placed = rc == 0 and bool(fmax)
    by_seed = None
    sweep = glob.glob(design_dir + "/pnr_seed*.log")
    if placed and sweep:
        runs = [(int(seed), float(fmax[-1]))]
        for path in sweep:
            found = re.findall(r"Max frequency for clock '[^']*': ([\d.]+) MHz", read(path))
            runs.append((int(re.search(r"seed(\d+)\.log$", path).group(1)),
                         float(found[-1]) if found else None))
        runs.sort()
        values = [f for _, f in runs if f is not None]
        by_seed = {"seeds": [s for s, _ in runs], "fmax_mhz": [f for _, f in runs],
                   "min": min(values), "max": max(values)}
    over = {k: v["used"] - v["available"] for k, v in use.items() if v["used"] > v["available"]}
    return {
        "design": "every port registered (timing harness)",
        "constraint_mhz": freq,
        "placed": placed,
        "fmax_mhz": float(fmax[-1]) if placed else None,
        "utilisation": use,
        "over_capacity": over,
        "error": error.group(1).strip() if error else None,
        "fmax_by_seed": by_seed,
    }


# --- Simulation: one parser per kernel's report JSON -------------------------------------------
def fusion_sim(r):
    off, on = r["bp_off"], r["bp_on"]
    return {
        "checked": bool(off["ok"] and on["ok"]),
        "cycles_per_cell": off["cycles_per_cell"],
        "cycles_per_cell_backpressure": on["cycles_per_cell"],
        "latency_cycles": off["latency_cycles"]["mean"],
        "latency_cycles_backpressure": on["latency_cycles"]["mean"],
        "sim_cells_per_s": off["sim_cells_per_s"],
    }


def ism_sim(r):
    cpc, lat = r["cycles_per_cell"], r["streaming_latency_mean"]
    return {
        "checked": bool(r["checked"]),
        "cycles_per_cell": cpc["no_backpressure"],
        "cycles_per_cell_backpressure": cpc["backpressure_50"],
        "latency_cycles": lat["no_backpressure"],
        "latency_cycles_backpressure": lat["backpressure_50"],
        "sim_cells_per_s": r["verilator_cells_per_second"],
    }


SIM = {"index_fusion": fusion_sim, "sectoral_ism": ism_sim}

sim_rows = [json.loads(line) for line in read(tmp + "/sim.jsonl").splitlines() if line.strip()]
for row in sim_rows:
    if row.get("kernel") not in SIM:
        raise SystemExit("hw_reports: error: no parser for the report of kernel %r" % row.get("kernel"))
    SIM[row["kernel"]](row)  # fails here, clearly, if a report's fields changed
failed = [r for r in sim_rows if not SIM[r["kernel"]](r)["checked"]]
if failed:
    raise SystemExit("hw_reports: error: a simulation failed its checks: %s" % json.dumps(failed[0]))


def parse_params(text):
    out = {}
    for item in text.split(","):
        key, value = item.split("=", 1)
        out[key] = int(value) if value.isdigit() else value
    return out


def config_label(params):
    if list(params) == ["config"]:
        return params["config"]
    return " ".join("%s=%s" % kv for kv in params.items())


def sim_of(kernel, params):
    for r in sim_rows:
        if r.get("kernel") == kernel and all(r.get(k) == v for k, v in params.items()):
            return r
    return None


# --- The designs -------------------------------------------------------------------------------
designs = []
for line in read(tmp + "/designs.tsv").splitlines():
    did, kernel, params, top, harness, target, fit = line.split("\t")
    params = parse_params(params)
    d = tmp + "/designs/" + did
    target = None if target == "-" else int(target)
    sim = sim_of(kernel, params)
    designs.append({
        "id": did,
        "kernel": kernel,
        "configuration": config_label(params),
        "parameters": params,
        "top": top,
        "fmax_target_mhz": target,
        "must_fit": fit == "yes",
        "simulation": sim,
        "ice40": ice40_resources(d),
        "place_and_route": place_and_route(d, target or 100),
        "generic": generic_resources(d),
    })


def fmt(x, digits=3):
    if x is None:
        return "n/a"
    if isinstance(x, float):
        return "%.*f" % (digits, x)
    return str(x)


def speed(x):
    return "%.2f M" % (x / 1e6)


def fit_text(d):
    p, r = d["place_and_route"], d["ice40"]
    if p["placed"]:
        io = p["utilisation"].get("SB_IO", {})
        return "fits the HX8K: %d LUT4 (%.1f%%), %d of %d BRAM, %s of %s I/O" % (
            r["lut4"], r["lut4_utilisation_percent"], r["bram"], PART["bram"], io.get("used", "?"),
            io.get("available", "?"))
    if p["over_capacity"]:
        names = {"SB_IO": "I/O", "ICESTORM_LC": "logic cells", "ICESTORM_RAM": "BRAM"}
        over = ", ".join("%d of %d %s (%d over)" % (p["utilisation"][k]["used"],
                                                   p["utilisation"][k]["available"], names.get(k, k), n)
                         for k, n in sorted(p["over_capacity"].items()))
        return "does not fit the HX8K: %s" % over
    return "not placed: %s" % (p["error"] or "see nextpnr's log")


# --- Targets -----------------------------------------------------------------------------------
targets = []
for d in designs:
    name = "%s %s" % (d["kernel"], d["configuration"])
    p = d["place_and_route"]
    if d["fmax_target_mhz"] is not None:
        t = d["fmax_target_mhz"]
        f = p["fmax_mhz"]
        met = f is not None and f >= t
        if f is None:
            how = "not placed"
        elif met:
            how = "margin %+.1f MHz (%+.0f%%)" % (f - t, 100.0 * (f - t) / t)
        else:
            how = "short by %.1f MHz (%.0f%%)" % (t - f, 100.0 * (t - f) / t)
        if p["fmax_by_seed"]:
            b = p["fmax_by_seed"]
            how += "; seeds %d..%d: %.1f..%.1f MHz" % (b["seeds"][0], b["seeds"][-1], b["min"],
                                                      b["max"])
        targets.append({"kernel": d["kernel"], "configuration": d["configuration"],
                        "target": "Fmax >= %d MHz on the HX8K" % t,
                        "measured": "%s MHz" % fmt(f, 1), "met": met, "detail": how})
    if d["must_fit"]:
        targets.append({"kernel": d["kernel"], "configuration": d["configuration"],
                        "target": "fits the HX8K (ct256), placed and routed",
                        "measured": fit_text(d), "met": p["placed"],
                        "detail": "" if p["placed"] else fit_text(d).split(": ", 1)[-1]})
fusion_sims = [r for r in sim_rows if r["kernel"] == "index_fusion"]
if fusion_sims:
    worst = max(r["bp_off"]["steady_ii"] for r in fusion_sims)
    targets.append({"kernel": "index_fusion", "configuration": "all %d simulated" % len(fusion_sims),
                    "target": "one beat per cycle (II = 1), no back-pressure",
                    "measured": "steady-state cycles per beat <= %.5f" % worst,
                    "met": worst <= 1.0 + 1e-9,
                    "detail": "" if worst <= 1.0 + 1e-9 else "II %.5f" % worst})
for r in sim_rows:
    if r["kernel"] != "sectoral_ism":
        continue
    cells, setup = r["cells_per_reading"], r["setup_cycles"]
    cpc = r["cycles_per_cell"]["no_backpressure"]
    targets.append({
        "kernel": "sectoral_ism", "configuration": r["config"],
        "target": "one cell per cycle after the per-reading set-up",
        "measured": "%.3f cycles per cell back to back; set-up %d..%d cycles (mean %.0f) per "
                    "%d-cell reading" % (cpc, setup["min"], setup["max"], setup["mean"], cells),
        "met": None,
        "detail": "not a pass/fail figure of the report: back to back, a reading costs its set-up "
                  "when that is longer than its %d output cycles (set-up and output overlap in "
                  "two banks; SectoralIsmRtl.*FullThroughput checks the bound)" % cells})

# --- Summary rows for `intgrid demo` -----------------------------------------------------------
summary = []
for d in designs:
    if d["kernel"] not in SIM:
        continue
    s = SIM[d["kernel"]](d["simulation"]) if d["simulation"] else {}
    r, p, t = d["ice40"], d["place_and_route"], d["fmax_target_mhz"]
    summary.append({
        "kernel": d["kernel"],
        "configuration": d["configuration"],
        "cycles_per_cell": s.get("cycles_per_cell"),
        "cycles_per_cell_backpressure": s.get("cycles_per_cell_backpressure"),
        "latency_cycles": s.get("latency_cycles"),
        "latency_cycles_backpressure": s.get("latency_cycles_backpressure"),
        "lut4": r["lut4"], "carry": r["carry"], "dff": r["dff"], "bram": r["bram"],
        "fmax_mhz": p["fmax_mhz"],
        "target_mhz": t,
        "target_met": None if t is None else (p["fmax_mhz"] is not None and p["fmax_mhz"] >= t),
        "note": ("%.1f%% of the HX8K's LUT4" % r["lut4_utilisation_percent"]) if p["placed"]
                else fit_text(d),
    })

report = {
    "report": "intgrid hardware kernels (docs/hardware.md, What each kernel reports)",
    "generated_by": "bash scripts/hw_reports.sh",
    "date": date,
    "generated_at": stamp,
    "run_seconds": int(run_seconds),
    "machine": {"cpu": cpu, "cores": int(cores)},
    "tools": {"yosys": v_yosys, "nextpnr_ice40": v_nextpnr, "verilator": v_verilator},
    "part": dict(PART, nextpnr=NEXTPNR, seed=int(seed)),
    "targets": targets,
    "summary": summary,
    "simulation": sim_rows,
    "designs": designs,
}

# --- Markdown ----------------------------------------------------------------------------------
md = []
w = md.append
w("# Hardware report")
w("")
w("Generated by `bash scripts/hw_reports.sh` on %s (%s s) on an `%s`, %s cores; %s, %s, %s. "
  "Every figure below is measured by that run: cycles and latency in Verilator simulation "
  "(the testbenches' report modes, every output checked against golden), resources by Yosys, "
  "Fmax by nextpnr-ice40. Only the targets (and the reference point's figure in docs/hardware.md) "
  "are quoted. Apart from the date, the run time and the simulation speeds, a rerun gives the "
  "same file." % (date, run_seconds, cpu, cores, v_yosys, v_nextpnr, v_verilator))
w("")
w("Part: Lattice %s %s, %s package (%d LUT4, %d SB_RAM40_4K). `%s`, on the kernel with a "
  "register on every port, so that Fmax covers every path of the kernel." % (
      PART["family"], PART["device"], PART["package"], PART["lut4"], PART["bram"], NEXTPNR))
w("")
w("## Targets")
w("")
w("| kernel | configuration | target | measured | met |")
w("|---|---|---|---|---|")
for t in targets:
    verdict = "—" if t["met"] is None else ("yes" if t["met"] else "**no**")
    if t["detail"]:
        verdict += ": " + t["detail"]
    w("| %s | %s | %s | %s | %s |" % (t["kernel"], t["configuration"], t["target"], t["measured"],
                                       verdict))
w("")
w("## Summary")
w("")
w("| kernel | configuration | cycles/cell | latency (cycles) | cycles/cell, back-pressure | "
  "latency, back-pressure | LUT4 | carry | DFF | BRAM | Fmax (MHz) | target (MHz) |")
w("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for s in summary:
    w("| %s | %s | %s | %s | %s | %s | %d | %d | %d | %d | %s | %s |" % (
        s["kernel"], s["configuration"], fmt(s["cycles_per_cell"]), fmt(s["latency_cycles"], 2),
        fmt(s["cycles_per_cell_backpressure"]), fmt(s["latency_cycles_backpressure"], 2),
        s["lut4"], s["carry"], s["dff"], s["bram"], fmt(s["fmax_mhz"], 1),
        fmt(s["target_mhz"])))
w("")
w("Back-pressure: y_ready high in 50% of cycles (random). Index fusion: inputs always valid, "
  "latency from a beat's acceptance to its output, mean. Sectoral ISM: readings back to back, "
  "latency from a reading's acceptance to its first cell, mean (queueing behind earlier "
  "readings included).")


def ice40_table(ds):
    w("| configuration | LUT4 | carry | DFF | BRAM | LUT4 of the HX8K | logic cells placed | I/O | "
      "Fmax (MHz) | Fmax, seed sweep (MHz) | nextpnr --freq | fit |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---|")
    for d in ds:
        r, p = d["ice40"], d["place_and_route"]
        lc = p["utilisation"].get("ICESTORM_LC", {})
        io = p["utilisation"].get("SB_IO", {})
        b = p["fmax_by_seed"]
        others = "n/a" if not b else "%.1f..%.1f (seeds %d..%d)" % (b["min"], b["max"],
                                                                  b["seeds"][0], b["seeds"][-1])
        w("| %s | %d | %d | %d | %d | %.1f%% | %s | %s | %s | %s | %d | %s |" % (
            d["configuration"], r["lut4"], r["carry"], r["dff"], r["bram"],
            r["lut4_utilisation_percent"], "%s/%s" % (lc.get("used", "?"), lc.get("available", "?")),
            "%s/%s" % (io.get("used", "?"), io.get("available", "?")), fmt(p["fmax_mhz"], 1),
            others, p["constraint_mhz"], "yes" if p["placed"] else "**no**: " + fit_text(d).split(": ", 1)[-1]))
    w("")
    w("LUT4, carry, DFF (every SB_DFF* variant) and BRAM (SB_RAM40_4K): `synth_ice40 -top <top>` "
      "of the kernel itself. Logic cells, I/O and Fmax: nextpnr on the registered-port harness "
      "(its extra flip-flops share logic cells with the LUTs).")
    w("")


def generic_table(ds):
    w("| configuration | cells | flip-flops | gates | memories before mapping (bits) | cell types |")
    w("|---|---:|---:|---:|---|---|")
    for d in ds:
        g = d["generic"]
        types = ", ".join("%s %d" % (t.strip("$_").rstrip("_"), n)
                          for t, n in sorted(g["by_type"].items(), key=lambda kv: (-kv[1], kv[0])))
        w("| %s | %d | %d | %d | %d (%d) | %s |" % (
            d["configuration"], g["cells"], g["flip_flops"], g["gates"],
            g["memories_before_mapping"], g["memory_bits_before_mapping"], types))
    w("")
    w("`synth -flatten -top <top>` (Yosys's generic gate library; memories are mapped to "
      "flip-flops and multiplexers, as plain `synth` does, and counted before that in the "
      "memories column).")
    w("")


for kernel in ["index_fusion", "sectoral_ism", "reference"]:
    ds = [d for d in designs if d["kernel"] == kernel]
    if not ds:
        continue
    w("")
    w("## " + KERNEL_TITLES.get(kernel, kernel))
    w("")
    sims = [r for r in sim_rows if r["kernel"] == kernel]
    if kernel == "index_fusion" and sims:
        w("### Simulation (Verilator, `index_fusion_rtl_test --report`)")
        w("")
        w("%d beats per run, inputs always valid; back-pressure off: y_ready always high; on: "
          "y_ready high in 50%% of cycles." % sims[0]["beats"])
        w("")
        w("| B | LANES | cycles/beat | cycles/cell | steady II | latency min/mean/max | "
          "cycles/cell, back-pressure | latency min/mean/max, back-pressure | "
          "sim cells/s | sim cycles/s |")
        w("|---:|---:|---:|---:|---:|---|---:|---|---:|---:|")
        for r in sims:
            off, on = r["bp_off"], r["bp_on"]
            lat = lambda x: "%d / %.2f / %d" % (x["min"], x["mean"], x["max"])
            w("| %d | %d | %.5f | %.5f | %.5f | %s | %.5f | %s | %s | %s |" % (
                r["B"], r["LANES"], off["cycles_per_beat"], off["cycles_per_cell"],
                off["steady_ii"], lat(off["latency_cycles"]), on["cycles_per_cell"],
                lat(on["latency_cycles"]), speed(off["sim_cells_per_s"]),
                speed(off["sim_cycles_per_s"])))
        w("")
    if kernel == "sectoral_ism" and sims:
        w("### Simulation (Verilator, `sectoral_ism_report`)")
        w("")
        w("%d readings uniform over the grid's reach per run. Set-up and latency of isolated "
          "readings (no back-pressure); cycles per cell and streaming latency with readings back "
          "to back, y_ready always high or high in 50%% of cycles." % sims[0]["readings"])
        w("")
        w("| configuration | cells/reading | set-up min/mean/max | latency min/mean/max | "
          "cycles/cell | cycles/cell, back-pressure | streaming latency | "
          "streaming latency, back-pressure | sim cells/s | sim cycles/s |")
        w("|---|---:|---|---|---:|---:|---:|---:|---:|---:|")
        for r in sims:
            st, la = r["setup_cycles"], r["latency_cycles"]
            w("| %s | %d | %d / %.1f / %d | %d / %.1f / %d | %.3f | %.3f | %.1f | %.1f | %s | %s |" % (
                r["config"], r["cells_per_reading"], st["min"], st["mean"], st["max"], la["min"],
                la["mean"], la["max"], r["cycles_per_cell"]["no_backpressure"],
                r["cycles_per_cell"]["backpressure_50"],
                r["streaming_latency_mean"]["no_backpressure"],
                r["streaming_latency_mean"]["backpressure_50"],
                speed(r["verilator_cells_per_second"]), speed(r["verilator_cycles_per_second"])))
        w("")
    if kernel == "reference":
        d = ds[0]
        w("docs/hardware.md quotes about %d MHz in %d LUT4 for a plain registered 8-bit saturating "
          "adder on the HX8K. Measured here (rtl/saturating_add.sv, B = 8, between an input and "
          "an output register, written by the script): %s MHz in %d LUT4 (+ %d SB_CARRY)." % (
              QUOTED_REFERENCE["fmax_mhz"], QUOTED_REFERENCE["lut4"],
              fmt(d["place_and_route"]["fmax_mhz"], 1), d["ice40"]["lut4"], d["ice40"]["carry"]))
        w("")
    w("### iCE40 HX8K (Yosys synth_ice40, nextpnr-ice40)")
    w("")
    ice40_table(ds)
    w("### Technology-neutral (Yosys generic synth)")
    w("")
    generic_table(ds)

w("## Method")
w("")
w("- Simulation: the Verilator testbenches' report programs in build/full (INTGRID_TB_SEED=%s), "
  "each output checked against golden; the script refuses to report a run that failed its "
  "checks." % seed)
w("- Yosys: every file of rtl/ read with `read_verilog -sv`, the configuration set with "
  "`chparam` (index fusion, the adder) or the committed rtl/config/<config>/sectoral_ism_<config>.ys "
  "(written with the ROM files by `intgrid hw-config`; the text is golden's ism_table_files, "
  "golden/kernel/src/table_export.cpp); then `synth_ice40 -top <top>` and `stat`, and separately `synth -flatten -top <top>` "
  "and `stat`.")
w("- nextpnr: `%s`; Fmax is the last \"Max frequency for clock\" line of its log. The design is "
  "the kernel with every input and output registered (harness written by the script into its "
  "temporary folder), so that paths from and to the package pins do not count as kernel "
  "paths; index fusion's data buses are filled through shift registers from one pin each and its "
  "output folded to one pin through registered parities, so that any lane count fits the "
  "package's pins, as it would inside a design. Fmax moves with the placement seed, so each placed design is also placed with a few "
  "more seeds (the range is shown); the targets are judged on seed 1." % NEXTPNR)
w("")

with open(json_path, "w", encoding="utf-8") as f:
    json.dump(report, f, indent=2)
    f.write("\n")
with open(md_path, "w", encoding="utf-8") as f:
    f.write("\n".join(md))
PY
end_s=$(date +%s)
python3 "$tmp/report.py" "$tmp" "$md_tmp" "$json_tmp" "$cpu" "$cores" "$v_yosys" "$v_nextpnr" \
  "$v_verilator" "$seed" "$(date -u +%Y-%m-%d)" "$(date -u +%Y-%m-%dT%H:%M:%SZ)" \
  "$((end_s - start_s))" || die "writing the report failed"
mv -f "$json_tmp" "$docs/hardware_report.json"
mv -f "$md_tmp" "$docs/hardware_report.md"
say "wrote docs/hardware_report.md and docs/hardware_report.json in $((end_s - start_s)) s"

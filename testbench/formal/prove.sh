#!/usr/bin/env bash
# One bounded (or k-induction) proof of a formal harness with Yosys and yosys-smtbmc.
#   prove.sh --dir DIR --top TOP --depth K [--induction] [--counterexample] [--solver S]
#            [--prepare "YOSYS COMMAND"]... [--params "-set P V..."]
#            --rtl FILE... --harness FILE...
# Reads the RTL, runs the --prepare commands on it (chparam, expose), reads the harness, sets
# its parameters (--params, given to chparam of TOP: the same values as the RTL's), writes
# DIR/model.smt2 and proves every assert of TOP for K steps from reset (with --induction also
# the induction step, which makes the proof unbounded). Logs go to DIR/yosys.log and
# DIR/smtbmc.log, a counterexample to DIR/trace.vcd (the induction step's to DIR/induction.vcd).
# Exit 0 when the proof passes; with --counterexample, exit 0 only when the solver finds a
# reachable assertion failure (a negative test: the harness must catch an injected fault), never
# when Yosys itself fails.
set -euo pipefail
dir="" top="" depth="" induction=0 expect_cex=0 solver=z3 prepare="" params=""
defines=() rtl=() harness=()
list=""
while (($# > 0)); do
  case "$1" in
    --dir) dir="$2"; shift 2 ;;
    --top) top="$2"; shift 2 ;;
    --depth) depth="$2"; shift 2 ;;
    --solver) solver="$2"; shift 2 ;;
    --prepare) prepare+="$2; "; shift 2 ;;
    --params) params="$2"; shift 2 ;;
    --induction) induction=1; shift ;;
    --counterexample) expect_cex=1; shift ;;
    --rtl) list=rtl; shift ;;
    --harness) list=harness; shift ;;
    -*) echo "prove: unknown option $1" >&2; exit 2 ;;
    *)
      case "$list" in
        rtl) rtl+=("$1") ;;
        harness) harness+=("$1") ;;
        *) echo "prove: $1 before --rtl or --harness" >&2; exit 2 ;;
      esac
      shift ;;
  esac
done
if [ -z "$dir" ] || [ -z "$top" ] || [ -z "$depth" ] || [ ${#harness[@]} -eq 0 ]; then
  echo "prove: --dir, --top, --depth and --harness are required" >&2
  exit 2
fi
mkdir -p "$dir"
rm -f "$dir/model.smt2" "$dir/trace.vcd" "$dir/induction.vcd" "$dir/smtbmc.log"

# FORMAL_INDUCTION enables the asserts that tie the RTL's registers to the reference, which only
# the induction step needs: a negative test must be caught by the harness's port properties.
((induction && !expect_cex)) && defines+=(-DFORMAL_INDUCTION)
read_opts="-sv -formal ${defines[*]}"
# The RTL is read as for synthesis (SYNTHESIS defined, as Yosys' plain read_verilog does): its
# simulation-only checkers are for Verilator, and their SVA is beyond Yosys' own parser.
script="read_verilog $read_opts -DSYNTHESIS ${rtl[*]}; ${prepare}read_verilog $read_opts ${harness[*]}"
[ -z "$params" ] || script+="; chparam $params $top"
script+="; prep -flatten -top $top; memory_map; opt -fast; dffunmap; write_smt2 -wires $dir/model.smt2"
if ! yosys -q -l "$dir/yosys.log" -p "$script" >/dev/null; then
  echo "prove: yosys failed on $top (see $dir/yosys.log)" >&2
  exit 1
fi

smt_opts=(-s "$solver" --presat --noprogress -t "$depth")
start=$SECONDS
set +e
# The base case: every assert on every trace of $depth steps from the initial state.
yosys-smtbmc "${smt_opts[@]}" --dump-vcd "$dir/trace.vcd" "$dir/model.smt2" >"$dir/smtbmc.log" 2>&1
status=$?
# The induction step: $depth steps that satisfy every assert are followed by one that does too.
if ((status == 0 && induction && !expect_cex)); then
  yosys-smtbmc "${smt_opts[@]}" -i --dump-vcd "$dir/induction.vcd" "$dir/model.smt2" >>"$dir/smtbmc.log" 2>&1
  status=$?
fi
set -e
mode="BMC of depth $depth"
((induction && !expect_cex)) && mode="k-induction of depth $depth (BMC base case and induction step)"
if ((expect_cex)); then
  if ((status != 0)) && grep -q "BMC failed" "$dir/smtbmc.log" && grep -q "Assert failed" "$dir/smtbmc.log"; then
    echo "prove: $top: counterexample found as required ($mode, $((SECONDS - start)) s):"
    grep "Assert failed" "$dir/smtbmc.log" | head -3
    echo "prove: trace in $dir/trace.vcd"
    exit 0
  fi
  echo "prove: $top: no counterexample within $mode: the harness missed the injected fault" >&2
  tail -5 "$dir/smtbmc.log" >&2
  exit 1
fi
if ((status == 0)) && ! grep -q "Status: FAILED" "$dir/smtbmc.log"; then
  echo "prove: $top: PASSED, $mode, $((SECONDS - start)) s"
  exit 0
fi
echo "prove: $top: FAILED ($mode); counterexample in $dir/trace.vcd (base case) or $dir/induction.vcd (induction step, from an unreachable state if the base case passed)" >&2
grep -E "Assert failed|failed|Status" "$dir/smtbmc.log" >&2 || tail -5 "$dir/smtbmc.log" >&2
exit 1

#!/bin/sh
# rtl/synth.sh CONFIG [ROOT]: Yosys synth_ice40 of the sectoral ISM in configuration CONFIG,
# the folder ROOT/config/CONFIG (ROOT defaults to this script's folder, rtl/). Yosys runs in
# ROOT, where the configuration's parameter file names its ROMs (config/CONFIG/...); the
# sources are this folder's sectoral_ism.f. Prints the cell counts; exits non-zero if Yosys
# fails, e.g. on a configuration the kernel's parameter checks refuse.
#   rtl/synth.sh cone16
#   YOSYS_EXTRA="write_json out.json" rtl/synth.sh cone12
set -eu
here=$(cd "$(dirname "$0")" && pwd)
[ $# -ge 1 ] && [ $# -le 2 ] || { echo "usage: $0 CONFIG [ROOT]" >&2; exit 2; }
config=$1
root=${2:-$here}
script="config/$config/sectoral_ism_$config.ys"
[ -f "$root/$script" ] || { echo "$0: no $root/$script" >&2; exit 2; }
sources=$(sed -e 's://.*$::' -e '/^[[:space:]]*$/d' -e "s:^:$here/:" "$here/sectoral_ism.f" | tr '\n' ' ')
cd "$root"
exec "${YOSYS:-yosys}" -q -p "read_verilog -sv $sources; script $script; synth_ice40 -top sectoral_ism; check -assert; tee -o /dev/stdout stat; ${YOSYS_EXTRA:-}"

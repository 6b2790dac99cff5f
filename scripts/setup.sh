#!/usr/bin/env bash
# Installs the Debian 12 packages intgrid needs, skipping those already present.
#   setup.sh [host]  the host library, the command and their tests (the demo needs only these),
#                    and ccache, which scripts/build.sh compiles through
#   setup.sh full    also the benchmarks, the hardware toolchain (SystemC, Verilator, Yosys, z3,
#                    nextpnr-ice40), the embedded one (arm-none-eabi, QEMU), Python (pybind11)
#                    and clang with libFuzzer (the preset fuzz)
set -euo pipefail
group="${1:-host}"
packages=(
  build-essential cmake pkg-config ccache
  libgtest-dev libgmock-dev
  libcli11-dev nlohmann-json3-dev libyaml-cpp-dev libpng-dev libeigen3-dev
  gnuplot-nox strace
)
case "$group" in
  host) ;;
  full)
    packages+=(
      libbenchmark-dev
      libsystemc-dev verilator yosys nextpnr-ice40 z3
      gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-newlib qemu-system-arm
      python3-dev pybind11-dev python3-numpy python3-pytest
      clang libclang-rt-14-dev
    )
    ;;
  *) echo "setup: unknown group '$group' (host or full)" >&2; exit 2 ;;
esac
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages of '$group' present"
  exit 0
fi
echo "setup: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"

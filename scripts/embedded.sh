#!/usr/bin/env bash
# The embedded measurement: set up, build the host check and the Cortex-M3 image, run the image
# under QEMU, check its integer results against the host's bit for bit, and write the table of
# instructions per operation into docs/embedded.md and the README.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh default embedded_check
cmake -DREPORT="$PWD/docs/embedded.md" -DREADME="$PWD/README.md" -P build/default/embedded_check.cmake

#!/usr/bin/env bash
# The embedded measurement: set up, build the host check and the Cortex-M3 image, run the image
# under QEMU, check its integer results against the host's bit for bit, and write the table of
# instructions per operation into docs/embedded.md and between the embedded-table markers of
# docs/results.md. The full preset's build (build/full): the default one has no embedded part.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh full embedded_check
cmake -DREPORT="$PWD/docs/embedded.md" -DRESULTS="$PWD/docs/results.md" -P build/full/embedded_check.cmake

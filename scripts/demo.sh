#!/usr/bin/env bash
# The main job: set up (host packages only), build, and run the full host pipeline on the bundled
# real log.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh default intgrid  # the demo needs only the command
./build/default/bin/intgrid demo "$@"

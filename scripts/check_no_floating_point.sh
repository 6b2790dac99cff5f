#!/usr/bin/env bash
# Fails if any of the object files given uses floating point: an x87 or SSE/AVX register or
# instruction in its code, or a call into libm or the soft-float helpers.
set -euo pipefail
status=0
for object in "$@"; do
  instructions=$(objdump -d --no-show-raw-insn "$object" |
    grep -E '%[xyz]mm[0-9]|%st(\(|\b)|\sf(ld|st|add|sub|mul|div|ild|istp)[a-z]*\s|\scvt' || true)
  calls=$(nm -u "$object" |
    grep -E '\s(sqrtf?|expf?|logf?|log1pf?|expm1f?|powf?|sinf?|cosf?|llround|lround|round|floor|ceil|__(add|sub|mul|div)[sdt]f3|__float[a-z]+|__fix[a-z]+)$' || true)
  if [ -n "$instructions$calls" ]; then
    echo "$object uses floating point:"
    echo "$instructions" | head -5
    echo "$calls" | head -5
    status=1
  else
    echo "$object: no floating point"
  fi
done
exit $status

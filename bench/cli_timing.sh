#!/usr/bin/env bash
# End-to-end timing of `foglab allan` on a 2e7-sample MAT file (lab layout,
# 100 Hz, 55.6 h): reading through matio, OADEV on the octave grid with noise
# identification and confidence intervals, JSON output. Prints wall time and
# peak memory (GNU time) against the size of the input array.
# Usage: bash bench/cli_timing.sh [BUILD_DIR] [SAMPLES]
set -euo pipefail
build=${1:-build}
samples=${2:-20000000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/bench/bench_make_mat" "$work/big.mat" "$samples" 100
ls -l "$work/big.mat" | awk '{printf "MAT file: %.1f MB\n", $5/1e6}'
for run in 1 2 3; do
  /usr/bin/time -f "run $run: %e s wall, %M kB peak RSS" \
    "$build/apps/foglab/foglab" allan "$work/big.mat" --channel Y1 --json "$work/out.json" >/dev/null
done
python3 - "$samples" "$work/out.json" <<'PY'
import json, sys
n = int(sys.argv[1]); out = json.load(open(sys.argv[2]))
print(f"input array: {n * 8 / 1e6:.1f} MB; taus: {len(out['tau_s'])}; "
      f"OADEV({out['tau_s'][0]} s) = {out['dev'][0]:.4g} deg/h")
PY

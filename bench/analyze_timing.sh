#!/usr/bin/env bash
# End-to-end timing of `foglab analyze` on a 1e7-sample MAT file with a
# temperature (lab layout f, t, Y1, T1; 100 Hz, 27.8 h, 10 degC ramp) made
# by `foglab generate`: reading Y1 and T1 through matio, the temperature
# polynomial (automatic degree: a quick noise model of the cubic's residual
# chooses it; here the cubic stays, so the cubic's OADEV with intervals and
# its full noise fit, run alongside the quick one, are the final ones), the
# Welch PSD of the residual, JSON output. Prints wall time and peak memory
# (GNU time) against the size of the input arrays, and the load average
# before the runs (the VM has 2 vCPUs: another job halves the speed).
# Usage: bash bench/analyze_timing.sh [BUILD_DIR] [SAMPLES]
set -euo pipefail
build=${1:-build}
samples=${2:-10000000}
foglab="$build/apps/foglab/foglab"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
hours=$(python3 -c "print(repr($samples / 100 / 3600))")
"$foglab" generate --N 0.5 --B 0.05 --K 0.005 --fs 100 --hours "$hours" \
  --temperature ramp:10 --temp-coef 2,0.05 --seed 2021 --out "$work/big.mat" >/dev/null
ls -l "$work/big.mat" | awk '{printf "MAT file: %.1f MB\n", $5/1e6}'
echo "load average before the runs: $(cut -d' ' -f1-3 /proc/loadavg)"
for run in 1 2 3; do
  /usr/bin/time -f "run $run: %e s wall, %M kB peak RSS" \
    "$foglab" analyze "$work/big.mat" --json "$work/out.json" >/dev/null 2>"$work/err" ||
    { cat "$work/err"; exit 1; }
  grep '^run ' "$work/err"
done
python3 - "$samples" "$work/out.json" <<'PY'
import json, sys
n = int(sys.argv[1]); out = json.load(open(sys.argv[2]))
s, m = out["systematic"], out["noise_model"]
print(f"input arrays: Y1 + T1 = {2 * n * 8 / 1e6:.1f} MB; samples: {out['input']['samples']}; "
      f"taus: {len(out['allan']['tau_s'])}; temperature degree {s['degree']}; "
      f"terms {out['fit']['terms']}; N = {m['N']['value']:.4g} deg/h/sqrt(Hz); "
      f"class {out['accuracy_class']}")
PY

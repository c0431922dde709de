#!/usr/bin/env bash
# The whole-IMU target of issue 17, end to end: a generated 8 h, 400 Hz,
# 6-axis ROS bag (1.15e7 messages, about 4.3 GB), read and analysed by one
# `foglab analyze` (six axes in parallel), timed with its peak memory; then
# every axis's N, bias instability and K against the truth, and the Kalibr
# file's four values.
#
#   bash bench/imu_timing.sh BUILD_DIR [WORK_DIR] [HOURS] [RUNS]
# WORK_DIR keeps the bag between runs (default /tmp/foglab-imu-bench); HOURS
# defaults to 8, RUNS to 3. Writing the bag takes about 3 minutes (the ROS
# library writes about 70,000 messages a second).
set -euo pipefail
build=${1:?usage: imu_timing.sh BUILD_DIR [WORK_DIR] [HOURS] [RUNS]}
work=${2:-/tmp/foglab-imu-bench}
hours=${3:-8}
runs=${4:-3}
foglab="$build/apps/foglab/foglab"
mkdir -p "$work"
bag="$work/imu_${hours}h.bag"
truth="$work/imu_${hours}h_truth.json"

if [ ! -f "$bag" ] || [ ! -f "$truth" ]; then
  echo "writing $bag ($hours h at 400 Hz) ..."
  /usr/bin/time -f "generate: %e s wall, %M kB peak" \
    "$foglab" generate --imu --hours "$hours" --seed 2026 --stamp-jitter 0.0005 \
    --drop 3600:0.1 --out "$bag" --truth "$truth"
fi
ls -l "$bag"

for r in $(seq "$runs"); do
  # The bag's pages may or may not be cached; the first run reads the disk.
  /usr/bin/time -f "run $r: %e s wall, %U s user, %S s system, %M kB peak" \
    "$foglab" analyze "$bag" --json "$work/imu.json" --kalibr "$work/imu.yaml" > /dev/null 2> "$work/err.txt" || {
    cat "$work/err.txt"; exit 1; }
  grep "^run $r" "$work/err.txt" || tail -n 1 "$work/err.txt"
done

/usr/bin/python3 - "$work/imu.json" "$truth" "$work/imu.yaml" <<'EOF'
import json, re, sys
result, truth = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
yaml = open(sys.argv[3]).read()
t = result["input"]["timing"]
print(f"bag: {t['messages']} messages, jitter {t['jitter_rms_s']:.3g} s rms, "
      f"gaps {result['channels'][0]['input']['gaps']['count']} "
      f"({result['channels'][0]['input']['gaps']['missing_samples']} samples)")
print(f"{'axis':8} {'N/true':>8} {'N in 95%':>9} {'BI/true':>8} {'K/true':>8} {'K status':>12} {'K in 95%':>9}")
for c in result["channels"]:
    name = c["input"]["channel"]
    a = truth["axes"][name]
    nm = c["noise_model"]
    bi = c.get("bias_instability_deg_h", c.get("bias_instability_m_s2"))
    n, k = nm["N"], nm["K"]
    n_in = n["ci95"] is not None and n["ci95"][0] <= a["N"] <= n["ci95"][1]
    if k["status"] == "resolved":
        k_in = k["ci95"][0] <= a["K"] <= k["ci95"][1]
        k_ratio = k["value"] / a["K"]
    else:
        k_in = a["K"] <= (k["upper_95"] or 0)
        k_ratio = float("nan")
    print(f"{name:8} {n['value']/a['N']:8.4f} {str(n_in):>9} {bi/a['bias_instability']:8.3f} "
          f"{k_ratio:8.3f} {k['status']:>12} {str(k_in):>9}")
for key in ["gyroscope_noise_density", "gyroscope_random_walk",
            "accelerometer_noise_density", "accelerometer_random_walk"]:
    v = float(re.search(r"\n" + key + r": ([0-9.eE+-]+)", yaml).group(1))
    print(f"kalibr {key}: {v:.6g} (truth {truth['kalibr'][key]:.6g}, ratio {v/truth['kalibr'][key]:.4f})")
EOF

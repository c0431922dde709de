#!/usr/bin/env bash
# A fleet, end to end (issue 18): `foglab generate --fleet` (200 units of 1 h at 10 Hz by
# default, three planted outliers), then `foglab batch` on it, timed with its peak memory
# (RUNS times, each from an empty --out), a rerun that keeps every unit, and, when Dask's
# distributed is importable by /usr/bin/python3, foglab.dask.batch on a LocalCluster with
# one worker per core.
#
#   bash bench/fleet_timing.sh BUILD_DIR [WORK_DIR] [UNITS] [HOURS] [FS] [RUNS]
set -euo pipefail
build=${1:?usage: fleet_timing.sh BUILD_DIR [WORK_DIR] [UNITS] [HOURS] [FS] [RUNS]}
work=${2:-/tmp/foglab-fleet-bench}
units=${3:-200}
hours=${4:-1}
fs=${5:-10}
runs=${6:-3}
foglab="$build/apps/foglab/foglab"
fleet="$work/fleet_${units}x${hours}h_${fs}hz"
mkdir -p "$work"
if [ ! -f "$fleet/fleet_truth.json" ]; then
  /usr/bin/time -f "generate --fleet: %e s wall, %M kB peak" \
    "$foglab" generate --N 0.06 --B 0.02 --fs "$fs" --hours "$hours" --fleet "$units" \
    --outliers 3 --seed 7 --out "$fleet/unit.mat"
fi
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
for r in $(seq "$runs"); do
  rm -rf "$work/out"
  /usr/bin/time -f "batch run $r: %e s wall, %U s user, %M kB peak" \
    "$foglab" batch "$fleet" --no-plots --out "$work/out" > "$work/batch.out" 2> "$work/batch.err" \
    || { cat "$work/batch.err"; exit 1; }
  tail -n 1 "$work/batch.err"
done
/usr/bin/time -f "rerun, every unit kept: %e s wall" \
  "$foglab" batch "$fleet" --no-plots --out "$work/out" > /dev/null 2> "$work/rerun.err"
tail -n 1 "$work/rerun.err"
grep "stands out" "$work/batch.out" || true

if /usr/bin/python3 -c "import distributed" 2> /dev/null; then
  rm -rf "$work/dask"
  # A file, not standard input: Dask's worker processes import the main script again.
  script="$work/dask_batch.py"
  cat > "$script" << 'PY'
import os, sys, time
from distributed import Client, LocalCluster
import foglab.dask

if __name__ == "__main__":
    start = time.perf_counter()
    with LocalCluster(n_workers=os.cpu_count(), threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        ready = time.perf_counter()
        fleet = foglab.dask.batch(client, [sys.argv[1]], sys.argv[2], plots=False)
        done = time.perf_counter()
    print(f"dask LocalCluster ({os.cpu_count()} workers): start {ready - start:.2f} s, batch "
          f"{done - ready:.2f} s for {len(fleet['units'])} units")
PY
  PYTHONPATH="$build/python" /usr/bin/python3 "$script" "$fleet" "$work/dask"
fi

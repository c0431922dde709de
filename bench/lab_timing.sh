#!/usr/bin/env bash
# End-to-end timing of the two lab commands with no arguments:
#  * `foglab lab2` (the main job; issue 5: under 30 s): variant 1 generated
#    in memory (FOG1 10 Hz x 3 h and FOG2 20 Hz x 2 h, constant and ramp
#    runs: 4 records, 504,000 samples), four analyses, 16 gnuplot SVG plots,
#    the HTML page, Markdown, CSV, JSON, Kalibr files and two MAT files;
#  * `foglab lab1` (issue 6: under 10 s): Table 4 variant 1 (f_m = 500 kHz,
#    16 samples per modulation period), the open loop with three
#    modulations, the sweeps, the 30 % bisection, the closed-loop ramp, the
#    off-frequency run and 8 plots.
# Prints wall time and peak memory (GNU time) of three runs each and the load
# average before them (the VM has 2 vCPUs: another job halves the speed).
# Usage: bash bench/lab_timing.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
foglab="$(cd "$build" && pwd)/apps/foglab/foglab"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "load average before the runs: $(cut -d' ' -f1-3 /proc/loadavg)"
for lab in lab2 lab1; do
  for run in 1 2 3; do
    /usr/bin/time -f "$lab run $run: %e s wall, %M kB peak RSS" \
      "$foglab" "$lab" --out "$work/$lab" >/dev/null 2>"$work/err" ||
      { cat "$work/err"; exit 1; }
    grep " run " "$work/err"
  done
  echo "$lab: report.html $(du -k "$work/$lab/report.html" | cut -f1) kB," \
    "$(grep -o '<svg' "$work/$lab/report.html" | wc -l) SVG plots"
done

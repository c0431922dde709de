#!/usr/bin/env bash
# End-to-end timing of the main job, `foglab lab2` with no arguments
# (issue 5: under 30 s): variant 1 generated in memory (FOG1 10 Hz x 3 h and
# FOG2 20 Hz x 2 h, constant and ramp runs: 4 records, 504,000 samples), the
# four analyses, 16 gnuplot SVG plots, the HTML page, Markdown, CSV, JSON,
# Kalibr files and the two MAT files. Prints wall time and peak memory (GNU
# time) of three runs and the load average before them (the VM has 2
# vCPUs: another job halves the speed).
# Usage: bash bench/lab2_timing.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
foglab="$(cd "$build" && pwd)/apps/foglab/foglab"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "load average before the runs: $(cut -d' ' -f1-3 /proc/loadavg)"
for run in 1 2 3; do
  /usr/bin/time -f "run $run: %e s wall, %M kB peak RSS" \
    "$foglab" lab2 --out "$work/report" >/dev/null 2>"$work/err" ||
    { cat "$work/err"; exit 1; }
  grep '^run ' "$work/err"
done
du -sh "$work/report/report.html" | awk '{print "report.html: " $1}'
grep -c '<svg' "$work/report/report.html" | awk '{print "SVG plots in the page: " $1}'

#!/usr/bin/env bash
# Compares what two foglab binaries write, for a refactoring that must not
# change behaviour: the JSON of the twelve lab-2 variant files (FOG1_k and
# FOG2_k, k = 1..6, both runs each: 24 `analyze` runs), every run JSON and
# table of `foglab lab2 --variant k`, the answer key of `lab2-data`, and the
# JSON of the README's examples (allan, psd, generate --truth, coil, sweep).
# Identical files are counted; for the others every differing value is
# listed (bench/json_diff.py), with its relative change.
#
# Usage: bash bench/json_compare.sh OLD_FOGLAB NEW_FOGLAB [WORK_DIR]
set -euo pipefail
old=$(realpath "$1")
new=$(realpath "$2")
work=${3:-$(mktemp -d)}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"

run_all() {  # FOGLAB OUT_DIR: runs in WORK_DIR/run, with relative paths so
  local foglab=$1 out=.  # that the paths written into the outputs agree
  rm -rf "$work/run" "$2"
  mkdir -p "$work/run/data"
  cd "$work/run"
  "$foglab" lab2-data --out "$out/data" --seed 2021 >/dev/null
  for g in 1 2; do
    for k in 1 2 3 4 5 6; do
      for run in 1 2; do
        "$foglab" analyze "$out/data/FOG${g}_$k.mat" --channel "Y$run" \
          --json "$out/analyze_FOG${g}_${k}_Y$run.json" >/dev/null
      done
    done
  done
  for k in 1 2 3 4 5 6; do
    "$foglab" lab2 --variant "$k" --out "$out/lab2_v$k" >/dev/null 2>&1
  done
  "$foglab" allan "$out/data/FOG1_1.mat" --channel Y1 --json "$out/allan_oadev.json" >/dev/null
  "$foglab" allan "$out/data/FOG2_2.mat" --channel Y2 --kind mdev --taus decade \
    --json "$out/allan_mdev.json" >/dev/null
  "$foglab" allan "$here/../tests/data/stable32-phasedat/PHASE.DAT" --input phase \
    --fs 1 --kind totdev --min-clusters 1 --json "$out/allan_totdev.json" >/dev/null
  "$foglab" psd "$out/data/FOG1_1.mat" --segment 65536 --json "$out/psd.json" >/dev/null
  "$foglab" generate --preset kvh-dsp-3000 --fs 100 --hours 0.2 --out "$out/gen.csv" \
    --truth "$out/gen_truth.json" >/dev/null
  "$foglab" analyze "$out/gen.csv" --channel rate --json "$out/analyze_gen.json" >/dev/null
  "$foglab" coil --variant 6 --json "$out/coil.json" >/dev/null
  "$foglab" sweep open-loop --variant 1 --modulation sine --json "$out/sweep.json" >/dev/null
  rm -f "$out"/data/*.mat "$out"/gen.csv "$out"/lab2_v*/*.mat
  # The HTML reports embed plots drawn in parallel: not compared.
  rm -f "$out"/lab2_v*/report.html
  cd - >/dev/null
  mv "$work/run" "$2"
}

run_all "$old" "$work/old"
run_all "$new" "$work/new"
python3 "$here/json_diff.py" "$work/old" "$work/new"

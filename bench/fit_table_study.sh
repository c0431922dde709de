#!/usr/bin/env bash
# `foglab fit` on the Allan tables of generated records (issue 19): ten 4 h
# records at 100 Hz with N 0.1, B 0.05, K 0.01, each table fitted whole (its
# edf column), with its counts only, and with tau and the deviation only.
# Prints each fit's N, B, K, their errors and whether the truth lies inside
# the 95 % interval (docs/validation.md, "foglab fit").
#   bash bench/fit_table_study.sh [build dir]
set -euo pipefail
foglab="${1:-build}/apps/foglab/foglab"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for seed in 1 2 3 4 5 6 7 8 9 10; do
  "$foglab" generate --N 0.1 --B 0.05 --K 0.01 --fs 100 --hours 4 --seed "$seed" \
    --out "$work/run.f32" > /dev/null
  "$foglab" allan "$work/run.f32" --fs 100 --csv "$work/whole.csv" > /dev/null
  cut -d, -f1-4 "$work/whole.csv" > "$work/counts.csv"
  cut -d, -f1,4 "$work/whole.csv" > "$work/bare.csv"
  for table in whole counts bare; do
    "$foglab" fit "$work/$table.csv" --json - | python3 -c "
import json, sys
j = json.load(sys.stdin)
def show(name, truth):
    p = j['noise_model'][name]
    ci = p['ci95']
    inside = ci is not None and ci[0] <= truth <= (ci[1] if ci[1] is not None else float('inf'))
    return f'{name} {p[\"value\"]:.4g} ({100 * (p[\"value\"] / truth - 1):+.1f} %, in 95 %: {inside})'
print('seed $seed $table', j['edf_source'], show('N', 0.1), show('B', 0.05), show('K', 0.01))"
  done
done

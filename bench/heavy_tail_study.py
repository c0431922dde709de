#!/usr/bin/env python3
"""Heavy-tailed white noise, which foglab's generator does not make:
`analyze` against the truth.

    python3 bench/heavy_tail_study.py BUILD/apps/foglab/foglab [--seeds 10]

Some sensors' noise is not Gaussian (bursts, popcorn noise in the
electronics). Each record is `generate`'s flicker and random walk (N 0,
2 h at 100 Hz, raw f64) plus white noise drawn here from Student's t with
DOF degrees of freedom, scaled to the grade's N (unit variance kept: the
PSD level, and so N, is that of the whole variance). Per (grade, DOF) it
prints N's worst error and how often its 95 % interval holds the truth,
B's and K's median errors, the records flagged heavy-tailed, and the
spikes and bias steps found (there are none). Needs numpy. Results go to
docs/validation.md by hand, with the date.
"""
import argparse
import concurrent.futures as cf
import json
import os
import statistics
import subprocess
import sys
import tempfile

import numpy as np

GRADES = {
    "tactical-fog": {"N": 0.3, "B": 0.1, "K": 0.02},
    "mems": {"N": 150.0, "B": 30.0, "K": 0.0},
}
FS_HZ = 100.0
HOURS = 2.0


def run(foglab, work, grade_name, dof, seed):
    g = GRADES[grade_name]
    stem = os.path.join(work, f"{grade_name}_{dof}_{seed}")
    subprocess.run([foglab, "generate", "--N", "0", "--B", str(g["B"]), "--K", str(g["K"]),
                    "--fs", f"{FS_HZ:g}", "--hours", f"{HOURS:g}", "--seed", str(seed),
                    "--out", stem + ".f64"], check=True, capture_output=True)
    y = np.fromfile(stem + ".f64")
    rng = np.random.default_rng([seed, int(dof * 1000)])
    scale = g["N"] * FS_HZ ** 0.5
    white = rng.standard_t(dof, len(y)) * np.sqrt((dof - 2.0) / dof) if dof else rng.standard_normal(len(y))
    (y + scale * white).tofile(stem + ".f64")
    a = subprocess.run([foglab, "analyze", stem + ".f64", "--fs", f"{FS_HZ:g}", "--json", "-"],
                       check=True, capture_output=True, text=True)
    os.remove(stem + ".f64")
    return json.loads(a.stdout)


def summarise(grade_name, results):
    g = GRADES[grade_name]
    n_err, b_err, k_err = [], [], []
    inside = heavy = spikes = steps = 0
    for r in results:
        nm = r["noise_model"]
        n = nm["N"]["value"]
        n_err.append(abs(n / g["N"] - 1))
        lo, hi = nm["N"]["ci95"] or (None, None)
        inside += lo is not None and lo <= g["N"] <= (hi if hi is not None else float("inf"))
        for key, sink in (("B", b_err), ("K", k_err)):
            if g[key] > 0:
                v = nm[key]["value"]
                sink.append(abs(v / g[key] - 1) if v is not None else float("inf"))
        heavy += r["spikes"].get("heavy_tailed", False)  # absent before 2026-11-28
        spikes += r["spikes"]["count"]
        steps += r["steps"]["count"]
    pct = lambda xs, f: f"{100 * f(xs):.1f}" if xs else "-"
    return [pct(n_err, max), f"{inside}/{len(results)}", pct(b_err, statistics.median),
            pct(k_err, statistics.median), f"{heavy}/{len(results)}", str(spikes), str(steps)]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("foglab")
    p.add_argument("--seeds", type=int, default=10)
    p.add_argument("--dofs", default="3,4,5,10,0", help="degrees of freedom; 0: Gaussian")
    p.add_argument("--jobs", type=int, default=2)
    args = p.parse_args()
    work = tempfile.mkdtemp(prefix="foglab_heavy_")
    print("| grade | t dof | N worst % | N inside 95 % | B median % | K median % | "
          "heavy-tailed | spikes | steps |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for grade_name in GRADES:
        for dof in (float(d) for d in args.dofs.split(",")):
            with cf.ThreadPoolExecutor(args.jobs) as pool:
                jobs = [pool.submit(run, args.foglab, work, grade_name, dof, seed)
                        for seed in range(1, args.seeds + 1)]
                results = [j.result() for j in jobs]
            label = f"{dof:g}" if dof else "Gaussian"
            print(f"| {grade_name} | {label} | " + " | ".join(summarise(grade_name, results)) + " |",
                  flush=True)


if __name__ == "__main__":
    sys.exit(main())

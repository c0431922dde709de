#!/usr/bin/env python3
"""A bias that jumps as a process (random telegraph, or popcorn, noise),
which foglab's generator does not make: `analyze` against the truth.

    python3 bench/telegraph_study.py BUILD/apps/foglab/foglab [--seeds 6]
        [--amplitudes 0.3,0.4,0.5,1.0] [--dwell 100]

Each record is `generate`'s tactical-grade noise (N 0.3 deg/h/sqrt(Hz),
B 0.1 deg/h, 2 h at 100 Hz, raw f64) plus a bias of +-A deg/h that switches
sign with probability 1 / (dwell fs) at each sample. Its autocorrelation
is A^2 exp(-|t| / Tc) with Tc = dwell / 2: in second-order statistics a
Gauss-Markov process of sigma A, which is what the noise model should
report; levelling some of its jumps as bias steps leaves the rest as a
walk. Per amplitude it prints the records whose jumps were levelled, left
in as noise, or not found, the random-bias process reported, and sigma's
and Tc's median errors. Standard library only. Results go to
docs/validation.md by hand, with the date.
"""
import argparse
import array
import concurrent.futures as cf
import json
import os
import random
import statistics
import subprocess
import tempfile

FS_HZ = 100.0
HOURS = 2.0
N, B = 0.3, 0.1


def run(foglab, work, amplitude, dwell_s, seed):
    stem = os.path.join(work, f"{amplitude:g}_{seed}")
    subprocess.run([foglab, "generate", "--N", str(N), "--B", str(B), "--fs", f"{FS_HZ:g}",
                    "--hours", f"{HOURS:g}", "--seed", str(seed), "--out", stem + ".f64"],
                   check=True, capture_output=True)
    rate = array.array("d")
    with open(stem + ".f64", "rb") as f:
        rate.frombytes(f.read())
    draw = random.Random(1000 + seed)
    p, level, jumps = 1.0 / (dwell_s * FS_HZ), amplitude, 0
    for k in range(len(rate)):
        if draw.random() < p:
            level, jumps = -level, jumps + 1
        rate[k] += level
    with open(stem + ".f64", "wb") as f:
        rate.tofile(f)
    out = subprocess.run([foglab, "analyze", stem + ".f64", "--fs", f"{FS_HZ:g}", "--json", "-"],
                         check=True, capture_output=True, text=True).stdout
    os.remove(stem + ".f64")
    j = json.loads(out)
    model, steps = j["noise_model"], j["steps"]
    return {"jumps": jumps, "found": steps["count"], "levelled": steps["removed"],
            "as_noise": steps.get("left_as_noise", False), "process": j["random_bias_process"],
            "sigma": model["gm_sigma"]["value"], "tc": model["gm_tc"]["value"],
            "K": model["K"]["value"]}


def median_error(values, truth):
    values = [abs(v / truth - 1.0) * 100.0 for v in values if v is not None]
    return f"{statistics.median(values):.1f}" if values else "-"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("foglab")
    ap.add_argument("--seeds", type=int, default=6)
    ap.add_argument("--amplitudes", default="0.3,0.4,0.5,1.0")
    ap.add_argument("--dwell", type=float, default=100.0, help="mean time between switches, s")
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args()
    amplitudes = [float(a) for a in args.amplitudes.split(",")]
    tc = args.dwell / 2.0
    print(f"telegraph bias, dwell {args.dwell:g} s (Tc {tc:g} s), on N {N}, B {B}, "
          f"{HOURS:g} h at {FS_HZ:g} Hz, seeds 1-{args.seeds}\n")
    print("| amplitude deg/h | jumps | records levelled / left as noise / none found | "
          "process reported | K reported | GM sigma median error % | GM Tc median error % |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="foglab_telegraph_") as work, \
            cf.ThreadPoolExecutor(args.jobs) as pool:
        for a in amplitudes:
            rows = list(pool.map(lambda s: run(args.foglab, work, a, args.dwell, s),
                                 range(1, args.seeds + 1)))
            levelled = sum(r["levelled"] for r in rows)
            as_noise = sum(r["as_noise"] for r in rows)
            none = sum(r["found"] == 0 for r in rows)
            processes = ", ".join(f"{p} {sum(r['process'] == p for r in rows)}"
                                  for p in sorted({r["process"] for r in rows}))
            jumps = f"{min(r['jumps'] for r in rows)}-{max(r['jumps'] for r in rows)}"
            with_k = sum(r["K"] is not None for r in rows)
            print(f"| {a:g} | {jumps} | {levelled} / {as_noise} / {none} | {processes} | "
                  f"{with_k}/{len(rows)} | {median_error([r['sigma'] for r in rows], a)} | "
                  f"{median_error([r['tc'] for r in rows], tc)} |")


if __name__ == "__main__":
    main()

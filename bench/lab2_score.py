#!/usr/bin/env python3
"""Scores `foglab analyze` on the lab-2 variant data sets against their
answer keys, over seeds: the random-bias process and the accuracy class of
every run (6 variants x 2 gyros x 2 runs = 24 runs a seed), and on the ramp
runs whose key has a temperature law, whether the fitted c1's 95 % interval
holds the key's.

    python3 bench/lab2_score.py BUILD/apps/foglab/foglab [--seeds 2021,1,2,...] [--misses]
                                [--temp-degree 2]

Prints, per seed and in total, how many random-bias decisions and classes
agree with the key; --misses lists each disagreement with the key's and the
analysis's numbers (bias instability, ARW, the random bias's octaves).
--temp-degree 2 analyses as `foglab lab2` does by default (the manual's
quadratic); without it, `analyze`'s own default (auto).
"""
import argparse
import concurrent.futures as cf
import json
import os
import subprocess
import sys
import tempfile


def c1_at(gyro_model, t_ref_key, t_ref_fit):
    """The key's linear coefficient about the fit's centre."""
    c = gyro_model["temp_coefs"] + [0.0, 0.0]
    return c[0] + 2.0 * c[1] * (t_ref_fit - t_ref_key)


def score_seed(foglab, work, seed, temp_degree):
    out = os.path.join(work, f"seed{seed}")
    subprocess.run([foglab, "lab2-data", "--out", out, "--seed", str(seed)], check=True,
                   capture_output=True)
    with open(os.path.join(out, "answers.json")) as f:
        key = json.load(f)
    gyros = {(g["file"], g["gyro"]): g for g in key["gyros"]}
    rows = []
    for run in key["runs"]:
        degree = ["--temp-degree", temp_degree] if temp_degree else []
        a = subprocess.run([foglab, "analyze", os.path.join(out, run["file"]), "--channel",
                            run["rate_variable"], *degree, "--json", "-"], check=True,
                           capture_output=True, text=True)
        r = json.loads(a.stdout)
        e = run["expected"]
        s = r["systematic"]
        gyro = gyros[(run["file"], run["gyro"])]["model"]
        c1 = None
        if run["run"] == "ramp" and gyro["temp_coefs"] and gyro["temp_coefs"][0] != 0.0:
            key_c1 = c1_at(gyro, run["temperature"]["reference_c"], s["t_ref_c"])
            fit = s["coefficients"][1] if len(s["coefficients"]) > 1 else 0.0
            se = s["standard_errors"][1] if len(s["coefficients"]) > 1 else None
            c1 = {"key": key_c1, "fit": fit, "se": se, "degree": s["degree"],
                  "held": se is not None and abs(fit - key_c1) <= 1.959964 * se}
        rows.append({
            "seed": seed, "file": run["file"], "channel": run["rate_variable"], "run": run["run"],
            "rb_key": e["random_bias_process"], "rb": r["random_bias_process"],
            "class_key": e["accuracy_class"], "class": r["accuracy_class"],
            "bi_key": e["bias_instability_deg_h"], "bi": r["bias_instability_deg_h"],
            "arw_key": e["arw_deg_per_sqrt_h"], "arw": r["arw_deg_per_sqrt_h"],
            "octaves": e.get("random_bias_octaves"),
            "terms": r["fit"]["terms"], "c1": c1,
        })
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("foglab")
    p.add_argument("--seeds", default="2021")
    p.add_argument("--misses", action="store_true")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--temp-degree", default=None)
    p.add_argument("--c1-spread", action="store_true",
                   help="per gyro channel: c1's error over its standard error, over the seeds")
    args = p.parse_args()
    work = tempfile.mkdtemp(prefix="foglab_lab2_score_")
    seeds = [int(s) for s in args.seeds.split(",")]
    with cf.ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda s: score_seed(args.foglab, work, s, args.temp_degree),
                                seeds))
    rb_ok = cls_ok = total = 0
    laws = held = 0
    for rows in results:
        rb = sum(r["rb"] == r["rb_key"] for r in rows)
        cl = sum(r["class"] == r["class_key"] for r in rows)
        print(f"seed {rows[0]['seed']}: random bias {rb}/{len(rows)}, class {cl}/{len(rows)}")
        rb_ok += rb
        cls_ok += cl
        total += len(rows)
        for r in rows:
            if r["c1"] is None:
                continue
            laws += 1
            held += r["c1"]["held"]
            if args.misses and not r["c1"]["held"]:
                c = r["c1"]
                print(f"  {r['file']} {r['channel']}: c1 {c['fit']:.4g} +- "
                      f"{1.96 * c['se'] if c['se'] else float('nan'):.3g} (degree {c['degree']}), "
                      f"key {c['key']:.4g}")
        if args.misses:
            for r in rows:
                if r["rb"] != r["rb_key"] or r["class"] != r["class_key"]:
                    print(f"  {r['file']} {r['channel']} ({r['run']}): random bias {r['rb']} "
                          f"(key {r['rb_key']}, {r['octaves']:.2f} octaves), class {r['class']} "
                          f"(key {r['class_key']}; BI {r['bi']:.4g}/{r['bi_key']:.4g} deg/h, "
                          f"ARW {r['arw']:.4g}/{r['arw_key']:.4g} deg/sqrt(h)), fit {r['terms']}")
    if args.c1_spread:
        by_channel = {}
        for rows in results:
            for r in rows:
                c = r["c1"]
                if c is None or not c["se"]:
                    continue
                by_channel.setdefault((r["file"], r["channel"]), []).append(
                    (c["fit"] - c["key"]) / c["se"])
        print("c1's error in its standard errors, per channel over the seeds "
              "(an honest standard error: mean 0, rms 1):")
        for (file, channel), z in sorted(by_channel.items()):
            mean = sum(z) / len(z)
            rms = (sum(v * v for v in z) / len(z)) ** 0.5
            outside = sum(abs(v) > 1.959964 for v in z)
            print(f"  {file} {channel}: {len(z)} runs, mean {mean:+.2f}, rms {rms:.2f}, "
                  f"outside the 95 % interval {outside}")
    print(f"total: random bias {rb_ok}/{total} ({100 * rb_ok / total:.1f} %), "
          f"class {cls_ok}/{total} ({100 * cls_ok / total:.1f} %), "
          f"ramp runs with a temperature law: c1's 95 % interval holds the key in {held}/{laws}")


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Scores `foglab analyze` on the lab-2 variant data sets against their
answer keys, over seeds: the random-bias process and the accuracy class of
every run (6 variants x 2 gyros x 2 runs = 24 runs a seed).

    python3 bench/lab2_score.py BUILD/apps/foglab/foglab [--seeds 2021,1,2,...] [--misses]

Prints, per seed and in total, how many random-bias decisions and classes
agree with the key; --misses lists each disagreement with the key's and the
analysis's numbers (bias instability, ARW, the random bias's octaves).
"""
import argparse
import concurrent.futures as cf
import json
import os
import subprocess
import sys
import tempfile


def score_seed(foglab, work, seed):
    out = os.path.join(work, f"seed{seed}")
    subprocess.run([foglab, "lab2-data", "--out", out, "--seed", str(seed)], check=True,
                   capture_output=True)
    with open(os.path.join(out, "answers.json")) as f:
        key = json.load(f)
    rows = []
    for run in key["runs"]:
        a = subprocess.run([foglab, "analyze", os.path.join(out, run["file"]), "--channel",
                            run["rate_variable"], "--json", "-"], check=True, capture_output=True,
                           text=True)
        r = json.loads(a.stdout)
        e = run["expected"]
        rows.append({
            "seed": seed, "file": run["file"], "channel": run["rate_variable"], "run": run["run"],
            "rb_key": e["random_bias_process"], "rb": r["random_bias_process"],
            "class_key": e["accuracy_class"], "class": r["accuracy_class"],
            "bi_key": e["bias_instability_deg_h"], "bi": r["bias_instability_deg_h"],
            "arw_key": e["arw_deg_per_sqrt_h"], "arw": r["arw_deg_per_sqrt_h"],
            "octaves": e.get("random_bias_octaves"),
            "terms": r["fit"]["terms"],
        })
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("foglab")
    p.add_argument("--seeds", default="2021")
    p.add_argument("--misses", action="store_true")
    p.add_argument("--jobs", type=int, default=2)
    args = p.parse_args()
    work = tempfile.mkdtemp(prefix="foglab_lab2_score_")
    seeds = [int(s) for s in args.seeds.split(",")]
    with cf.ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda s: score_seed(args.foglab, work, s), seeds))
    rb_ok = cls_ok = total = 0
    for rows in results:
        rb = sum(r["rb"] == r["rb_key"] for r in rows)
        cl = sum(r["class"] == r["class_key"] for r in rows)
        print(f"seed {rows[0]['seed']}: random bias {rb}/{len(rows)}, class {cl}/{len(rows)}")
        rb_ok += rb
        cls_ok += cl
        total += len(rows)
        if args.misses:
            for r in rows:
                if r["rb"] != r["rb_key"] or r["class"] != r["class_key"]:
                    print(f"  {r['file']} {r['channel']} ({r['run']}): random bias {r['rb']} "
                          f"(key {r['rb_key']}, {r['octaves']:.2f} octaves), class {r['class']} "
                          f"(key {r['class_key']}; BI {r['bi']:.4g}/{r['bi_key']:.4g} deg/h, "
                          f"ARW {r['arw']:.4g}/{r['arw_key']:.4g} deg/sqrt(h)), fit {r['terms']}")
    print(f"total: random bias {rb_ok}/{total} ({100 * rb_ok / total:.1f} %), "
          f"class {cls_ok}/{total} ({100 * cls_ok / total:.1f} %)")


if __name__ == "__main__":
    sys.exit(main())

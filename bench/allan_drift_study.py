#!/usr/bin/env python3
"""The short taus' stationarity check (stats/allan_drift.h) on the effects
study's records, which are stationary: how often it calls, and whether its
Mann-Kendall z follows N(0, 1).

    python3 bench/allan_drift_study.py BUILD/apps/foglab/foglab [--seeds 10]

Each grade x effect x seed of bench/effects_study.py (2 h at 100 Hz) is
generated and analysed; the script prints the number of records and taus
checked, the mean and mean square of z, the largest |z|, and every record
with a call (none expected: p < 1e-4 at each tau).
"""
import argparse
import concurrent.futures as cf
import os
import shutil
import statistics
import tempfile

import effects_study as es


def main():
    p = argparse.ArgumentParser()
    p.add_argument("foglab")
    p.add_argument("--seeds", type=int, default=10)
    p.add_argument("--jobs", type=int, default=2)
    args = p.parse_args()
    work = tempfile.mkdtemp(prefix="foglab_drift_")
    jobs = [(g, e, s) for g in es.GRADES for e in es.effects(es.GRADES[g])
            for s in range(1, args.seeds + 1)]

    def one(job):
        g, e, s = job
        _, r = es.run(args.foglab, work, g, e, es.effects(es.GRADES[g])[e], s)
        os.remove(os.path.join(work, f"{g}_{e}_{s}_truth.json"))
        return g, e, s, r["allan_drift"]

    with cf.ThreadPoolExecutor(args.jobs) as ex:
        results = list(ex.map(one, jobs))
    shutil.rmtree(work)
    zs = [z for *_, d in results for z in d["trend_z"]]
    calls = [(g, e, s, d["tau_s"], [round(z, 2) for z in d["trend_z"]])
             for g, e, s, d in results if any(d["drifting"])]
    print(f"records {len(results)}, taus checked {len(zs)}, mean z {statistics.mean(zs):+.3f}, "
          f"mean z^2 {statistics.mean(z * z for z in zs):.3f}, max |z| {max(abs(z) for z in zs):.2f}")
    print("records with a call:", len(calls))
    for c in calls:
        print(" ", c)


if __name__ == "__main__":
    main()

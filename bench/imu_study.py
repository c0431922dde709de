#!/usr/bin/env python3
"""Accuracy of the IMU form of `foglab analyze` over seeds (issue 17).

For each seed: `foglab generate --imu` (the mems-imu model) to a MAT file, then
`foglab analyze` of all six axes; every axis's N, bias instability (the ADEV
minimum against the model's) and K against the truth, and whether the 95 %
intervals cover it; the Kalibr values against the truth's.

    python3 bench/imu_study.py build/apps/foglab/foglab --seeds 1-5 --hours 8 --fs 400

Plain python3 (no numpy). Writes into a temporary folder it removes.
"""
import argparse
import json
import statistics
import subprocess
import tempfile
from pathlib import Path


def seeds_of(text):
    if "-" in text:
        a, b = text.split("-")
        return list(range(int(a), int(b) + 1))
    return [int(s) for s in text.split(",")]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("foglab")
    ap.add_argument("--seeds", default="1-5")
    ap.add_argument("--hours", type=float, default=8.0)
    ap.add_argument("--fs", type=float, default=400.0)
    args = ap.parse_args()

    rows = {}  # axis -> list of dicts
    kalibr = []
    with tempfile.TemporaryDirectory() as tmp:
        for seed in seeds_of(args.seeds):
            csv = Path(tmp) / f"imu{seed}.mat"
            truth = Path(tmp) / f"truth{seed}.json"
            subprocess.run([args.foglab, "generate", "--imu", "--hours", str(args.hours),
                            "--fs", str(args.fs), "--seed", str(seed), "--out", str(csv),
                            "--truth", str(truth)], check=True, capture_output=True)
            out = subprocess.run([args.foglab, "analyze", str(csv), "--json", "-"], check=True,
                                 capture_output=True, text=True).stdout
            csv.unlink()
            result, t = json.loads(out), json.load(open(truth))
            for c in result["channels"]:
                axis = c["input"]["channel"]
                a = t["axes"][axis]
                nm = c["noise_model"]
                bi = c.get("bias_instability_deg_h", c.get("bias_instability_m_s2"))
                k = nm["K"]
                if k["status"] == "resolved":
                    k_cover = k["ci95"][0] <= a["K"] <= k["ci95"][1]
                    k_err = k["value"] / a["K"] - 1
                else:
                    k_cover = k["upper_95"] is not None and a["K"] <= k["upper_95"]
                    k_err = None
                n = nm["N"]
                rows.setdefault(axis, []).append({
                    "n_err": n["value"] / a["N"] - 1,
                    "n_cover": n["ci95"] is not None and n["ci95"][0] <= a["N"] <= n["ci95"][1],
                    "bi_err": bi / a["bias_instability"] - 1,
                    "k_resolved": k["status"] == "resolved",
                    "k_err": k_err,
                    "k_cover": k_cover,
                })
            kalibr.append({key: result["kalibr"][key] / t["kalibr"][key] - 1
                           for key in ["gyroscope_noise_density", "gyroscope_random_walk",
                                       "accelerometer_noise_density", "accelerometer_random_walk"]})

    def med_abs(values):
        values = [abs(v) for v in values if v is not None]
        return f"{100 * statistics.median(values):.1f} %" if values else "-"

    print(f"{len(kalibr)} seeds, {args.hours} h at {args.fs} Hz")
    print("| axis | N median abs error | N covered | bias instability median abs error | "
          "K resolved | K median abs error | K covered |")
    print("|---|---|---|---|---|---|---|")
    for axis, r in rows.items():
        print(f"| {axis} | {med_abs([x['n_err'] for x in r])} | "
              f"{sum(x['n_cover'] for x in r)}/{len(r)} | {med_abs([x['bi_err'] for x in r])} | "
              f"{sum(x['k_resolved'] for x in r)}/{len(r)} | {med_abs([x['k_err'] for x in r])} | "
              f"{sum(x['k_cover'] for x in r)}/{len(r)} |")
    for key in kalibr[0]:
        print(f"kalibr {key}: median abs error {med_abs([k[key] for k in kalibr])}")


if __name__ == "__main__":
    main()

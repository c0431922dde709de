#!/usr/bin/env python3
"""Issue 16's real-channel check on records the estimator was not tuned on.

    python3 bench/real_variants.py BUILD/apps/foglab/foglab [--data ../shared/data/real]

Only three real recordings are here (nine gyro channels), and foglab's
short-tau models were built while looking at them. This derives other real
records from them, each with a sensor behaviour the nine channels do not
show, and applies the issue's done-when to each:

- halves: the first and the second 5 x 10^5 samples (1.4 h; the long taus
  and the flicker floor rest on half the data);
- avg2: pairs of samples averaged (50 Hz): the output filter becomes a
  different filter, the output word a half-step grid;
- pick4: every fourth sample (25 Hz): the filter's correlation is gone,
  and the 20 Hz resonance of the z axes aliases to 5 Hz;
- xy: the x and y channels of one IMU summed over sqrt(2): two sensors'
  flicker and correlation mixed, the output word a finer grid.

The derived files are written to a temporary folder and removed (the data's
licence: never into the repository). Per record it prints N against the
Allan white level (the -1/2 region, as tests/cli/cli_real_data_test.cc
computes it), the terms, B, the bandwidth, a search bound if one was hit,
a Gauss-Markov Tc below the first tau, the class, and the taus where the
fitted curve leaves the 95 % intervals; and the count of records that meet
each criterion.
"""
import argparse
import concurrent.futures as cf
import json
import math
import os
import subprocess
import sys
import tempfile

AXES = ["x", "y", "z"]


def read_channels(path):
    rows = []
    with open(path) as f:
        header = f.readline().strip().split(",")
        for line in f:
            parts = line.split(",")
            rows.append([float(p) for p in parts])
    return header, rows


def write(path, values):
    with open(path, "w") as f:
        f.write("rate_dps\n")
        for v in values:
            f.write(f"{v:.9g}\n")


def white_level(allan):
    tau, dev = allan["tau_s"], allan["adev_deg_h"]

    def on_slope(i):
        return abs(math.log(dev[i + 1] / dev[i]) / math.log(tau[i + 1] / tau[i]) + 0.5) <= 0.05

    best = (0, 0)
    i = 0
    while i + 1 < len(tau):
        if not on_slope(i):
            i += 1
            continue
        j = i
        while j + 1 < len(tau) and on_slope(j):
            j += 1
        if j + 1 - i > best[1] - best[0]:
            best = (i, j + 1)
        i = j
    if best[1] - best[0] < 3:
        return float("nan")
    logs = [math.log(dev[k] * math.sqrt(tau[k])) for k in range(best[0], best[1])]
    return math.exp(sum(logs) / len(logs))


def analyse(foglab, path, fs):
    r = subprocess.run([foglab, "analyze", path, "--fs", str(fs), "--units", "deg/s", "--json", "-"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return {"error": r.stderr.strip()}
    return json.loads(r.stdout)


def verdict(j):
    nm = j["noise_model"]
    n = nm["N"]["value"]
    level = white_level(j["allan"])
    a = j["allan"]
    outside = [a["tau_s"][i] for i in range(len(a["tau_s"]))
               if not a["ci95_low"][i] <= a["model_adev_deg_h"][i] <= a["ci95_high"][i]]
    bw = j["sensor_bandwidth"]
    gm_short = nm["gm_tc"]["status"] == "resolved" and nm["gm_tc"]["value"] < a["tau_s"][0]
    bw_text = "-"
    if bw.get("resolved"):
        if bw["kind"] == "moving_average":
            bw_text = f"{bw['moving_average_samples']}-avg {bw['filtered_fraction']:.0%}"
        elif bw["kind"] == "beyond_memory":
            bw_text = f"beyond memory c {bw['memory_constant_samples']:.2f}"
        else:
            bw_text = f"{bw['kind']} {bw['cutoff_hz']:.1f} Hz"
    return {
        "N": n, "level": level, "n_err": n / level - 1,
        "terms": j["fit"]["terms"], "B": nm["B"]["value"], "B_status": nm["B"]["status"],
        "bandwidth": bw_text, "bw_resolved": bw.get("resolved", False), "bound": bw.get("at_search_bound", False),
        "gm_short": gm_short, "class": j["accuracy_class"], "outside": outside,
        "lines": [round(l["frequency_hz"], 1) for l in j["spectral_lines"]],
        "lag1": bw.get("lag1_correlation"), "status": j["fit"]["status"],
    }


def real_data_arguments():
    """The command line of the scripts on the real recordings: the foglab
    binary, --data (their folder; exits, saying so, when they are not
    there) and --jobs."""
    ap = argparse.ArgumentParser()
    ap.add_argument("foglab")
    ap.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "..", "..", "shared",
                                                   "data", "real"))
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args()
    if not os.path.exists(os.path.join(args.data, "adis_16405_imu1_gyro.csv")):
        sys.exit(f"the real recordings are not in {args.data}")
    return args


def main():
    args = real_data_arguments()
    tmp = tempfile.mkdtemp(prefix="foglab_real_variants_")
    jobs = []
    for imu in (1, 2, 3):
        _, rows = read_channels(os.path.join(args.data, f"adis_16405_imu{imu}_gyro.csv"))
        for k, axis in enumerate(AXES):
            x = [r[k] for r in rows]
            half = len(x) // 2
            variants = {
                "half1": (x[:half], 100.0), "half2": (x[half:], 100.0),
                "avg2": ([(x[i] + x[i + 1]) / 2 for i in range(0, len(x) - 1, 2)], 50.0),
                "pick4": (x[::4], 25.0),
            }
            for name, (values, fs) in variants.items():
                path = os.path.join(tmp, f"imu{imu}_{axis}_{name}.csv")
                write(path, values)
                jobs.append((f"imu{imu} {axis} {name}", path, fs))
        xy = [(r[0] + r[1]) / math.sqrt(2) for r in rows]
        path = os.path.join(tmp, f"imu{imu}_xy.csv")
        write(path, xy)
        jobs.append((f"imu{imu} x+y", path, 100.0))

    with cf.ThreadPoolExecutor(args.jobs) as ex:
        results = list(ex.map(lambda job: (job[0], analyse(args.foglab, job[1], job[2])), jobs))
    for _, path, _ in jobs:
        os.remove(path)
    os.rmdir(tmp)

    print("| record | N | white level | N / level | terms | B (status) | bandwidth | lines [Hz] "
          "| taus outside | class |")
    print("|---|---:|---:|---:|---|---|---|---|---|---|")
    counts = {"N within 5 %": 0, "no reported value at a search bound": 0, "no GM below the taus": 0, "B resolved": 0,
              "bandwidth resolved (none expected on pick4)": 0, "class consumer": 0, "<= 2 taus outside": 0, "converged": 0}
    for name, j in results:
        if "error" in j:
            print(f"| {name} | error: {j['error']} |")
            continue
        v = verdict(j)
        bandwidth = v["bandwidth"]
        if v["bw_resolved"] and v["lag1"] is not None:
            bandwidth += f" (lag-1 {v['lag1']:.2f})"
        if v["bound"]:
            bandwidth += " (best T at the search bound: not resolved)"
        outside = f"{len(v['outside'])} {v['outside']}" if v["outside"] else "0"
        print(f"| {name} | {v['N']:.1f} | {v['level']:.1f} | {v['n_err']:+.1%} | {v['terms']} "
              f"| {v['B'] or 0:.1f} ({v['B_status']}) | {bandwidth} | {v['lines'] or '-'} "
              f"| {outside} | {v['class']} |")
        counts["N within 5 %"] += abs(v["n_err"]) <= 0.05
        counts["no reported value at a search bound"] += not (v["bound"] and v["bw_resolved"])
        counts["no GM below the taus"] += not v["gm_short"]
        counts["B resolved"] += v["B_status"] == "resolved"
        counts["bandwidth resolved (none expected on pick4)"] += v["bw_resolved"]
        counts["class consumer"] += v["class"] == "consumer"
        counts["<= 2 taus outside"] += len(v["outside"]) <= 2
        counts["converged"] += v["status"] == "converged"
    print()
    for k, c in counts.items():
        print(f"{k}: {c}/{len(results)}")


if __name__ == "__main__":
    main()

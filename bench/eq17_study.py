#!/usr/bin/env python3
"""The manual's eq. (17) against the measured Allan deviation (issue 23).

For six generated models, ten seeds each, `foglab analyze` fits the model and
integrates its PSD through eq. (17); this counts the taus where the result lies
inside the measured OADEV's 95 % interval and the largest disagreement in
half-widths of that interval (JSON `psd_allan_check`).

    python3 bench/eq17_study.py build/apps/foglab/foglab [--seeds 10]
"""
import argparse
import json
import os
import subprocess
import tempfile

MODELS = {
    "N+B+K": "--N 0.5 --B 0.05 --K 0.005 --fs 10 --hours 2",
    "N+GM": "--N 0.5 --gm-sigma 0.3 --gm-tc 60 --fs 10 --hours 2",
    "N+B+Q": "--N 0.2 --B 0.05 --Q 0.3 --fs 10 --hours 1",
    "N+B, first-order filter": "--N 150 --B 5 --filter-tc 0.03 --fs 100 --hours 1",
    "N+K+R": "--N 0.5 --K 0.01 --R 2e-4 --fs 10 --hours 2",
    "N+B+K, T ramp, 0.3 Hz line": "--N 0.5 --B 0.05 --K 0.005 --temp-coef 0.8 "
    "--temperature ramp:10 --sine 0.3:2 --fs 10 --hours 2",
}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("foglab")
    parser.add_argument("--seeds", type=int, default=10)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        record = os.path.join(tmp, "r.mat")
        print("| model | taus inside the 95 % intervals | worst, half-widths: median | max |")
        print("|---|---|---|---|")
        for name, options in MODELS.items():
            inside = compared = 0
            worst = []
            for seed in range(1, args.seeds + 1):
                subprocess.run(f"{args.foglab} generate {options} --seed {seed} --out {record}",
                               shell=True, check=True, capture_output=True)
                out = subprocess.run(f"{args.foglab} analyze {record} --json -", shell=True,
                                     check=True, capture_output=True, text=True).stdout
                check = json.loads(out)["psd_allan_check"]
                inside += check["inside_95"]
                compared += check["compared"]
                worst.append(check["worst_half_widths"])
            worst.sort()
            print(f"| {name} | {inside}/{compared} ({100 * inside / compared:.1f} %) | "
                  f"{worst[len(worst) // 2]:.2f} | {worst[-1]:.2f} |")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""`foglab allan` end to end against AllanTools on the same MAT file and taus (issue 19).

    /usr/bin/python3 bench/cli_vs_allantools.py [--build build] [--allantools DIR]
        [--samples 20000000] [--repeat 7] [--at-repeat 3] [--keep FILE]

Writes a MAT v5 file of white rate noise (f and Y1, 100 Hz; build/bench/bench_make_mat),
then times from this process, wall clock, each a fresh process:
  * `foglab allan FILE --channel Y1 --min-clusters 1 --json OUT`: reading, integration,
    OADEV on the octave grid down to 2 clusters, noise identification, edf, 68/95 %
    intervals, JSON written; and the same with --no-ci (the deviations only);
  * a Python process that does the same with AllanTools: scipy.io.loadmat, then
    allantools.oadev(Y1, rate=f, data_type="freq", taus="octave"), the result written as
    JSON. It also reports the time of the oadev call alone (the record in memory).
Checks that both give the same taus, counts and deviations (1e-9), and prints the medians
and the ratios: AllanTools end to end / foglab end to end, and AllanTools's call alone /
foglab end to end (the stricter one). AllanTools is not part of this repository
(--allantools DIR holds its allantools/ package; it needs numpy and scipy).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

from bench_common import import_allantools, machine_line, runs_text, timed

ALLANTOOLS_RUN = r"""
import json, sys, time
sys.path.insert(0, sys.argv[3])
import scipy.io, allantools
mat = scipy.io.loadmat(sys.argv[1])
y, rate = mat["Y1"].ravel(), float(mat["f"].ravel()[0])
start = time.perf_counter()
taus, devs, errors, ns = allantools.oadev(y, rate=rate, data_type="freq", taus="octave")
call_s = time.perf_counter() - start
json.dump({"tau_s": taus.tolist(), "dev": devs.tolist(), "n": ns.tolist(), "call_s": call_s},
          open(sys.argv[2], "w"))
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build", help="foglab's build folder")
    parser.add_argument("--allantools", help="folder holding the allantools package")
    parser.add_argument("--samples", type=int, default=20_000_000)
    parser.add_argument("--repeat", type=int, default=7, help="runs of each foglab command")
    parser.add_argument("--at-repeat", type=int, default=3, help="runs of AllanTools")
    parser.add_argument("--keep", help="write the MAT file here and keep it (else a scratch one)")
    args = parser.parse_args()
    allantools = import_allantools(args.allantools)
    at_dir = os.path.dirname(os.path.dirname(os.path.abspath(allantools.__file__)))
    foglab = os.path.join(args.build, "apps", "foglab", "foglab")
    print(machine_line())

    with tempfile.TemporaryDirectory() as work:
        mat = args.keep or os.path.join(work, "record.mat")
        subprocess.run([os.path.join(args.build, "bench", "bench_make_mat"), mat,
                        str(args.samples), "100"], check=True)
        print(f"record: {mat}, {os.path.getsize(mat) / 1e6:.0f} MB, {args.samples} samples "
              "at 100 Hz, OADEV, octave taus down to 2 clusters")
        mine_json = os.path.join(work, "foglab.json")
        command = [foglab, "allan", mat, "--channel", "Y1", "--min-clusters", "1",
                   "--json", mine_json]
        run = lambda extra: subprocess.run(command + extra, check=True, stdout=subprocess.DEVNULL)
        full, full_runs, _ = timed(lambda: run([]), args.repeat)
        print(f"foglab allan, with intervals: median {full:.3f} s (runs {runs_text(full_runs)})")
        mine = json.load(open(mine_json))
        bare, bare_runs, _ = timed(lambda: run(["--no-ci"]), args.repeat)
        print(f"foglab allan --no-ci: median {bare:.3f} s (runs {runs_text(bare_runs)})")

        theirs_json = os.path.join(work, "allantools.json")
        at_command = [sys.executable, "-c", ALLANTOOLS_RUN, mat, theirs_json, at_dir]
        calls = []

        def run_allantools():
            subprocess.run(at_command, check=True)
            calls.append(json.load(open(theirs_json))["call_s"])

        at_total, at_runs, _ = timed(run_allantools, args.at_repeat)
        at_call = float(np.median(calls))
        print(f"AllanTools {getattr(allantools, '__version__', '?')}, end to end: median "
              f"{at_total:.3f} s (runs {runs_text(at_runs)}); its oadev call alone: median "
              f"{at_call:.3f} s (runs {runs_text(calls)})")
        theirs = json.load(open(theirs_json))

    np.testing.assert_allclose(mine["tau_s"], theirs["tau_s"], rtol=1e-12)
    np.testing.assert_array_equal(mine["n"], theirs["n"])
    worst = float(np.max(np.abs(np.asarray(mine["dev"]) / theirs["dev"] - 1.0)))
    if worst > 1e-9:
        sys.exit(f"foglab and AllanTools differ by {worst:.1e}")
    print(f"same {len(mine['tau_s'])} taus and counts; deviations agree to {worst:.1e} relative")
    for label, value in (("with intervals", full), ("--no-ci", bare)):
        print(f"foglab allan {label}: AllanTools end to end / it {at_total / value:.1f}x; "
              f"AllanTools's call alone / it {at_call / value:.1f}x")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""The total and Theo family against AllanTools, in process, on the same phase record and
taus (issue 19): MTOTDEV, HTOTDEV and Theo1 of white-FM phase (a random walk).

    PYTHONPATH=build/python /usr/bin/python3 bench/total_vs_allantools.py \
        [--allantools DIR] [--points 100000] [--max-m 32] [--repeat 3] [--seed 7]

For each statistic, times foglab.compat.<kind> (AllanTools's call and tuple through foglab;
Theo1 through foglab.allan at AllanTools's factors) on the octave factors m = 1 .. --max-m
(Theo1: the even ones from 10 on, up to 32 --max-m), then AllanTools's function on the same
taus when it can be imported (--allantools DIR holds the allantools/ package, which is not
part of this repository). AllanTools's pure-Python loops cost O(N m) per tau, so --max-m
keeps its run to minutes; foglab's whole octave grid to N/3 is timed as well. Checks the
deviations agree (1e-9) and prints each median and the ratio.
"""
import argparse
import sys

import numpy as np

import foglab
import foglab.compat
from bench_common import import_allantools, machine_line, timed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--allantools", help="folder holding the allantools package")
    parser.add_argument("--points", type=int, default=100_000)
    parser.add_argument("--max-m", type=int, default=32)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args()
    phase = np.cumsum(np.random.default_rng(args.seed).standard_normal(args.points))
    print(f"{machine_line()}, foglab {foglab.__version__}")
    print(f"record: {args.points} phase points (white FM), octave m = 1 .. {args.max_m}")
    allantools = import_allantools(args.allantools, required=False) if args.allantools else None

    octave = [float(2 ** k) for k in range(args.max_m.bit_length()) if 2 ** k <= args.max_m]
    theo_m = [m for m in range(10, 32 * args.max_m + 1, 2) if m & (m - 1) == 0 or m == 10]
    for kind in ("mtotdev", "htotdev", "theo1"):
        if kind == "theo1":
            # AllanTools labels Theo1 at tau = m tau0; foglab at 0.75 m tau0.
            mine = lambda: foglab.allan(phase, 1.0, kind="theo1", input="phase",
                                        taus=[0.75 * m for m in theo_m], confidence=False)
            median, _, r = timed(mine, args.repeat)
            devs = r.dev
            taus_at = [float(m) for m in theo_m]
        else:
            median, _, (taus, devs, _, _) = timed(
                lambda: getattr(foglab.compat, kind)(phase, taus=octave), args.repeat)
            taus_at = list(taus)
        print(f"{kind}: foglab {median:.4f} s on {len(taus_at)} taus", end="")
        whole, _, _ = timed(lambda: foglab.allan(phase, 1.0, kind=kind, input="phase",
                                              min_clusters=1, confidence=False), 1)
        print(f"; the whole octave grid (min_clusters 1): {whole:.3f} s", end="")
        if allantools is None:
            print()
            continue
        theirs_s, _, (_, theirs, _, _) = timed(
            lambda: getattr(allantools, kind)(phase, rate=1.0, data_type="phase", taus=taus_at), 1)
        worst = float(np.max(np.abs(np.asarray(devs) / theirs - 1.0)))
        print(f"; AllanTools {theirs_s:.2f} s, ratio {theirs_s / median:.0f}x, "
              f"largest relative difference {worst:.1e}")
        if worst > 1e-9:
            sys.exit(f"{kind}: foglab and AllanTools differ by {worst:.1e}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""foglab's Python module against AllanTools, in process, on the same record and taus
(issue 18): OADEV of 2e7 fractional-frequency (rate) samples, octave taus.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_vs_allantools.py \
        [--allantools DIR] [--samples 20000000] [--repeat 3] [--seed 5]

Times, with the record made before any timing:
  * foglab.compat.oadev(data, rate, data_type="freq", taus="octave") - AllanTools's call,
    taus and tuple, through foglab;
  * foglab.allan(data, rate, taus=<the same seconds>) - the same deviations plus noise
    identification, edf and 68/95 % intervals;
  * allantools.oadev(data, rate, data_type="freq", taus="octave"), when AllanTools can be
    imported (--allantools DIR holds the allantools/ package; it is not part of this
    repository and needs numpy and scipy).
Checks that foglab's taus equal AllanTools's and its deviations agree to 1e-9, and prints
each median and the ratio.
"""
import argparse

import numpy as np

import foglab
import foglab.compat
from bench_common import import_allantools, machine_line, runs_text, timed

RATE_HZ = 100.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--allantools", help="folder holding the allantools package")
    parser.add_argument("--samples", type=int, default=20_000_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--seed", type=int, default=5)
    args = parser.parse_args()
    data = np.random.default_rng(args.seed).standard_normal(args.samples)
    print(f"{machine_line()}, foglab {foglab.__version__}")
    print(f"record: {args.samples} samples at {RATE_HZ} Hz, OADEV, octave taus")

    median, runs, (taus, devs, _, ns) = timed(
        lambda: foglab.compat.oadev(data, rate=RATE_HZ, data_type="freq", taus="octave"),
        args.repeat)
    print(f"foglab.compat.oadev: median {median:.3f} s (runs {runs_text(runs)}); "
          f"{taus.size} taus, m = {int(taus[0] * RATE_HZ)} .. {int(taus[-1] * RATE_HZ)}")
    full, full_runs, _ = timed(lambda: foglab.allan(data, RATE_HZ, taus=list(taus)), args.repeat)
    print(f"foglab.allan with noise ID, edf, intervals: median {full:.3f} s "
          f"(runs {runs_text(full_runs)})")

    allantools = import_allantools(args.allantools, required=False)
    if allantools is None:
        return
    at, at_runs, (at_taus, at_devs, _, at_ns) = timed(
        lambda: allantools.oadev(data, rate=RATE_HZ, data_type="freq", taus="octave"),
        args.repeat)
    print(f"allantools.oadev {getattr(allantools, '__version__', '?')}: median {at:.3f} s "
          f"(runs {runs_text(at_runs)})")
    np.testing.assert_allclose(taus, at_taus, rtol=1e-15)
    np.testing.assert_array_equal(ns, at_ns)
    worst = float(np.max(np.abs(devs / at_devs - 1.0)))
    print(f"same taus and counts; deviations agree to {worst:.1e} relative")
    print(f"ratio AllanTools / foglab.compat.oadev: {at / median:.1f}x; "
          f"/ foglab.allan with intervals: {at / full:.1f}x")


if __name__ == "__main__":
    main()

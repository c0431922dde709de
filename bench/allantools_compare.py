#!/usr/bin/env python3
"""A 6-axis IMU's records in memory through AllanTools: six OADEVs timed,
for comparison with foglab's bench/bench_imu.cc on the same sizes (issue 17).

    python3 bench/allantools_compare.py --allantools DIR [--samples 11520000]
        [--axes 6] [--repeat 1] [--seed 17] [--taus-only]

DIR is a directory that holds the `allantools/` package (a clone of
https://github.com/aewallin/allantools, or a site-packages directory); without
--allantools the script imports whatever `allantools` is installed. AllanTools
is not part of this repository: get it with `pip install allantools` (it
needs numpy and scipy) on a machine with PyPI access, or clone it.

The records are made before any timing (the records in memory): --axes
float64 arrays of --samples white-noise samples each (numpy default_rng,
fixed --seed; 8 h at 400 Hz by default). Each is then passed to

    allantools.oadev(data, rate=400.0, data_type="freq", taus="octave")

and the call is timed with time.perf_counter. Prints each call's time and
the total of the axes, for every repeat, then the median total. The call
includes AllanTools's frequency -> phase integration (frequency2phase: mean
removal, cumsum, a leading 0; len(phase) = samples + 1) and its tau
generation. Also prints the taus and averaging factors m = tau * rate the
call returned, so foglab can be checked to evaluate the same ones, and the
machine (platform, CPU, numpy, scipy, AllanTools versions).

--taus-only prints the octave m list AllanTools would return for --samples
(it depends only on the length) without making the records or timing.

The full size wants about 0.6 GB for the records plus about 0.5 GB of
AllanTools's temporaries, and takes minutes: numpy runs these passes on one
core.
"""
import argparse
import os
import statistics
import sys
import time

import numpy as np

from bench_common import import_allantools, machine_line

RATE_HZ = 400.0


def print_machine(at):
    try:
        import scipy
        scipy_version = scipy.__version__
    except ImportError:
        scipy_version = "not installed"
    print(machine_line())
    print(f"scipy {scipy_version}; allantools "
          f"{getattr(at, '__version__', 'unknown (no __version__)')} "
          f"from {os.path.dirname(at.__file__)}")


def octave_ms(at, samples, rate):
    """The m list oadev(..., data_type="freq", taus="octave") returns for a
    record of `samples` samples: AllanTools's tau_generator on the phase
    length (samples + 1), then oadev's rejection of n <= 1, where n is the
    number of overlapping second differences (samples + 1 - 2m; 0 becomes 1)."""
    phase_len = samples + 1
    # tau_generator only needs the length; a zero-stride view keeps this cheap
    # (it still copies it once, np.array(data): 8 bytes a sample).
    _, ms, _ = at.tau_generator(np.broadcast_to(np.float64(0.0), (phase_len,)), rate,
                                taus="octave")
    kept = []
    for m in ms:
        n = max(phase_len - 2 * int(m), 0)
        if n == 0:
            n = 1
        if n > 1:
            kept.append(int(m))
    return kept


def print_taus(label, ms, rate):
    print(f"{label}: {len(ms)} taus")
    print("  m   = " + " ".join(str(m) for m in ms))
    print("  tau = " + " ".join(f"{m / rate:g}" for m in ms) + " s")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--allantools", metavar="DIR",
                    help="directory holding the allantools/ package")
    ap.add_argument("--samples", type=int, default=11_520_000,
                    help="samples per axis (default 11520000: 8 h at 400 Hz)")
    ap.add_argument("--axes", type=int, default=6, help="axes (default 6)")
    ap.add_argument("--repeat", type=int, default=1,
                    help="runs over all axes; the median total is reported (default 1)")
    ap.add_argument("--seed", type=int, default=17, help="numpy seed (default 17)")
    ap.add_argument("--taus-only", action="store_true",
                    help="only print the octave m list for --samples; no records, no timing")
    args = ap.parse_args()
    if args.samples < 3 or args.axes < 1 or args.repeat < 1:
        ap.error("--samples >= 3, --axes >= 1 and --repeat >= 1")

    at = import_allantools(args.allantools)
    print_machine(at)
    predicted = octave_ms(at, args.samples, RATE_HZ)
    print_taus(f"octave taus for {args.samples} samples at {RATE_HZ:g} Hz (predicted)",
               predicted, RATE_HZ)
    if args.taus_only:
        return 0

    print(f"{args.axes} axes x {args.samples} samples at {RATE_HZ:g} Hz "
          f"({args.samples / RATE_HZ / 3600:.3g} h), white noise, seed {args.seed}")
    rng = np.random.default_rng(args.seed)
    records = [rng.standard_normal(args.samples) for _ in range(args.axes)]
    print(f"records in memory: {sum(r.nbytes for r in records) / 1e6:.0f} MB")

    totals = []
    returned = None
    for rep in range(args.repeat):
        times = []
        for k, y in enumerate(records):
            t0 = time.perf_counter()
            taus, devs, _, _ = at.oadev(y, rate=RATE_HZ, data_type="freq", taus="octave")
            dt = time.perf_counter() - t0
            times.append(dt)
            ms = [int(round(t * RATE_HZ)) for t in taus]
            if returned is None:
                returned = ms
                first_dev = devs[0]
            elif ms != returned:
                print(f"warning: axis {k} returned other taus: {ms}")
            print(f"run {rep + 1} axis {k}: oadev {dt:.3f} s")
        totals.append(sum(times))
        print(f"run {rep + 1}: total of {args.axes} oadev calls {totals[-1]:.3f} s")

    print_taus("taus returned by oadev", returned, RATE_HZ)
    if returned != predicted:
        print("warning: the returned taus differ from the predicted ones")
    print(f"oadev at tau0 (axis 0): {first_dev:.6f} (white noise of unit variance: about 1)")
    print(f"median total of {args.axes} oadev calls over {args.repeat} run(s): "
          f"{statistics.median(totals):.3f} s  (runs: "
          + " / ".join(f"{t:.3f}" for t in totals) + ")")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""The Cramer-Rao bound on the noise terms of a record, from the Whittle
(spectral) likelihood: how precisely ANY unbiased estimator can find N, B,
K and a Gauss-Markov (sigma, Tc) from a record of a given length and rate.

    python3 bench/whittle_bound.py --N 0.3 --B 0.1 --K 0.02 --fs 100 --hours 2

Prints the standard deviation of the natural log of each parameter (about
its relative standard deviation when small) and the median absolute
relative error a Gaussian spread of that size gives (0.674 sd). The
validation study (docs/validation.md) compares foglab's spread over seeds
with it: where the two are close, a smaller error needs a longer record,
not a better estimator.

The PSD is IEEE Std 952's (one-sided, the convention in which white noise
of coefficient N has S = N^2 and sigma^2(tau) = N^2/tau): S(f) = N^2 +
B^2/(2 pi f) + (K/(2 pi))^2/f^2 + 2 sigma^2 Tc/(1 + (2 pi f Tc)^2). The
Whittle Fisher information of parameter vector theta over the Fourier
frequencies f_k = k/T, k = 1..n/2, is sum_k d ln S_k/d theta_i d ln S_k/d
theta_j (Whittle 1953; e.g. Percival and Walden, "Spectral Analysis for
Physical Applications", 1993, sec. 6.6). Asymptotic: it ignores leakage at
the lowest frequencies and the filters of a real sensor.
"""
import argparse
import math


def invert(a):
    """Gauss-Jordan inverse of a small dense matrix (lists)."""
    n = len(a)
    m = [row[:] + [float(i == j) for j in range(n)] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        pivot = m[c][c]
        m[c] = [x / pivot for x in m[c]]
        for r in range(n):
            if r != c:
                f = m[r][c]
                m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    return [row[n:] for row in m]


def bound(n_coef, b, k, sigma, tc, fs_hz, hours):
    """{name: sd of ln(parameter)} for the parameters that are > 0."""
    names = [name for name, v in (("N", n_coef), ("B", b), ("K", k), ("gm_sigma", sigma))
             if v > 0]
    if sigma > 0:
        names.append("gm_tc")
    samples = int(fs_hz * hours * 3600.0)
    span_s = samples / fs_hz
    info = [[0.0] * len(names) for _ in names]
    for j in range(1, samples // 2 + 1):
        f = j / span_s
        white = n_coef * n_coef
        flicker = b * b / (2.0 * math.pi * f)
        walk = (k / (2.0 * math.pi)) ** 2 / (f * f)
        w = 2.0 * math.pi * f * tc
        gm = 2.0 * sigma * sigma * tc / (1.0 + w * w) if sigma > 0 else 0.0
        s = white + flicker + walk + gm
        # d S / d ln(parameter): 2 x the term for a coefficient (S ~ c^2)
        grad = {"N": 2 * white, "B": 2 * flicker, "K": 2 * walk, "gm_sigma": 2 * gm,
                "gm_tc": gm * (1.0 - 2.0 * w * w / (1.0 + w * w))}
        d = [grad[name] / s for name in names]
        for a in range(len(names)):
            for c in range(len(names)):
                info[a][c] += d[a] * d[c]
    cov = invert(info)
    return {name: math.sqrt(cov[i][i]) for i, name in enumerate(names)}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--N", type=float, required=True, help="deg/h/sqrt(Hz)")
    p.add_argument("--B", type=float, default=0.0, help="deg/h")
    p.add_argument("--K", type=float, default=0.0, help="deg/h/sqrt(s)")
    p.add_argument("--gm-sigma", type=float, default=0.0, help="deg/h")
    p.add_argument("--gm-tc", type=float, default=0.0, help="s")
    p.add_argument("--fs", type=float, default=100.0, help="Hz")
    p.add_argument("--hours", type=float, default=2.0)
    a = p.parse_args()
    if a.gm_sigma > 0 and not a.gm_tc > 0:
        p.error("--gm-sigma needs --gm-tc > 0")
    for name, sd in bound(a.N, a.B, a.K, a.gm_sigma, a.gm_tc, a.fs, a.hours).items():
        print(f"{name:9s} sd of ln: {100 * sd:6.2f} %   median |relative error| >= "
              f"{100 * 0.674 * sd:6.2f} %")


if __name__ == "__main__":
    main()

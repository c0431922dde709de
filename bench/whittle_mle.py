#!/usr/bin/python3
"""The spectral (Whittle) maximum-likelihood estimate of N, B and K on
generated records, beside foglab's fit on the same records: an estimator
outside the Allan family, to tell a record's luck from an estimator's fault.

    /usr/bin/python3 bench/whittle_mle.py BUILD/apps/foglab/foglab --grade mems --seeds 1-10

For each seed it generates the grade's record (bench/effects_study.py's
grades, 2 h at 100 Hz, no effect), runs `foglab analyze` on it, and
maximises the Whittle likelihood of the record's periodogram under the
true model's form (Whittle 1953; Percival and Walden, "Spectral Analysis
for Physical Applications", 1993, sec. 6.6):

    -ln L = sum_k [ln S(f_k) + I(f_k) / S(f_k)],
    S(f) = N^2 + B^2 / (2 pi f) + (K / (2 pi))^2 / f^2

(the two-sided PSD in which white noise of coefficient N has S = N^2 and
sigma^2(tau) = N^2 / tau, flicker the plateau 2 ln 2 B^2 / pi and a random
walk K^2 tau / 3; IEEE Std 952-1997, Annex C). Fisher scoring on the logs
of the squared coefficients. Without K the periodogram is the record's
own, mean removed (a flat white floor leaks nothing into the lowest
frequencies); with K the record is differenced first, so that the random
walk becomes stationary, and tapered (Hann), so that the differenced white
noise, which rises towards the Nyquist frequency, does not leak into the
lowest frequencies (without the taper K came out 10-270 % high); the model
is then 4 sin^2(pi f / fs) S(f). Both skip the first two Fourier
frequencies. With the taper neighbouring ordinates are correlated and the
estimate is less efficient than the bound (bench/whittle_bound.py).

It prints, per seed, ln(estimate / truth) in % for both and the fit's
model; then the median absolute relative error of each term.

With --effect and --passband-to F_HZ it asks what a record holds of N
behind a filter of unknown kind (docs/validation.md, "N behind a filter
no kind follows"): the white term's shape is left free near DC, as any
low-pass filter's power response is there,

    |H(f)|^2 = 1 + a1 f^2 + a2 f^4 + ...   (even in f, |H(0)| = 1),

so S(f) = N^2 (1 + a1 f^2 + a2 f^4) + the other terms, fitted to the
Fourier frequencies up to F_HZ only (Fisher scoring on the squared
coefficients, which enter S linearly; a1 and a2 may take either sign).
The spread of N over seeds is then what a 'kind-free' estimator gets:
the bias of the truncated expansion against its variance, as F_HZ moves.

Needs numpy (python3-numpy, installed by scripts/install-deps.sh; run it
with the system Python). The generated files go to a temporary folder and are
removed. Results: docs/validation.md ("What a 2 h record holds").
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from effects_study import FS_HZ, GRADES, HOURS, effects  # noqa: E402

TERMS = ("N", "B", "K")


def periodogram(rate, fs_hz, difference):
    """(frequencies [Hz], ordinates [(deg/h)^2/Hz], the model's factor on S)."""
    x = np.diff(rate) if difference else rate - np.mean(rate)
    n = len(x)
    window = np.hanning(n) if difference else np.ones(n)
    spectrum = np.fft.rfft(x * window)
    k = np.arange(2, n // 2)
    f = k * fs_hz / n
    ordinates = np.abs(spectrum[2:n // 2]) ** 2 / (np.sum(window * window) * fs_hz)
    factor = 4.0 * np.sin(np.pi * f / fs_hz) ** 2 if difference else np.ones_like(f)
    return f, ordinates, factor


def whittle(rate, fs_hz, terms, start):
    """{term: estimate} maximising the Whittle likelihood; `start` {term: value}."""
    f, ordinates, factor = periodogram(rate, fs_hz, "K" in terms)
    shapes = {"N": factor, "B": factor / (2 * np.pi * f), "K": factor / (2 * np.pi * f) ** 2}
    g = np.array([shapes[t] for t in terms])
    theta = np.array([math.log(start[t] ** 2) for t in terms])
    for _ in range(200):
        parts = np.exp(theta)[:, None] * g
        s = parts.sum(0)
        share = parts / s
        score = (share * (ordinates / s - 1.0)).sum(1)
        step = np.linalg.solve(share @ share.T, score)
        theta += np.clip(step, -1.0, 1.0)
        if np.max(np.abs(step)) < 1e-9:
            break
    else:
        raise RuntimeError("Fisher scoring did not converge in 200 steps")
    return {t: math.sqrt(math.exp(theta[i])) for i, t in enumerate(terms)}


def passband_whittle(rate, fs_hz, terms, to_hz, orders=2):
    """{term: estimate} with N's shape free near DC: S(f) = sum_i c_i g_i(f),
    N^2's g times f^(2j), j = 0..orders, fitted over f <= to_hz; Fisher
    scoring on the c_i (linear in S)."""
    f, ordinates, factor = periodogram(rate, fs_hz, "K" in terms)
    keep = f <= to_hz
    f, ordinates, factor = f[keep], ordinates[keep], factor[keep]
    shapes = [factor * f ** (2 * j) for j in range(orders + 1)]
    names = ["N"] + [f"a{j}" for j in range(1, orders + 1)]
    if "B" in terms:
        shapes.append(factor / (2 * np.pi * f))
        names.append("B")
    if "K" in terms:
        shapes.append(factor / (2 * np.pi * f) ** 2)
        names.append("K")
    g = np.array(shapes)

    def deviance(c):
        s = g.T @ c
        return np.sum(np.log(s) + ordinates / s) if np.all(s > 0) else math.inf

    # start: the white level alone at the mean ordinate, every other term 0
    c = np.zeros(len(names))
    c[0] = ordinates.mean() / factor.mean()
    here = deviance(c)
    for _ in range(500):
        s = g.T @ c
        score = (g * ((ordinates - s) / s ** 2)).sum(1)
        step = np.linalg.solve((g / s) @ (g / s).T, score)
        for _ in range(60):  # halve the step until S stays positive and -ln L falls
            there = deviance(c + step)
            if there <= here:
                break
            step /= 2
        c, drop, here = c + step, here - there, there
        if drop < 1e-9:
            break
    else:
        raise RuntimeError("Fisher scoring did not converge in 500 steps")
    return {t: math.sqrt(max(c[names.index(t)], 0.0)) for t in terms}


def one_seed(foglab, workdir, grade_name, seed, effect_args=(), fs_hz=FS_HZ, hours=HOURS,
             passband_to=None):
    grade = GRADES[grade_name]
    stem = os.path.join(workdir, f"{grade_name}_{seed}")
    model = [a for k, v in grade.items() for a in (f"--{k}", str(v))]
    subprocess.run([foglab, "generate", *model, *effect_args, "--fs", f"{fs_hz:g}",
                    "--hours", f"{hours:g}", "--seed", str(seed), "--out", stem + ".csv"],
                   check=True, capture_output=True)
    fit = json.loads(subprocess.run([foglab, "analyze", stem + ".csv", "--json", "-"], check=True,
                                    capture_output=True, text=True).stdout)
    # the generated CSV: a comment line, the header (t, rate, temperature), the samples
    rate = np.loadtxt(stem + ".csv", delimiter=",", skiprows=2, usecols=1)
    os.remove(stem + ".csv")
    terms = [t for t in TERMS if grade.get(t, 0.0) > 0.0]
    if passband_to is None:
        mle = whittle(rate, fs_hz, terms, {t: grade[t] for t in terms})
    else:
        mle = passband_whittle(rate, fs_hz, terms, passband_to)
    fitted = {}
    for t in terms:
        entry = fit["noise_model"][t]
        fitted[t] = entry["value"] if entry["status"] == "resolved" else None
    return mle, fitted, fit["fit"]["terms"]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("foglab", help="the foglab binary")
    p.add_argument("--grade", required=True, choices=[g for g, v in GRADES.items()
                                                       if not any(k.startswith("gm") for k in v)])
    p.add_argument("--seeds", default="1-10", help="FIRST-LAST")
    p.add_argument("--effect", default="none", help="one of bench/effects_study.py's effects")
    p.add_argument("--fs", type=float, default=FS_HZ, help="sample rate, Hz (default %(default)g)")
    p.add_argument("--hours", type=float, default=HOURS,
                   help="record length, h (default %(default)g)")
    p.add_argument("--passband-to", type=float, metavar="F_HZ",
                   help="leave N's shape free near DC and fit up to F_HZ only")
    args = p.parse_args()
    effect_args = effects(GRADES[args.grade], args.fs, args.hours)[args.effect]
    first, last = (int(s) for s in args.seeds.split("-"))
    grade = GRADES[args.grade]
    terms = [t for t in TERMS if grade.get(t, 0.0) > 0.0]
    errors = {"whittle": {t: [] for t in terms}, "fit": {t: [] for t in terms}}
    shape = (f", N's shape free below {args.passband_to:g} Hz" if args.passband_to else "")
    print(f"{args.grade}, {args.effect} ({args.hours:g} h at {args.fs:g} Hz{shape}), "
          "ln(estimate / truth) in %: Whittle | foglab's fit")
    with tempfile.TemporaryDirectory(prefix="foglab_whittle_") as workdir:
        for seed in range(first, last + 1):
            mle, fitted, model = one_seed(args.foglab, workdir, args.grade, seed, effect_args,
                                          args.fs, args.hours, args.passband_to)
            cells = []
            for t in terms:
                w = 100 * math.log(mle[t] / grade[t]) if mle[t] > 0 else -math.inf
                errors["whittle"][t].append(abs(mle[t] / grade[t] - 1))
                if fitted[t] is None:
                    errors["fit"][t].append(math.inf)
                    cells.append(f"{t} {w:+6.1f} | unresolved")
                else:
                    errors["fit"][t].append(abs(fitted[t] / grade[t] - 1))
                    cells.append(f"{t} {w:+6.1f} | {100 * math.log(fitted[t] / grade[t]):+6.1f}")
            print(f"seed {seed:4d}: " + "   ".join(cells) + f"   (fit: {model})", flush=True)
    print("median |relative error| %:")
    for t in terms:
        print(f"  {t}: Whittle {100 * statistics.median(errors['whittle'][t]):.2f}, "
              f"foglab's fit {100 * statistics.median(errors['fit'][t]):.2f}")


if __name__ == "__main__":
    main()

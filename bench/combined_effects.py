#!/usr/bin/env python3
"""Real-sensor effects in combination: several effects of the output chain
in one record, with and without a temperature law, on three grades;
`analyze` against the truth.

    python3 bench/combined_effects.py BUILD/apps/foglab/foglab [--seeds 3]

The effects study (bench/effects_study.py) puts one effect into each
record; real recordings carry several at once, and the detectors run one
after the other (the temperature channel's steps, the output word, spikes,
bias steps, the temperature law, the bandwidth, the lines), so each must
work on what the others leave. Per record it prints N's and B's error (and K's, when the grade has one; "!"
when the truth is outside the 95 % interval), the terms, what was found of
each effect against the truth (spikes and steps as found/true), and c1's
error in its standard errors where there is a temperature law. The closing
lines count the records where each held. Results go to docs/validation.md
by hand, with the date.
"""
import argparse
import concurrent.futures as cf
import subprocess
import sys
import tempfile

from effects_study import FS_HZ, GRADES, run

STUDY_GRADES = ("tactical-fog", "mems", "nav-fog")


def combinations(grade):
    """The effects per combination, sized as in effects_study (by the
    sample spread sd = N sqrt(fs)); the temperature laws are 30 B and 0.5 B
    per degC (and degC^2) over a 10 degC ramp, as in the issue-4 study."""
    sd = grade["N"] * FS_HZ ** 0.5
    b = grade["B"]
    ramp = ["--temperature", "ramp:10@20"]
    return {
        "ma4+lsb+spikes+step+gaps": [
            "--moving-average", "4", "--lsb", f"{0.5 * sd:.6g}", "--spikes", f"3:{20 * sd:.6g}",
            "--step", f"2000:{0.5 * sd:.6g}", "--drop", "600:30", "--drop", "5000:900"],
        "lowpass+lsb+sine": [
            "--filter-tc", "0.0054", "--lsb", f"{0.5 * sd:.6g}", "--sine", f"20:{3 * sd:.6g}"],
        "butterworth+sine+step": [
            "--butterworth", "25", "--sine", f"7.5:{2 * sd:.6g}", "--step", f"3000:{0.5 * sd:.6g}"],
        "ma8+spikes+lsb": [
            "--moving-average", "8", "--spikes", f"10:{20 * sd:.6g}", "--lsb", f"{0.3 * sd:.6g}"],
        "ramp(c1,c2)+steps": [
            *ramp, "--temp-coef", f"{30 * b:.6g},{0.5 * b:.6g}",
            "--step", f"2000:{0.5 * sd:.6g}", "--step", f"5000:{-0.4 * sd:.6g}"],
        "ramp(c1)+gaps+spikes": [
            *ramp, "--temp-coef", f"{30 * b:.6g}", "--drop", "600:30", "--drop", "5000:900",
            "--spikes", f"3:{20 * sd:.6g}"],
        # a temperature sensor read in steps of 0.25 degC (the rate follows
        # the temperature itself), with a step and a low-pass
        "ramp(c1,c2)+temp-lsb+step+lowpass": [
            *ramp, "--temp-coef", f"{30 * b:.6g},{0.5 * b:.6g}", "--temp-lsb", "0.25",
            "--step", f"3000:{0.5 * sd:.6g}", "--filter-tc", "0.0054"],
    }


def run_or_fail(foglab, workdir, grade_name, name, args, seed):
    """effects_study.run, with a failed run's last error line instead of an exception."""
    try:
        truth, r = run(foglab, workdir, grade_name, name, args, seed)
        return truth, r, []
    except subprocess.CalledProcessError as e:
        return None, None, (e.stderr or b"").decode(errors="replace").strip().splitlines()[-1:]


def judge(truth, r):
    """One line for the record and what held in it."""
    m, nm, out = truth["model"], r["noise_model"], truth["sensor_output"]
    held = {}
    parts = []
    for key in ("N", "B", "K"):
        true = m[key]
        if true <= 0:
            continue
        v = nm[key]["value"]
        lo, hi = nm[key]["ci95"] or (None, None)
        inside = lo is not None and lo <= true <= (hi if hi is not None else float("inf"))
        parts.append(f"{key} {100 * (v / true - 1):+.1f}%{'' if inside else '!'}"
                     if v else f"{key} none")
        if key == "N":
            held["N within 3 %"] = v is not None and abs(v / true - 1) <= 0.03
            held["N inside its interval"] = inside
    spikes = (r["spikes"]["count"], len(out["spike_times_s"]))
    steps = (r["steps"]["count"], len(out["steps"]))
    held["spikes as the truth"] = spikes[0] == spikes[1]
    held["steps as the truth"] = steps[0] == steps[1]
    held["gaps as the truth"] = r["input"]["gaps"]["count"] == len(out["dropouts"]["gaps"])
    line = (f"{' '.join(parts)}  terms {r['fit']['terms']}  spikes {spikes[0]}/{spikes[1]}  "
            f"steps {steps[0]}/{steps[1]}  lines {len(r['spectral_lines'])}/{len(out['sinusoids'])}"
            f"  bandwidth {r['sensor_bandwidth'].get('kind') if r['sensor_bandwidth']['resolved'] else '-'}"
            f"  class {r['accuracy_class']}")
    if truth["temperature"].get("lsb_c", 0) > 0:
        tq = r["temperature_quantisation"]
        held["temperature step found"] = (
            tq["detected"] and abs(tq["lsb_c"] / truth["temperature"]["lsb_c"] - 1) < 1e-6)
    coefs = m.get("temp_coefs") or []
    fit = r.get("systematic")
    if coefs and fit:
        z = (fit["coefficients"][1] - coefs[0]) / fit["standard_errors"][1]
        held["c1 within 3 standard errors"] = abs(z) <= 3
        line += f"  c1 {z:+.2f} se"
    return line, held


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("foglab")
    p.add_argument("--seeds", type=int, default=3)
    p.add_argument("--jobs", type=int, default=2)
    args = p.parse_args()
    work = tempfile.mkdtemp(prefix="foglab_combined_")
    tally = {}
    with cf.ThreadPoolExecutor(args.jobs) as pool:
        jobs = []
        for grade_name in STUDY_GRADES:
            for name, extra in combinations(GRADES[grade_name]).items():
                for seed in range(1, args.seeds + 1):
                    jobs.append((grade_name, name, seed, pool.submit(
                        run_or_fail, args.foglab, work, grade_name, name, extra, seed)))
        for grade_name, name, seed, job in jobs:
            truth, r, err = job.result()
            if r is None:
                print(f"{grade_name:13s} {name:26s} seed {seed}: failed: {err}")
                tally.setdefault("ran", [0, 0])[1] += 1
                continue
            line, held = judge(truth, r)
            print(f"{grade_name:13s} {name:26s} seed {seed}: {line}", flush=True)
            for what, ok in held.items():
                t = tally.setdefault(what, [0, 0])
                t[0] += ok
                t[1] += 1
    for what, (ok, total) in tally.items():
        print(f"{what}: {ok}/{total}")


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Issue 16's effects on real noise: known spikes, steps, gaps, a line and a
coarser output word put into the nine real channels.

    python3 bench/real_injected.py BUILD/apps/foglab/foglab [--data ../shared/data/real]

The effects study (bench/effects_study.py) puts each effect on foglab's own
generator, whose noise is exactly the fit's model. Here the noise is the
ADIS16405's: filtered, quantised to 0.05 deg/s, with the z axes' moving
20 Hz resonance. Each channel gets the effects study's effects, sized by
the channel's own sample spread sd and scaled to its 2.78 h:

- spikes: 3 single samples of 20 sd (+, -, +);
- steps: +0.5 sd at 2778 s and -0.4 sd at 4167 s;
- gaps: a time column with 3 gaps: 41.7 s at 833 s, 50 samples at 4167 s
  (where the second step is: with the gaps, a power glitch that lost half
  a second and came back with another bias, found as the bias's jump
  across the gap), 1250 s (1/8 of the record) at 8333 s;
- line: a sine of 3 sd amplitude at 7.3 Hz (away from the z axes'
  resonance and from the PSD's bins);
- slow-line: a sine of 80 deg/h amplitude (about three times the channels'
  bias instability) at 0.01 Hz, a thermal control cycle's kind: its
  Allan hump (at 37 s) lies where B and the random bias are read. It is
  smaller than half an output step, and the samples are already rounded
  (rounding the sum gives the clean record back), so this one is added
  off the grid: the output word's rounding then stays in N, as foglab
  takes it (its LSB is no longer found);
- lsb: the output word made 5 times coarser (0.25 deg/s; an odd factor, so
  that no sample lies half-way between two codes of the coarse grid);
- all: spikes, steps, gaps and the line together.

Every sum but the slow line's is rounded to the sensor's own 0.05 deg/s
grid, as its output word would be. Per record it prints whether the effect
was found (the count, and the times within a tolerance), and N, B and the
class against the clean record's. The derived files go to a temporary folder and are removed (the
data's licence: never into the repository).
"""
import concurrent.futures as cf
import json
import math
import os
import subprocess
import tempfile

from real_variants import AXES, read_channels, real_data_arguments

FS_HZ = 100.0
LSB_DPS = 0.05
LINE_HZ = 7.3
SLOW_LINE_HZ, SLOW_LINE_DPS = 0.01, 80.0 / 3600.0
COARSE = 5  # the coarser output word, in the sensor's steps
SPIKES = ((123457, 20.0), (456791, -20.0), (789013, 20.0))  # sample, size in sd
STEPS_S = ((2778.0, 0.5), (4167.0, -0.4))                   # time, size in sd
GAPS_S = ((833.0, 41.7), (4167.0, 0.5), (8333.0, 1250.0))   # start, length


def on_grid(v, lsb=LSB_DPS):
    return round(v / lsb) * lsb


def spread(x):
    mean = sum(x) / len(x)
    return math.sqrt(sum((v - mean) ** 2 for v in x) / (len(x) - 1))


def with_effects(x, sd, spikes=False, steps=False, line=False, slow_line=False):
    y = list(x)
    if slow_line:
        y = [v + SLOW_LINE_DPS * math.sin(2 * math.pi * SLOW_LINE_HZ * i / FS_HZ + 0.3)
             for i, v in enumerate(y)]
    if steps:
        for t, size in STEPS_S:
            jump = on_grid(size * sd)
            for i in range(int(t * FS_HZ), len(y)):
                y[i] += jump
    if line:
        amplitude = 3 * sd
        y = [v + on_grid(amplitude * math.sin(2 * math.pi * LINE_HZ * i / FS_HZ + 0.3))
             for i, v in enumerate(y)]
    if spikes:
        for i, size in SPIKES:
            y[i] += on_grid(size * sd)
    return y


def write(path, values, gaps=False):
    with open(path, "w") as f:
        if not gaps:
            f.write("rate_dps\n")
            for v in values:
                f.write(f"{v:.9g}\n")
            return
        dropped = [(int(s * FS_HZ), int((s + n) * FS_HZ)) for s, n in GAPS_S]
        f.write("time_s,rate_dps\n")
        for i, v in enumerate(values):
            if not any(a <= i < b for a, b in dropped):
                f.write(f"{i / FS_HZ:.2f},{v:.9g}\n")


def analyse(foglab, path, fs):
    """`analyze --json -`; without `fs` the time column gives the rate (and the gaps)."""
    rate = ["--fs", str(fs)] if fs else []
    r = subprocess.run([foglab, "analyze", path, *rate, "--units", "deg/s", "--json", "-"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return {"error": r.stderr.strip()}
    return json.loads(r.stdout)


def in_gap(t_s):
    return any(start <= t_s < start + length for start, length in GAPS_S)


def found(effect, j, clean, sd):
    """What was found of the effect, and whether it is what was put in. With
    the gaps ("all"), a step where a gap starts is the bias's jump across
    it (`steps.across_gaps`); where no step is, no jump is significant."""
    notes, ok = [], True
    gaps = effect == "all"
    if effect in ("spikes", "all"):
        times = sorted(j["spikes"]["times_s"])
        want = [i / FS_HZ for i, _ in SPIKES]
        hit = len(times) == len(want) and all(abs(a - b) < 0.015 for a, b in zip(times, want))
        notes.append(f"spikes {len(times)}/{len(want)}")
        ok &= hit
    if effect in ("steps", "all"):
        # a step the clean record has (imu1 y: -304 deg/h at 6.8 s) is the sensor's
        steps = [(t, size) for t, size in zip(j["steps"]["times_s"], j["steps"]["sizes_deg_h"])
                 if all(abs(t - c) > 5 for c in clean["steps"]["times_s"])]
        across = [(g["time_s"], g["size_deg_h"]) for g in j["steps"]["across_gaps"] if g["significant"]]
        want = [(t, on_grid(size * sd) * 3600) for t, size in STEPS_S]
        want_across = [(t, size) for t, size in want if gaps and in_gap(t)]
        want = [w for w in want if w not in want_across]

        def match(got, put, time_tolerance_s):
            return len(got) == len(put) and all(
                abs(t - tp) < time_tolerance_s and abs(size / sp - 1) < 0.25
                for (t, size), (tp, sp) in zip(got, put))

        # a jump across a gap is dated where the record resumes
        ok &= match(steps, want, 5) and match(across, want_across, 1e9)
        listed = lambda pairs: ", ".join(f"{t:.0f} s {size:+.0f}" for t, size in pairs) or "none"
        notes.append(f"steps {listed(steps)} (put in {listed(want)} deg/h)")
        if gaps:
            notes.append(f"across gaps {listed(across)} (put in {listed(want_across)})")
    if effect in ("gaps", "all"):
        count = j["input"]["gaps"]["count"]
        notes.append(f"gaps {count}/{len(GAPS_S)}")
        ok &= count == len(GAPS_S)
    if effect == "gaps":
        jumps = [g["significance"] for g in j["steps"]["across_gaps"]]
        notes.append("jumps across them " + ", ".join(f"{z:.1f}" for z in jumps) + " spreads")
        ok &= not any(g["significant"] for g in j["steps"]["across_gaps"])
    if effect in ("line", "all", "slow-line"):
        # the lines of the clean record (the z axes' resonance) are found again, within 0.5 Hz
        before = [l["frequency_hz"] for l in clean["spectral_lines"]]
        new = [l for l in j["spectral_lines"] if all(abs(l["frequency_hz"] - f) > 0.5 for f in before)]
        if effect == "slow-line":
            hit = len(new) == 1 and abs(new[0]["frequency_hz"] / SLOW_LINE_HZ - 1) < 0.01
            notes.append("line " + (", ".join(f"{l['frequency_hz']:.4g} Hz, {l['rms_deg_h']:.1f} "
                                              f"deg/h rms" for l in new) or "none")
                         + f" (put in {SLOW_LINE_DPS * 3600 / math.sqrt(2):.1f})")
        else:
            hit = len(new) == 1 and abs(new[0]["frequency_hz"] - LINE_HZ) < 0.05
            notes.append("line " + (", ".join(f"{l['frequency_hz']:.2f} Hz" for l in new) or "none"))
        ok &= hit
    if effect == "lsb":
        q = j["output_quantisation"]
        lsb = q["lsb_deg_h"] if q["detected"] else None
        notes.append(f"LSB {lsb} deg/h")
        ok &= lsb is not None and abs(lsb / (COARSE * LSB_DPS * 3600) - 1) < 1e-6
    return ok, "; ".join(notes)


def inside(interval, value):
    lo, hi = interval or (None, None)
    return value is not None and lo is not None and lo <= value <= (hi if hi is not None else math.inf)


def compare(j, clean):
    """N's and B's change from the clean record, and whether the record's
    own 95 % interval holds the clean record's value."""
    nm, cm = j["noise_model"], clean["noise_model"]
    n_diff = nm["N"]["value"] / cm["N"]["value"] - 1
    b, cb = nm["B"]["value"], cm["B"]["value"]
    b_diff = b / cb - 1 if b and cb else float("nan")
    return (n_diff, inside(nm["N"]["ci95"], cm["N"]["value"]), b_diff,
            inside(nm["B"]["ci95"], cb), j["accuracy_class"] == clean["accuracy_class"])


def main():
    args = real_data_arguments()
    effects = ["clean", "spikes", "steps", "gaps", "line", "slow-line", "lsb", "all"]
    tmp = tempfile.mkdtemp(prefix="foglab_real_injected_")
    jobs, sds = [], {}
    for imu in (1, 2, 3):
        _, rows = read_channels(os.path.join(args.data, f"adis_16405_imu{imu}_gyro.csv"))
        for k, axis in enumerate(AXES):
            x = [r[k] for r in rows]
            sd = spread(x)
            channel = f"imu{imu} {axis}"
            sds[channel] = sd
            for effect in effects:
                if effect == "lsb":
                    y = [on_grid(v, COARSE * LSB_DPS) for v in x]
                else:
                    y = with_effects(x, sd, spikes=effect in ("spikes", "all"),
                                     steps=effect in ("steps", "all"), line=effect in ("line", "all"),
                                     slow_line=effect == "slow-line")
                path = os.path.join(tmp, f"imu{imu}_{axis}_{effect}.csv")
                write(path, y, gaps=effect in ("gaps", "all"))
                # a time column gives the rate where there are gaps
                jobs.append((channel, effect, path, None if effect in ("gaps", "all") else FS_HZ))

    with cf.ThreadPoolExecutor(args.jobs) as ex:
        results = list(ex.map(lambda job: analyse(args.foglab, job[2], job[3]), jobs))
    for job in jobs:
        os.remove(job[2])
    os.rmdir(tmp)

    by = {(c, e): r for (c, e, _, _), r in zip(jobs, results)}
    print("| channel | effect | found | what was found | N vs clean (clean N in the interval) "
          "| B vs clean (clean B in the interval) | class as clean |")
    print("|---|---|---|---|---|---|---|")
    tally = {e: [0, 0, 0, 0, 0] for e in effects[1:]}  # found, N within 1 %, N held, B held, class
    for channel in sds:
        clean = by[(channel, "clean")]
        if "error" in clean:
            print(f"| {channel} | clean | error: {clean['error']} |")
            continue
        for effect in effects[1:]:
            j = by[(channel, effect)]
            if "error" in j:
                print(f"| {channel} | {effect} | error: {j['error']} |")
                continue
            ok, text = found(effect, j, clean, sds[channel])
            n_diff, n_held, b_diff, b_held, same_class = compare(j, clean)
            yes = lambda flag: "yes" if flag else "NO"
            print(f"| {channel} | {effect} | {yes(ok)} | {text} | {n_diff:+.2%} ({yes(n_held)}) "
                  f"| {b_diff:+.1%} ({yes(b_held)}) | {yes(same_class)} |")
            for i, flag in enumerate((ok, abs(n_diff) <= 0.01, n_held, b_held, same_class)):
                tally[effect][i] += flag
    print()
    print("| effect | found | N within 1 % of clean | its N interval holds clean N | its B interval holds "
          "clean B | class as clean |")
    print("|---|---|---|---|---|---|")
    for effect, counts in tally.items():
        print("| " + " | ".join([effect] + [f"{c}/{len(sds)}" for c in counts]) + " |")


if __name__ == "__main__":
    main()

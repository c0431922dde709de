#!/usr/bin/env bash
# Part of the test command (README): builds the library, the CLI, the tests
# and the libFuzzer targets with clang-14, AddressSanitizer and
# UndefinedBehaviorSanitizer (CMakePresets.json "asan", build-asan/), then
# runs the unit and CLI tests under them with leak checking, and each fuzz
# target's smoke run (FuzzSmoke.*: its kept regression inputs, then
# FOGLAB_FUZZ_SECONDS of fuzzing, default 20). Not built here
# (tests/CMakeLists.txt): the 10^9-sample test, which needs 8 GB before
# ASan's shadow memory, and the browser tests, which only render what the
# other tests checked. Left out (CMakePresets.json, the asan test preset's
# exclude): the statistical cases that run a path another
# kept case runs, only on other numbers (these cost 15-100 s each under ASan
# and run in the Release half): seven of Bandwidth's ten (the flicker one,
# the 1 Hz union over the memory constants and the 40-sample moving average
# stay, and SensorEffects' filter cases, its Butterworth among them, which
# also run the fit that assumes no filter kind), the
# Wiener random bias named over six seeds (NoiseFit's Wiener round trip
# stays), eq. (17) on five generated records (every analysis computes it;
# PsdAllan's closed-form cases stay), the library's triad (CliCalibrate's
# triad stays), SpectralLine's broad line, lab2's default and --no-answers
# runs (the generated variant and the lab's files stay), eight of the nine
# ADIS16405 channels (imu1_x stays) and the eighteen records derived from
# them, two of AllanTheory's 2^20-sample loops over all eleven statistics
# (their kernels run under ASan in the kernel, gap and Stable32 tests), two
# of Systematic's three scatter studies (the white-noise one stays), the
# Allan covariance's Monte Carlo, and calibrate's two coverage studies over
# seeds (the CLI tests run its generalised least squares, triads and optics
# once each), and three CLI runs whose paths other kept cases take under
# ASan (the fleet's interrupted batch, 80 s: the batch and its resume run in
# CliBatch's and CliInterrupt's other cases; the real three-axis IMU run and
# the bag analysed against every axis, 40 and 33 s: CliImu's CSV cases and
# RosbagTest's bag parsing stay), and two studies over seeds: six ramp
# records never set aside (RecordTrend's scatter case stays) and ten
# white-noise records resolving no other term (NoiseFit's round trips run
# the same fit).
# Needs clang-14, libclang-rt-14-dev, libomp-14-dev (install-deps.sh --tests).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset asan >/dev/null
cmake --build --preset asan
ctest --preset asan

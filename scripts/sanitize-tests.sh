#!/usr/bin/env bash
# Part of the test command (README): builds the library, the CLI, the tests
# and the libFuzzer targets with clang-14, AddressSanitizer and
# UndefinedBehaviorSanitizer (CMakePresets.json "asan", build-asan/), then
# runs the unit and CLI tests under them with leak checking, and each fuzz
# target's smoke run (FuzzSmoke.*: its kept regression inputs, then
# FOGLAB_FUZZ_SECONDS of fuzzing, default 20). The 10^9-sample test and the
# browser test are left out: the first needs 8 GB before ASan's shadow
# memory, the second only renders what the other tests already checked.
# Needs clang-14, libclang-rt-14-dev, libomp-14-dev (install-deps.sh --tests).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset asan >/dev/null
cmake --build --preset asan
ctest --preset asan

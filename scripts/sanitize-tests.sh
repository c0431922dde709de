#!/usr/bin/env bash
# Builds the library, the CLI and the tests with AddressSanitizer and
# UndefinedBehaviorSanitizer (CMakePresets.json "asan", build-asan/) and runs
# the unit and CLI tests under them (the 10^9-sample test and the browser
# test are left out: the first needs 8 GB before ASan's shadow memory, the
# second only renders what the other tests already checked).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset asan >/dev/null
cmake --build --preset asan
ctest --preset asan

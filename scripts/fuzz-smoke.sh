#!/usr/bin/env bash
# Fuzzes longer than the test command does: builds only the libFuzzer
# targets of the "asan" preset (clang-14, ASan + UBSan, build-asan/) and runs
# their FuzzSmoke.* tests (fuzz/smoke.sh) for FOGLAB_FUZZ_SECONDS each
# (default 300 here). A finding is left as build-asan/fuzz/findings/
# <target>-crash-*: fix the bug and keep the input in fuzz/regressions/<target>/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --fuzz
export FOGLAB_FUZZ_SECONDS=${FOGLAB_FUZZ_SECONDS:-300}
cmake --preset asan >/dev/null
cmake --build --preset asan --target fuzz_text_reader fuzz_mat_reader fuzz_options
ctest --preset asan -R '^FuzzSmoke\.' --timeout $((FOGLAB_FUZZ_SECONDS + 300))

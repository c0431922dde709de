#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang-14, AddressSanitizer and
# UndefinedBehaviorSanitizer in build-fuzz/, replays every kept regression
# input, then fuzzes each target for a short period (FOGLAB_FUZZ_SECONDS,
# default 30) starting from its seed corpus. Any crash, sanitizer report or
# exception other than foglab's usage/data errors fails the run; libFuzzer
# leaves the input as crash-* in build-fuzz/findings/: fix the bug and keep
# the input in fuzz/regressions/<target>/.
# Needs clang-14, libclang-rt-14-dev, libomp-14-dev (installed by
# scripts/install-deps.sh --fuzz, which this script runs).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --fuzz
seconds=${FOGLAB_FUZZ_SECONDS:-30}
build=build-fuzz
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
  -DFOGLAB_BUILD_FUZZ=ON -DFOGLAB_BUILD_TESTS=OFF -DFOGLAB_BUILD_BENCH=OFF \
  -DFOGLAB_BUILD_EXAMPLES=OFF >/dev/null
cmake --build "$build" -j2 --target fuzz_text_reader fuzz_mat_reader fuzz_options
mkdir -p "$build/findings"
# matio/HDF5 keep global state at exit (no leak checks here); a small
# quarantine keeps ASan from counting freed memory against the RSS limit;
# an impossible allocation returns NULL as glibc's would (matio checks it)
# instead of aborting, and libFuzzer judges memory by the RSS limit alone.
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:quarantine_size_mb=64:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
for target in text_reader mat_reader options; do
  exe="$build/fuzz/fuzz_$target"
  regressions=(fuzz/regressions/$target/*)
  if [ -e "${regressions[0]}" ]; then
    echo "fuzz_$target: replaying ${#regressions[@]} regression inputs"
    "$exe" -rss_limit_mb=4096 -malloc_limit_mb=1048576 "${regressions[@]}" >/dev/null \
      2>"$build/findings/$target.replay.log" ||
      { tail -40 "$build/findings/$target.replay.log"; exit 1; }
  fi
  corpus="$build/corpus/$target"
  mkdir -p "$corpus"
  echo "fuzz_$target: fuzzing for $seconds s"
  "$exe" "$corpus" "fuzz/corpus/$target" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=4096 -malloc_limit_mb=1048576 \
    -artifact_prefix="$build/findings/$target-" -print_final_stats=1 \
    >"$build/findings/$target.log" 2>&1 ||
    { tail -60 "$build/findings/$target.log"; exit 1; }
  grep -E "stat::number_of_executed_units|stat::new_units_added" "$build/findings/$target.log" |
    sed "s/^/  /"
done
echo "fuzz smoke: no findings"

#!/usr/bin/env bash
# One fuzz target's smoke run, as a CTest test (fuzz/CMakeLists.txt):
# replays every kept regression input, then fuzzes for FOGLAB_FUZZ_SECONDS
# (default 20) from the seed corpus. Any crash, sanitizer report or
# exception other than foglab's usage/data errors fails the test; libFuzzer
# leaves the input as <build>/findings/<target>-crash-*: fix the bug and keep
# the input in fuzz/regressions/<target>/.
# usage: smoke.sh EXE TARGET SOURCE_DIR BUILD_DIR
set -euo pipefail
exe=$1 target=$2 source=$3 build=$4
seconds=${FOGLAB_FUZZ_SECONDS:-20}
findings="$build/findings"
corpus="$build/corpus/$target"
mkdir -p "$findings" "$corpus"
# matio/HDF5 keep global state at exit (no leak checks here); a small
# quarantine keeps ASan from counting freed memory against the RSS limit;
# an allocation above 2 GB returns NULL, as on a machine without that much
# memory (matio checks it), instead of aborting; and libFuzzer judges memory
# by the RSS limit alone. (Without the 2 GB cap ASan would grant a 40 GB
# request that glibc refuses, and write its 5 GB of shadow: the RSS limit
# fails the run although the native build never touches the memory.)
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:quarantine_size_mb=64:allocator_may_return_null=1:max_allocation_size_mb=2048
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
limits=(-rss_limit_mb=4096 -malloc_limit_mb=1048576)

shopt -s nullglob
regressions=("$source/regressions/$target"/*)
if ((${#regressions[@]})); then
  echo "fuzz_$target: replaying ${#regressions[@]} regression inputs"
  "$exe" "${limits[@]}" "${regressions[@]}" >"$findings/$target.replay.log" 2>&1 ||
    { tail -40 "$findings/$target.replay.log"; exit 1; }
fi
echo "fuzz_$target: fuzzing for $seconds s"
"$exe" "$corpus" "$source/corpus/$target" -max_total_time="$seconds" -max_len=65536 "${limits[@]}" \
  -artifact_prefix="$findings/$target-" -print_final_stats=1 >"$findings/$target.log" 2>&1 ||
  { tail -60 "$findings/$target.log"; exit 1; }
grep -E "stat::number_of_executed_units|stat::new_units_added" "$findings/$target.log" | sed "s/^/  /"
echo "fuzz_$target: no findings"

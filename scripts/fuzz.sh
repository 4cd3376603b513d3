#!/usr/bin/env bash
# Fuzzes the scene-file loader and the narrowphase with libFuzzer for a time budget each, and the
# OBJ and PNG loaders (small, one library call each) for a third of it:
#   scripts/fuzz.sh [seconds per target, default 60]
# Builds build/fuzz with clang, the whole project instrumented for coverage and under ASan +
# UBSan (any UB aborts). Seeds come from fuzz/corpus/<target>/; inputs the fuzzer finds
# interesting go to build/fuzz/corpus/<target>/ (kept between runs, never into the tree).
# A finding stops the run with status 1 and leaves the input as build/fuzz/<target>-crash-*;
# replay it with build/fuzz/fuzz/<target> FILE, then turn it into a regression test in tests/.
# Warnings are not errors here: the GCC build of scripts/test.sh is the one that checks them.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
jobs="${TUMBLE_FUZZ_JOBS:-2}"
build=build/fuzz

if ! command -v clang++ >/dev/null; then
  echo "fuzz: clang++ not found; install Debian's clang package (scripts/install-deps.sh)" >&2
  exit 2
fi

cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link" \
  -DTUMBLE_FUZZ=ON -DTUMBLE_SANITIZE=ON \
  -DTUMBLE_BUILD_TESTS=OFF -DTUMBLE_BUILD_BENCH=OFF -DTUMBLE_BUILD_VALIDATION=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target narrowphase_fuzz scene_loader_fuzz obj_loader_fuzz \
  png_height_field_fuzz

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
status=0
for target in scene_loader_fuzz narrowphase_fuzz obj_loader_fuzz png_height_field_fuzz; do
  budget="$seconds"
  case "$target" in obj_loader_fuzz | png_height_field_fuzz) budget=$(( (seconds + 2) / 3 )) ;; esac
  seeds="fuzz/corpus/${target%_fuzz}"
  work="$build/corpus/${target%_fuzz}"
  mkdir -p "$work"
  echo "=== fuzz: $target for ${budget} s"
  # -rss_limit_mb: a scene may legally ask for many bodies; the target builds only small ones.
  # -timeout: a unit this slow is a hang (libccd's EPA once looped for ever). 30 s, not 10: a
  # legal but crowded scene can take seconds under the sanitizers on a loaded machine.
  if ! "$build/fuzz/$target" -max_total_time="$budget" -timeout=30 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="$build/$target-" "$work" "$seeds" \
      2>"$build/$target.log"; then
    status=1
    echo "fuzz: $target found something; see $build/$target.log and $build/$target-*" >&2
    tail -n 40 "$build/$target.log" >&2
  fi
  grep -E "^stat::number_of_executed_units|^stat::new_units_added|^Done" "$build/$target.log" || true
done
exit "$status"

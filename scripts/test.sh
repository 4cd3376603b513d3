#!/usr/bin/env bash
# The README's test command: installs what is missing, checks the formatting (clang-format 14),
# then builds and runs the whole test suite twice -- an optimised GCC build with warnings as
# errors, and an AddressSanitizer + UndefinedBehaviorSanitizer build -- and builds the tree with
# Clang, warnings as errors, as well. Set TUMBLE_SKIP_SANITIZERS=1 for the first build only,
# TUMBLE_SKIP_CLANG=1 to leave out the Clang build.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"
bash scripts/install-deps.sh
bash scripts/viewer-deps.sh

echo "=== formatting"
bash scripts/check-format.sh

presets=(ci)
if [ "${TUMBLE_SKIP_CLANG:-0}" != "1" ]; then presets+=(clang); fi
if [ "${TUMBLE_SKIP_SANITIZERS:-0}" != "1" ]; then presets+=(asan); fi
for preset in "${presets[@]}"; do
  cmake --preset "$preset" >/dev/null
  if [ "$preset" = clang ]; then
    # Clang's warnings are not GCC's: the build is the check. Its tests would repeat the GCC
    # build's, bar the golden trajectories, which are one compiler's (docs/determinism.md;
    # Clang 14's net-capture hash, at least, differs from GCC 12's).
    echo "=== build: $preset"
    cmake --build --preset "$preset" -j "$jobs"
    continue
  fi
  echo "=== build and test: $preset"
  cmake --build --preset "$preset" -j "$jobs"
  ctest --preset "$preset" -j "$jobs"
done

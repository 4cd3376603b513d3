#!/usr/bin/env bash
# The README's test command: installs what is missing, then builds and runs the whole test suite
# twice -- an optimised build with warnings as errors, and an AddressSanitizer +
# UndefinedBehaviorSanitizer build. Set TUMBLE_SKIP_SANITIZERS=1 for the first only.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"
bash scripts/install-deps.sh

presets=(ci)
if [ "${TUMBLE_SKIP_SANITIZERS:-0}" != "1" ]; then presets+=(asan); fi
for preset in "${presets[@]}"; do
  echo "=== build and test: $preset"
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j "$jobs"
  ctest --preset "$preset" -j "$jobs"
done

#!/usr/bin/env bash
# The README's demo command: installs what is missing, builds, and runs the main demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target tumble-demo -j "$(nproc)"
echo
./build/release/demos/tumble-demo

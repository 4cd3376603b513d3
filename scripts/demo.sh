#!/usr/bin/env bash
# The README's demo command: installs what is missing, builds, and runs the main demos: the
# T-handle's flips (conservation figures), then the `tumble` command on the pyramid scene, which
# prints its summary and draws it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target tumble-demo tumble-cli -j "$(nproc)"
echo
./build/release/demos/tumble-demo
echo
./build/release/demos/tumble run pyramid --picture build/pyramid.svg
echo "picture: build/pyramid.svg (the pyramid at the start, middle and end, side view)"

#!/usr/bin/env bash
# The README's demo command: installs what is missing, builds, and runs the main demos: the
# T-handle's flips (conservation figures), then the `tumble` command on the net-capture scene (the
# study's capture net wrapping a dustbin), which prints its summary, records the net's four
# corners, draws it and records it for the browser viewer (tumble view).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/viewer-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target tumble-demo tumble-cli -j "$(nproc)"
echo
./build/release/demos/tumble-demo
echo
./build/release/demos/tumble run net-capture --picture build/net-capture.svg \
    --record build/net-corners.csv --replay build/net-capture.tumble
echo "picture: build/net-capture.svg (the net at 0, 0.35, 0.6 and 3 s, side view: it lands on"
echo "the dustbin's lid and wraps down its sides; lines: the four corners' paths)"
echo "corner trajectories: build/net-corners.csv"
echo "replay: build/net-capture.tumble; watch it in a browser (orbit, scrub, tensions, contacts):"
echo "    build/release/demos/tumble view build/net-capture.tumble"

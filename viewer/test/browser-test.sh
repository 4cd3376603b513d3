#!/usr/bin/env bash
# ctest viewer.browser: records one second of net-capture and checks the viewer on it in
# headless chromium (browser-test.mjs), leaving the screenshot at SCREENSHOT.
#   viewer/test/browser-test.sh TUMBLE WORKDIR SCREENSHOT.png
set -euo pipefail
tumble=$1 work=$2 screenshot=$3
mkdir -p "$work"
"$tumble" run net-capture --time 1 --replay-rate 30 -q --replay "$work/net-capture.tumble"
node "$(dirname "$0")/browser-test.mjs" "$tumble" "$work/net-capture.tumble" "$screenshot"

#!/usr/bin/env bash
# ctest viewer.gltf: exports net-capture (its net: a line mesh skinned to 400 nodes) and the
# pyramid as animated glTF and has Khronos' validator (npm gltf-validator) check them: 0 errors.
#   viewer/test/gltf-test.sh TUMBLE WORKDIR
set -euo pipefail
tumble=$1 work=$2
mkdir -p "$work"
"$tumble" run net-capture --time 1 -q --gltf "$work/net-capture.glb"
"$tumble" run pyramid --time 1 -q --gltf "$work/pyramid.glb"
node "$(dirname "$0")/../validate-gltf.mjs" "$work/net-capture.glb" "$work/pyramid.glb"

#!/usr/bin/env bash
# Installs the viewer's npm packages (three; playwright-core and gltf-validator for its tests)
# exactly as viewer/package-lock.json pins them, with `npm ci`; Debian's nodejs and npm first
# when there is no npm. Does nothing when node_modules already matches the lock file.
set -euo pipefail
cd "$(dirname "$0")/../viewer"
if ! command -v npm >/dev/null; then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -q
  $sudo apt-get install -y -q --no-install-recommends nodejs npm
fi
stamp=node_modules/.tumble-lock
if [ -f "$stamp" ] && cmp -s package-lock.json "$stamp"; then
  echo "viewer-deps: node_modules matches package-lock.json"
  exit 0
fi
npm ci --no-audit --no-fund
cp package-lock.json "$stamp"

#!/usr/bin/env bash
# Installs what Tumble needs to build, test and benchmark, from Debian 12's packages (run as root,
# or with sudo available). Does nothing when everything is already installed.
set -euo pipefail

packages=(
  build-essential cmake git pkg-config   # toolchain
  libeigen3-dev                          # linear algebra (Vec3, Quat, Mat3)
  libccd-dev                             # GJK/EPA/MPR narrowphase
  libqhull-dev                           # convex hulls (Qhull::qhull_r)
  nlohmann-json3-dev                     # JSON reports and scene files
  libtinyobjloader-dev libpng-dev        # scene files' OBJ meshes and PNG height fields (optional)
  libcli11-dev                           # command lines
  libgtest-dev libgmock-dev              # unit tests
  libbenchmark-dev                       # micro-benchmarks
  clang                                  # libFuzzer for scripts/fuzz.sh; the `clang` preset
  clang-format                           # scripts/check-format.sh (Debian 12: version 14)
  libbullet-dev libode-dev libbox2d-dev  # peer engines for tumble-bench (optional at configure)
  libmujoco-dev                          # MuJoCo 2.2, the fourth peer (optional at configure)
  python3-matplotlib                     # PNG plots of the sweeps and reports (/usr/bin/python3)
  openmpi-bin libopenmpi-dev             # tumble-sweep: studies across MPI ranks (optional)
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module (python/) and its tests
  chromium chromium-driver               # the viewer's browser test (scripts/viewer-deps.sh: npm)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"

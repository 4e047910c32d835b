// writePly(out, comment, properties, vertices, faces): a binary little-endian PLY of float vertex
// properties (e.g. ["x", "y", "z", "nx", "ny", "nz"], each vertex an array of that many numbers)
// and triangles (each three vertex indices), as aosuite's mesh reader takes it. converterInput:
// a converter's command line (IN OUT [SOURCE]) and IN's bytes, or one line on stderr and exit 1.
// Shared by stl_to_ply.js and module_to_ply.js, the converters scripts/fetch_assets.sh runs.
const fs = require("fs");

function writePly(out, comment, properties, vertices, faces) {
  const head = Buffer.from(["ply", "format binary_little_endian 1.0", "comment " + comment,
                            "element vertex " + vertices.length, ...properties.map((p) => "property float " + p),
                            "element face " + faces.length, "property list uchar int vertex_indices", "end_header", ""].join("\n"));
  const body = Buffer.alloc(4 * properties.length * vertices.length + 13 * faces.length);
  let o = 0;
  for (const v of vertices) for (const x of v) o = body.writeFloatLE(x, o);
  for (const f of faces) {
    o = body.writeUInt8(3, o);
    for (const i of f) o = body.writeInt32LE(i, o);
  }
  fs.writeFileSync(out, Buffer.concat([head, body]));
}

function converterInput(name, usage) {
  const [src, out, pkg = src] = process.argv.slice(2);
  const fail = (why) => {
    process.stderr.write(`${name}: ${why}\n`);
    process.exit(1);
  };
  if (!src || !out) fail(`usage: node scripts/${name}.js ${usage}`);
  try {
    return { src, out, pkg, fail, bytes: fs.readFileSync(src) };
  } catch (e) {
    return fail(`${src}: ${e.code === "ENOENT" ? "no such file" : e.message}`);
  }
}

module.exports = { writePly, converterInput };

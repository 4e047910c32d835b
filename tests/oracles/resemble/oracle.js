// Runs the real Resemble.js 5.0.0 in headless Chromium on the PNG pairs of a batch file and
// prints one JSON line per pair, in input order. Started by ./resemble-oracle, which installs
// the pinned npm packages and names their folder in AOSUITE_ORACLE_MODULES.
//
//   resemble-oracle --batch FILE [--stats]
//
// A batch line is a JSON object: "a", "b" (PNG paths), "id", and Resemble.js's own options in
// its own shapes: "mode" (nothing|less|colors|antialiasing|alpha, Resemble's `ignore`; absent
// or "default" calls none), "largeImageThreshold", "errorType", "errorColor", "transparency",
// "boundingBoxes", "ignoredBoxes", "ignoreAreasColoredWith" (its `output` settings),
// "returnEarlyThreshold", "tolerance"; and "diffRaw": where to write the diff image's pixels.
// Out: {"id", "misMatchPercentage", "rawMisMatchPercentage", "isSameDimensions",
// "dimensionDifference", "diffBounds"} as Resemble.js returns them, or {"id", "error"} (the
// exit status is then 1). --stats prints the throughput to stderr.
//
// How Resemble.js is driven, so that its answers are the library's and nothing else's:
//  * A loopback-only HTTP server (127.0.0.1, ephemeral port) serves the page and resemble.js,
//    nothing else. Resemble.js gets the two PNGs as data: URLs, as a page would call
//    resemble.compare(urlA, urlB, ...) (1.5 times as fast as fetching them from the server).
//  * Both images are loaded before the compare, with Resemble's own crossorigin setting, so its
//    `img.src = url` finds them decoded and completes synchronously in argument order: image 1
//    is A and dimensionDifference is A - B. (Resemble otherwise takes the images in the order
//    their loads finish.) A compare that did not finish synchronously is reported as an error.
//  * The diff image: Resemble fills an ImageData and only in getImageDataUrl() puts it on a
//    canvas, which premultiplies alpha (lossy below 255) before encoding a PNG. putImageData is
//    intercepted there to take the buffer itself; the PNG round trip is skipped.
//  * Resemble sees each PNG through drawImage + getImageData, so Chromium's premultiplication
//    of pixels with alpha < 255 is part of its answer (compare/canvas_alpha.hpp models it; the
//    test's translucent pairs compare with CanvasAlpha::kChromium). Colour management is pinned
//    to sRGB; the test's PNGs carry no colour chunks, so Chromium decodes them unchanged.
"use strict";

const fs = require("fs");
const http = require("http");
const path = require("path");
const { createRequire } = require("module");

const CHUNK_PAIRS = 32, CHUNK_BYTES = 8 << 20;  // at most per page.evaluate call

function die(msg) {
  process.stderr.write("resemble-oracle: " + msg + "\n");
  process.exit(2);
}

if (!process.env.AOSUITE_ORACLE_MODULES) die("run me through ./resemble-oracle");
const req = createRequire(path.join(path.resolve(process.env.AOSUITE_ORACLE_MODULES), "x.js"));

// Runs in the page: compares jobs [{urlA, urlB, opt, wantDiff}] one after another.
async function comparePairs(jobs) {
  const load = (url, name) =>
    new Promise((resolve, reject) => {
      const im = new Image();
      im.setAttribute("crossorigin", "anonymous");  // as Resemble's loadImageData
      im.onload = () => resolve(im);
      im.onerror = () => reject(new Error("Chromium cannot decode image " + name));
      im.src = url;
    });
  const base64 = (u8) => {
    let s = "";
    for (let i = 0; i < u8.length; i += 0x8000) {
      s += String.fromCharCode.apply(null, u8.subarray(i, i + 0x8000));
    }
    return btoa(s);
  };
  const proto = CanvasRenderingContext2D.prototype;
  const put = proto.putImageData;
  const out = [];
  for (const job of jobs) {
    if (job.error) {
      out.push({ error: job.error });
      continue;
    }
    try {
      await load(job.urlA, "A");  // now in Chromium's list of available images: Resemble's own
      await load(job.urlB, "B");  // loads of these URLs complete at once, in argument order
      let result = null;
      resemble.compare(job.urlA, job.urlB, job.opt, (err, data) => {
        if (err) {
          result = { error: String(err) };
          return;
        }
        result = {
          misMatchPercentage: data.misMatchPercentage,
          rawMisMatchPercentage: data.rawMisMatchPercentage,
          isSameDimensions: data.isSameDimensions,
          dimensionDifference: data.dimensionDifference,
          diffBounds: data.diffBounds,
        };
        if (!job.wantDiff) return;
        const taken = {};
        proto.putImageData = function (imgd) {
          taken.w = imgd.width;
          taken.h = imgd.height;
          taken.rgba = base64(new Uint8Array(imgd.data.buffer));
          throw taken;  // skip the canvas round trip and PNG encoding
        };
        try {
          data.getImageDataUrl();
        } catch (e) {
          if (e !== taken) throw e;
        } finally {
          proto.putImageData = put;
        }
        result.diff = taken;
      });
      out.push(result || { error: "Resemble.js did not finish synchronously: image order unknown" });
    } catch (e) {
      out.push({ error: String(e && e.message ? e.message : e) });
    }
  }
  return out;
}

// Resemble.compare's options object for one batch line.
function resembleOptions(p) {
  const opt = { output: {} };
  for (const k of ["largeImageThreshold", "errorType", "errorColor", "transparency",
                   "boundingBoxes", "ignoredBoxes", "ignoreAreasColoredWith"]) {
    if (p[k] !== undefined) opt.output[k] = p[k];
  }
  if (p.mode !== undefined && p.mode !== "default") opt.ignore = p.mode;
  if (p.returnEarlyThreshold !== undefined) opt.returnEarlyThreshold = p.returnEarlyThreshold;
  if (p.tolerance !== undefined) opt.tolerance = p.tolerance;
  return opt;
}

function writeRgbaPng(file, d) {
  const { PNG } = req("pngjs");
  const png = new PNG({ width: d.w, height: d.h });
  png.data = Buffer.from(d.rgba, "base64");
  fs.writeFileSync(file, PNG.sync.write(png, { colorType: 6 }));
}

function serve() {
  const page = "<!doctype html><meta charset=utf-8><script src=/resemble.js></script>";
  const resembleJs = fs.readFileSync(req.resolve("resemblejs/resemble.js"));
  const server = http.createServer((q, res) => {
    const [code, type, body] = q.url === "/"            ? [200, "text/html", page]
                               : q.url === "/resemble.js" ? [200, "text/javascript", resembleJs]
                                                          : [404, "text/plain", ""];
    res.writeHead(code, { "content-type": type });
    res.end(body);
  });
  return new Promise((resolve, reject) => {
    server.on("error", reject);
    server.listen(0, "127.0.0.1", () => resolve(server));
  });
}

async function main() {
  const args = process.argv.slice(2);
  const stats = args.includes("--stats");
  const at = args.indexOf("--batch");
  if (at < 0 || at + 1 >= args.length || args.length !== (stats ? 3 : 2)) {
    die("usage: resemble-oracle --batch FILE [--stats]");
  }
  const pairs = fs.readFileSync(args[at + 1], "utf8").split("\n").filter((l) => l.trim())
      .map((l) => JSON.parse(l));

  const start = Date.now();
  const server = await serve();
  const { chromium } = req("playwright-core");
  const browser = await chromium.launch({
    executablePath: process.env.AOSUITE_ORACLE_CHROMIUM || "/usr/bin/chromium",
    args: ["--no-sandbox", "--disable-gpu", "--force-color-profile=srgb",
           "--disable-background-networking", "--disable-component-update"],
  });
  let errors = 0;
  try {
    const page = await browser.newPage();
    await page.goto("http://127.0.0.1:" + server.address().port + "/");
    const dataUrl = (file) => "data:image/png;base64," + fs.readFileSync(file).toString("base64");
    for (let next = 0; next < pairs.length;) {
      const chunk = [], jobs = [];
      for (let bytes = 0; next < pairs.length && chunk.length < CHUNK_PAIRS &&
                          bytes < CHUNK_BYTES; ++next) {
        const p = pairs[next];
        chunk.push(p);
        try {
          jobs.push({ urlA: dataUrl(p.a), urlB: dataUrl(p.b), opt: resembleOptions(p),
                      wantDiff: p.diffRaw !== undefined });
          bytes += jobs[jobs.length - 1].urlA.length + jobs[jobs.length - 1].urlB.length;
        } catch (e) {
          jobs.push({ error: e.message });  // an unreadable file
        }
      }
      const results = await page.evaluate(comparePairs, jobs);
      chunk.forEach((p, k) => {
        const { diff, ...r } = results[k];
        if (diff) writeRgbaPng(p.diffRaw, diff);
        if (r.error) ++errors;
        process.stdout.write(JSON.stringify({ id: p.id, ...r }) + "\n");
      });
    }
  } finally {
    await browser.close();
    server.close();
  }
  if (stats) {
    const s = (Date.now() - start) / 1000;
    process.stderr.write(`resemble-oracle: ${pairs.length} pairs in ${s.toFixed(1)} s ` +
                         `(${(pairs.length / s).toFixed(0)}/s), ${errors} errors\n`);
  }
  process.exitCode = errors ? 1 : 0;
}

main().catch((e) => die(e && e.stack ? e.stack : String(e)));

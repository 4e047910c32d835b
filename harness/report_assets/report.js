// The report's behaviour: filter by status and text, keyboard navigation, one case opened
// beside the table in a panel of adjustable width (golden / new / diff, swap and flicker,
// slider, zoom, 1:1, pan and zoom shared by an image's views, a jump to its largest
// difference), every failure on one page, and the bless command for the cases selected. Works
// from disk: no network, no external scripts, no server.
(function () {
  "use strict";
  const $ = (id) => document.getElementById(id);
  const meta = JSON.parse($("meta").textContent);
  const data = JSON.parse($("data").textContent);
  const pics = JSON.parse($("images").textContent);
  const url = (u) => (u && u.startsWith("k:") ? "data:image/png;base64," + pics[u.slice(2)] : u);
  const esc = (s) =>
    String(s).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);
  const tbody = document.querySelector("#cases tbody");
  const more = $("more");

  // --- rows: drawn a chunk at a time for the cases that pass the filter ----------------------
  // What needs a person's eyes (and, but for ERROR, an approval to clear): not PASS or FLAKY.
  const failing = (s) => s === "FAIL" || s === "NEW" || s === "ERROR" || s === "WARN";
  const text = data.map((c) => (c.id + " " + c.source + " " + c.message).toLowerCase());
  const selected = new Set(); // indices into data
  const rowOf = new Map(); // index into data -> its <tr>, once drawn
  let view = []; // indices into data that pass the filter, in the report's order
  let drawn = 0; // how many of `view` are in the table
  const CHUNK = 150;
  // A row keeps a fixed height beside an open panel: the case's name breaks only after a
  // separator (/ _ - .), never inside a word, and is cut after three lines; its source and
  // message keep one line each; each is whole in its title. Measured, limit and time (class
  // wide) give way when the table is narrow: the open case shows them.
  const breakable = (s) => esc(s).replace(/[/_\-.]+/g, "$&<wbr>");
  const line = (cls, s) => `<div class=${cls} title="${esc(s)}">${esc(s)}</div>`;
  function rowHtml(i) {
    const c = data[i];
    const thumb = c.thumb ? `<img class=thumb loading=lazy src="${esc(url(c.thumb))}" alt=""${exposed(c.thumb_stops != null, c.thumb_stops)}>` : "";
    return `<tr data-i=${i} data-s=${c.status}><td><input type=checkbox aria-label=select${c.status === "ERROR" ? " disabled" : ""}${selected.has(i) ? " checked" : ""}></td>` +
      `<td><span class=${c.status}>${c.status}</span></td><td class=id><a href="#case=${esc(encodeURIComponent(c.id))}" title="${esc(c.id)}">${breakable(c.id)}</a>` +
      (c.source ? line("src", c.source) : "") + (c.status !== "PASS" && c.message ? line("msg", c.message) : "") +
      `</td><td class="num wide">${esc(c.measured)}</td><td class="num wide">${esc(c.limit)}</td><td class=num>${esc(c.margin)}</td>` +
      `<td class=num>${esc(c.delta)}</td><td class="num wide">${c.seconds.toFixed(2)}</td><td class=thumb>${thumb}</td></tr>`;
  }
  function drawTo(count) {
    count = Math.min(count, view.length);
    if (count > drawn) {
      tbody.insertAdjacentHTML("beforeend", view.slice(drawn, count).map(rowHtml).join(""));
      const added = Array.from(tbody.rows).slice(drawn);
      for (const tr of added) rowOf.set(+tr.dataset.i, tr);
      drawn = count;
    }
    more.textContent = drawn < view.length ? `${view.length - drawn} more below (scroll, or press End)` : "";
  }
  function applyFilter() {
    const on = new Set();
    for (const box of document.querySelectorAll("#filters input")) if (box.checked) on.add(box.dataset.status);
    const words = $("search").value.toLowerCase().split(/\s+/).filter((w) => w);
    view = [];
    data.forEach((c, i) => {
      if (on.has(c.status) && words.every((w) => text[i].includes(w))) view.push(i);
    });
    tbody.textContent = "";
    rowOf.clear();
    drawn = 0;
    drawTo(CHUNK);
    if (current >= 0 && rowOf.has(current)) rowOf.get(current).classList.add("cur");
    $("shown").textContent = view.length + " of " + data.length + " shown";
    listFailures();
  }
  for (const box of document.querySelectorAll("#filters input")) box.addEventListener("change", applyFilter);
  $("search").addEventListener("input", applyFilter);
  new IntersectionObserver((seen) => {
    if (seen.some((e) => e.isIntersecting)) drawTo(drawn + CHUNK);
  }).observe(more);
  tbody.addEventListener("click", (e) => {
    const tr = e.target.closest("tr");
    if (!tr) return;
    const i = +tr.dataset.i;
    if (e.target.tagName === "INPUT") {
      select(i, e.target.checked);
      updateCommand();
      return;
    }
    if (e.target.tagName === "A") e.preventDefault();
    open(i);
  });

  // --- selection and the bless command -----------------------------------------------------
  // As the harness writes them: the regular expression matching exactly these ids, and one
  // shell word (bare when safe, else single-quoted).
  const exact = (ids) => {
    const alt = ids.map((id) => id.replace(/[\\^$.|?*+()[\]{}]/g, "\\$&")).join("|");
    return ids.length === 1 ? "^" + alt + "$" : "^(" + alt + ")$";
  };
  const shq = (s) => (/^[A-Za-z0-9_\-./=:,+@%]+$/.test(s) ? s : "'" + s.replace(/'/g, "'\\''") + "'");
  function updateCommand() {
    const chosen = Array.from(selected).sort((a, b) => a - b);
    const ids = chosen.map((i) => data[i].id);
    const passing = chosen.some((i) => !failing(data[i].status));
    $("selected").textContent = ids.length ? ids.length + " selected" : "none selected (all FAIL, NEW and WARN)";
    $("command").textContent = ids.length
      ? meta.approve + (passing ? " --force" : "") + " --filter " + shq(exact(ids))
      : meta.approve_failed;
  }
  function select(i, on) {
    if (data[i].status === "ERROR") return;
    on ? selected.add(i) : selected.delete(i);
    for (const at of [rowOf.get(i), blockOf.get(i)]) if (at) at.querySelector("input").checked = on;
  }
  $("select-failing").addEventListener("click", () => {
    for (const i of view) if (data[i].status === "FAIL" || data[i].status === "NEW") select(i, true);
    updateCommand();
  });
  $("select-none").addEventListener("click", () => {
    for (const i of Array.from(selected)) select(i, false);
    updateCommand();
  });
  $("copy").addEventListener("click", () => {
    const command = $("command").textContent;
    const fallback = () => {
      const range = document.createRange();
      range.selectNodeContents($("command"));
      const s = getSelection();
      s.removeAllRanges();
      s.addRange(range);
      $("copied").textContent = document.execCommand("copy") ? "copied" : "selected: press Ctrl+C";
    };
    if (navigator.clipboard && window.isSecureContext) {
      navigator.clipboard.writeText(command).then(() => ($("copied").textContent = "copied"), fallback);
    } else fallback();
  });

  // --- one case beside the table -----------------------------------------------------------
  let current = -1, zoom = 0; // zoom 0: fit; else a factor of the natural size
  const detail = $("detail");
  // A picture and its caption; `file`, when given, is the image itself (an EXR), of which `src`
  // is the PNG preview: linked beside it. A picture that cannot be loaded says so.
  // --- exposure: a float image's preview holds sRGB(v / 2^stops) (stops: enough that its
  // brightest sample is not clipped); an SVG filter per stops maps each 8-bit code back to
  // sRGB(min(1, v * 2^exposure)), so one control sets every float picture's exposure ---------
  // Until the reviewer moves the control, each case opens at its own images' exposure: minus
  // the most stops a preview of it is darkened by, so its brightest 0.1 % is just below white
  // (harness/report_images.hpp) instead of a sky of 4 clipped. The control then rules.
  let exposure = 0, exposureSet = false;
  const autoExposure = (images) =>
    -Math.max(0, ...images.filter((v) => v.golden_file || v.new_file).map((v) => Math.max(v.golden_stops || 0, v.new_stops || 0)));
  const toLinear = (c) => (c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4));
  const toSrgb = (l) => (l <= 0.0031308 ? 12.92 * l : 1.055 * Math.pow(l, 1 / 2.4) - 0.055);
  document.body.insertAdjacentHTML("beforeend", "<svg id=exposure-filters width=0 height=0 style=position:absolute aria-hidden=true></svg>");
  const filterDefs = $("exposure-filters");
  function exposureTable(stops) {
    const gain = Math.pow(2, stops + exposure), t = [];
    for (let i = 0; i < 256; ++i) t.push(toSrgb(Math.min(1, toLinear(i / 255) * gain)).toFixed(5));
    return t.join(" ");
  }
  function exposureFilter(stops) {
    const id = "exposure" + stops;
    if (!document.getElementById(id)) {
      filterDefs.insertAdjacentHTML("beforeend", `<filter id=${id} color-interpolation-filters=sRGB><feComponentTransfer>` +
        ["R", "G", "B"].map((c) => `<feFunc${c} type=table tableValues="${exposureTable(stops)}"/>`).join("") +
        "</feComponentTransfer></filter>");
    }
    return id;
  }
  function setExposure(stops) {
    exposure = stops;
    for (const f of filterDefs.querySelectorAll("filter")) {
      const table = exposureTable(+f.id.slice(8));
      for (const fn of f.querySelectorAll("[type=table]")) fn.setAttribute("tableValues", table);
    }
    for (const out of document.querySelectorAll(".exposure output")) out.textContent = stops;
    for (const input of document.querySelectorAll(".exposure input")) input.value = stops;
  }
  document.addEventListener("input", (e) => {
    if (e.target.closest && e.target.closest(".exposure")) {
      exposureSet = true;
      setExposure(+e.target.value);
    }
  });
  // The style that puts a float picture (a preview: `file` is its float file) under the
  // exposure control.
  const exposed = (file, stops) => (file ? ` style="filter:url(#${exposureFilter(stops || 0)})"` : "");
  // A view: a box of the picture's size at fit that scrolls its picture when zoomed; the views
  // of one image pan together. Its only child holds the picture and what is drawn over it.
  const viewHtml = (inner, cls) => `<div class=view><div${cls ? " class=" + cls : ""}>${inner}</div></div>`;
  const fig = (src, caption, file, stops) =>
    !src && !file ? "" : `<figure>${src ? viewHtml(`<img src="${esc(url(src))}" alt="${esc(caption)}"${exposed(file, stops)}>`) : ""}` +
      `<figcaption>${esc(caption)}${file ? ` — <a href="${esc(file)}">${esc(file.split("/").pop())}</a>${src ? " (sRGB preview)" : ""}` : ""}</figcaption></figure>`;
  // The diff with what the tolerance set apart drawn over it: ignored pixels (boxes and mask)
  // outlined in blue, regions tinted in their colours.
  function diffFig(v) {
    if (!v.diff) return "";
    const layers = [[v.ignored, "ignored", "ignored pixels outlined in blue"], [v.regions, "regions", "regions tinted"]]
      .filter((l) => l[0]);
    if (!layers.length) return fig(v.diff, "diff");
    return `<figure>${viewHtml(`<img src="${esc(url(v.diff))}" alt=diff>` +
      layers.map(([src, cls, what]) => `<img class=${cls} src="${esc(url(src))}" alt="${what}">`).join(""), "over")}<figcaption>diff; ${layers.map((l) => l[2]).join(", ")}</figcaption></figure>`;
  }
  // The FLIP map with its colour scale: magma from 0 (no perceived difference) to 1.
  const heatFig = (v) =>
    !v.heat ? "" : `<figure>${viewHtml(`<img src="${esc(url(v.heat))}" alt="FLIP error">`)}` +
      `<figcaption>FLIP error (magma) <span class=scale aria-label="colour scale 0 to 1">0 <i></i> 1</span></figcaption></figure>`;
  document.addEventListener("error", (e) => {
    const fail = e.target.closest && e.target.closest("figure");
    if (fail && e.target.tagName === "IMG") fail.classList.add("missing");
  }, true);
  // An image's verdict and pictures; `brief` (the page of failures) leaves out the gates' table
  // (its message names the failing ones), the swap and the slider.
  function imageHtml(c, v, brief) {
    const resemble = c.resemble ? ` ${esc(v.mismatch || "-")}% (allowed ${c.allowed}%), max channel Δ ${v.delta}` : "";
    const where = v.largest ? `, largest difference ${esc(v.largest)}` : "";
    let h = `<h3>${esc(v.image)} — <span class="${v.status}">${v.status}</span>${resemble}${where}${v.identical ? ", byte-identical" : ""}</h3>`;
    if (v.message) h += `<p>${esc(v.message)}</p>`;
    if (v.changes) h += `<p class=changes>What changed: ${esc(v.changes)}</p>`;
    if (!brief && v.gates.length) {
      h += "<table class=gates><tr><th>gate</th><th>value</th><th>limit</th><th>margin</th></tr>" +
        v.gates.map((g) => `<tr class="${g.pass ? "PASS" : "FAIL"}"><td>${esc(g.gate)}</td><td class=num>${esc(g.value)}</td><td class=num>${esc(g.limit)}</td><td class=num>${esc(g.margin)}</td></tr>`).join("") + "</table>";
    }
    if (v.golden_file || v.new_file) {
      h += `<p><label class=exposure>exposure <input type=range min=-8 max=8 step=0.5 value=${exposure} aria-label=exposure> <output>${exposure}</output> stops</label>` +
        `${exposureSet ? "" : " <span class=note>(chosen from the images: their brightest 0.1 % just below white)</span>"}</p>`;
    }
    // Where the jump to the largest difference goes: `largest` is "12 @ (3, 4)".
    const at = /@ \((\d+), (\d+)\)$/.exec(v.largest);
    h += `<div class=images${at ? ` data-x=${at[1]} data-y=${at[2]}` : ""}>${fig(v.golden, "golden", v.golden_file, v.golden_stops)}${fig(v.new, "new", v.new_file, v.new_stops)}${diffFig(v)}` +
      `${fig(v.abs, "|new − golden|, scaled: white is the largest difference" + (v.largest ? ` (${v.largest})` : ""))}` +
      `${fig(v.signed, "new − golden: blue darker, white unchanged, red brighter, scaled to the largest")}` +
      `${heatFig(v)}${fig(v.regions, "region map")}`;
    if (!brief && v.golden && v.new && !v.identical) {
      h += `<figure class=swap>${viewHtml(`<img class=golden src="${esc(url(v.golden))}" alt=golden${exposed(v.golden_file, v.golden_stops)}><img class=new src="${esc(url(v.new))}" alt=new${exposed(v.new_file, v.new_stops)}>`)}` +
        "<figcaption><b class=golden>golden</b><b class=new>new</b>: hover for the other, b flickers</figcaption></figure>";
      h += `<figure class=slider>${viewHtml(`<img src="${esc(url(v.golden))}" alt=golden${exposed(v.golden_file, v.golden_stops)}><img class=top src="${esc(url(v.new))}" alt=new${exposed(v.new_file, v.new_stops)}>`)}` +
        `<input type=range min=0 max=100 value=50 aria-label="new vs golden"><figcaption>slider: new (left) over golden</figcaption></figure>`;
    }
    return h + "</div>";
  }
  const table = (o) =>
    "<table>" + Object.keys(o).map((k) => `<tr><th>${esc(k)}</th><td>${esc(o[k])}</td></tr>`).join("") + "</table>";
  function open(i) {
    if (i < 0 || i >= data.length) return;
    if (onePage) return goToBlock(i);
    if (rowOf.has(current)) rowOf.get(current).classList.remove("cur");
    current = i;
    const at = view.indexOf(i);
    if (at >= drawn) drawTo(at + CHUNK);
    const tr = rowOf.get(i);
    if (tr) {
      tr.classList.add("cur");
      tr.scrollIntoView({ block: "nearest" });
    }
    const c = data[i];
    if (!exposureSet) setExposure(autoExposure(c.images));
    let h = `<button class=close title="close (Esc)">×</button><h2 id="${esc(c.id)}">${breakable(c.id)} <span class="${c.status}">${c.status}</span></h2>`;
    if (c.message) h += `<p>${esc(c.message)}</p>`;
    if (c.not_reused) h += `<p class=note>${esc(c.not_reused)}</p>`;
    if (c.source) h += `<p>${c.kind === "command" ? "Command" : "Source"} <code>${esc(c.source)}</code>${c.exit >= 0 ? ", exit status " + c.exit : ""}${c.attempts > 1 ? ", " + c.attempts + " attempts" : ""}</p>`;
    if (c.stderr) h += `<details${c.status === "ERROR" ? " open" : ""}><summary>stderr</summary><pre>${esc(c.stderr)}</pre></details>`;
    if (c.bless) h += `<p>Accept after making the images again: <code>${esc(c.bless)}</code><br>Accept this report's image: <code>${esc(meta.approve + " --filter " + shq(exact([c.id])))}</code></p>`;
    h += `<p class=zoom>Zoom: <button data-z=0>fit (f)</button> <button data-z=1>1:1 (1)</button> <button data-z=2>2×</button> <button data-z=4>4×</button> <button data-z=8>8×</button>` +
      ` <button class=largest>largest difference (m)</button> <button class=flicker>flicker (b)</button></p>`;
    if (c.images_left_out) {
      h += `<p class=note>Its images were not kept (<code>--report-images failures</code>): it passed. Golden: ` +
        c.images.map((v) => `<code>${esc(v.golden_path)}</code>`).join(", ") + "</p>";
    }
    for (const v of c.images) h += imageHtml(c, v);
    c.failed_attempts.forEach((a, k) => {
      h += `<details open class=attempt><summary>Attempt ${k + 1}: <span class="${a.status}">${a.status}</span> ${esc(a.message)}</summary>` +
        a.images.map((p) => `<div class=images>${fig(p.golden, p.image + ": golden", p.golden_file, p.golden_stops)}` +
          `${fig(p.new, p.image + ": new", p.new_file, p.new_stops)}${fig(p.diff, p.image + ": diff")}</div>`).join("") + "</details>";
    });
    h += `<details><summary>parameters, timings</summary>${table(c.about)}${table(c.params)}${table(c.times)}</details>`;
    detail.innerHTML = h;
    detail.hidden = false;
    document.body.classList.add("panel");
    detail.querySelector(".close").addEventListener("click", close);
    for (const b of detail.querySelectorAll(".zoom [data-z]")) b.addEventListener("click", () => setZoom(+b.dataset.z));
    detail.querySelector(".largest").addEventListener("click", jumpToLargest);
    detail.querySelector(".flicker").addEventListener("click", toggleFlicker);
    detail.querySelector(".flicker").classList.toggle("on", !!flicker);
    for (const slider of detail.querySelectorAll(".slider")) {
      const top = slider.querySelector("img.top"), input = slider.querySelector("input");
      input.addEventListener("input", () => (top.style.clipPath = "inset(0 " + (100 - input.value) + "% 0 0)"));
    }
    jumped = -1;
    setZoom(zoom);
    history.replaceState(null, "", "#case=" + encodeURIComponent(c.id));
  }
  function close() {
    detail.hidden = true;
    document.body.classList.remove("panel");
    history.replaceState(null, "", "#");
  }
  // A picture takes the zoom's size once loaded, and its view the picture's shape (its size at
  // fit), so a zoomed picture scrolls inside the box it had at fit.
  function sizePicture(img) {
    if (!img.naturalWidth) return;
    img.style.width = zoom ? img.naturalWidth * zoom + "px" : "";
    img.closest(".view").style.aspectRatio = img.naturalWidth + " / " + img.naturalHeight;
  }
  detail.addEventListener("load", (e) => e.target.closest(".view") && sizePicture(e.target), true);
  // A view's scale (shown pixels per image pixel), the image pixel at its centre, and the scroll
  // that puts an image pixel there.
  function scaleOf(box) {
    const img = box.querySelector("img");
    return img.naturalWidth ? img.getBoundingClientRect().width / img.naturalWidth : 0;
  }
  const centreOf = (box) => [(box.scrollLeft + box.clientWidth / 2) / scaleOf(box), (box.scrollTop + box.clientHeight / 2) / scaleOf(box)];
  function centreAt(box, [x, y]) {
    const s = scaleOf(box);
    box.scrollLeft = x * s - box.clientWidth / 2;
    box.scrollTop = y * s - box.clientHeight / 2;
  }
  // Zooming keeps each view's centre where it was.
  function setZoom(z) {
    const views = Array.from(detail.querySelectorAll(".view")).filter(scaleOf);
    const centres = views.map(centreOf);
    zoom = z;
    detail.classList.toggle("fit", z === 0);
    for (const b of detail.querySelectorAll(".zoom [data-z]")) b.classList.toggle("on", +b.dataset.z === z);
    for (const img of detail.querySelectorAll(".view img")) sizePicture(img);
    views.forEach((box, k) => centreAt(box, centres[k]));
  }
  // The views of one image pan together: scrolling (or dragging) one scrolls the others to the
  // same spot; they are at the same zoom.
  detail.addEventListener("scroll", (e) => {
    const from = e.target;
    if (!from.classList || !from.classList.contains("view")) return;
    for (const to of from.closest(".images").querySelectorAll(".view")) {
      to.scrollLeft = from.scrollLeft;
      to.scrollTop = from.scrollTop;
    }
  }, true);
  detail.addEventListener("pointerdown", (e) => {
    const box = e.target.closest(".view");
    if (!box || !zoom || e.button) return;
    let x = e.clientX, y = e.clientY;
    drag(e, (m) => {
      box.scrollLeft -= m.clientX - x;
      box.scrollTop -= m.clientY - y;
      x = m.clientX;
      y = m.clientY;
    });
  });
  // `m`: the next image of the case (in turn) at its largest difference: zoomed in (8× from
  // fit), each of its views centred on that pixel, marked.
  let jumped = -1;
  function jumpToLargest() {
    const images = detail.querySelectorAll(".images[data-x]");
    if (!images.length) return;
    const at = images[(jumped = (jumped + 1) % images.length)];
    const loaded = (img) => img.complete || new Promise((done) => ["load", "error"].forEach((e) => img.addEventListener(e, done)));
    Promise.all(Array.from(at.querySelectorAll(".view img"), loaded)).then(() => {
      setZoom(zoom || 8);
      for (const mark of detail.querySelectorAll(".mark")) mark.remove();
      const x = +at.dataset.x + 0.5, y = +at.dataset.y + 0.5;
      for (const box of at.querySelectorAll(".view")) {
        const img = box.querySelector("img");
        if (!img.naturalWidth) continue;
        box.firstChild.insertAdjacentHTML("beforeend", `<i class=mark style="left:${(100 * x) / img.naturalWidth}%;top:${(100 * y) / img.naturalHeight}%"></i>`);
        centreAt(box, [x, y]);
      }
      at.scrollIntoView({ block: "nearest" });
    });
  }
  // `b`: the swap view flickers, golden and new in turn every 500 ms, until `b` again; it goes
  // on as the reviewer moves from case to case.
  let flicker = 0;
  function toggleFlicker() {
    clearInterval(flicker);
    flicker = flicker ? 0 : setInterval(() => detail.classList.toggle("flick"), 500);
    detail.classList.remove("flick");
    const button = detail.querySelector(".flicker"), swap = detail.querySelector(".swap");
    if (button) button.classList.toggle("on", !!flicker);
    if (flicker && swap) swap.scrollIntoView({ block: "nearest" });
  }
  // Follows the pointer from a pointerdown until it is released or the browser takes it over
  // (window listeners: synthetic events, as a test sends, cannot capture the pointer).
  function drag(e, onMove, onEnd) {
    e.preventDefault();
    document.body.classList.add("dragging");
    addEventListener("pointermove", onMove);
    const end = () => {
      removeEventListener("pointermove", onMove);
      removeEventListener("pointerup", end);
      removeEventListener("pointercancel", end);
      document.body.classList.remove("dragging");
      if (onEnd) onEnd();
    };
    addEventListener("pointerup", end);
    addEventListener("pointercancel", end);
  }

  // --- the panel's width: its left edge (#grip) drags, or moves by ←/→ when focused; the width
  // is remembered (localStorage, which may throw for a page from disk: then it lasts as long as
  // the page). The style keeps it within bounds as the window changes (report.css) -----------
  const STORED = "aosuite.panel";
  const setPanel = (px) => document.documentElement.style.setProperty("--panel", Math.round(px) + "px");
  const panelWidth = () => detail.getBoundingClientRect().width; // as bounded
  const keepWidth = () => {
    try {
      localStorage.setItem(STORED, Math.round(panelWidth()));
    } catch (e) {}
  };
  try {
    if (+localStorage.getItem(STORED)) setPanel(+localStorage.getItem(STORED));
  } catch (e) {}
  document.body.insertAdjacentHTML("beforeend", "<div id=grip role=separator aria-orientation=vertical tabindex=0 title=\"panel width: drag, or ←/→\"></div>");
  $("grip").addEventListener("pointerdown", (e) => {
    const right = detail.getBoundingClientRect().right; // the window's, less its scroll bar
    drag(e, (m) => setPanel(right - m.clientX), keepWidth);
  });
  $("grip").addEventListener("keydown", (e) => {
    const by = { ArrowLeft: 40, ArrowRight: -40 }[e.key];
    if (!by) return;
    e.preventDefault();
    e.stopPropagation(); // not the table's keys
    setPanel(panelWidth() + by);
    keepWidth();
  });
  // The next case of the list shown (the filtered table, or the page of failures) after (dir 1)
  // or before (dir -1) `from` that `want`s.
  function step(from, dir, want) {
    const list = onePage ? listed : view;
    let at = list.indexOf(from);
    if (at < 0) at = dir > 0 ? -1 : list.length;
    for (let k = at + dir; k >= 0 && k < list.length; k += dir) {
      if (want(data[list[k]])) return list[k];
    }
    return -1;
  }
  function onKey(e) {
    if (e.target.tagName === "INPUT" && e.target.type !== "checkbox") {
      if (e.key === "Escape") e.target.blur();
      return;
    }
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const any = () => true, bad = (c) => failing(c.status);
    let to = -2;
    switch (e.key) {
      case "j": case "ArrowDown": to = step(current, 1, any); break;
      case "k": case "ArrowUp": to = step(current, -1, any); break;
      case "n": to = step(current, 1, bad); break;
      case "p": case "N": to = step(current, -1, bad); break;
      case "Enter": case "o": to = current >= 0 ? current : step(-1, 1, any); break;
      case "Home": to = step(-1, 1, any); break;
      case "End": to = step(-1, -1, any); break;
      case "Escape": close(); break;
      case "x": case " ": if (current >= 0) { select(current, !selected.has(current)); updateCommand(); } break;
      case "/": $("search").focus(); break;
      case "v": showView(!onePage); break;
      case "f": setZoom(0); break;
      case "1": setZoom(1); break;
      case "+": case "=": setZoom(Math.min(16, (zoom || 1) * 2)); break;
      case "-": setZoom(zoom > 1 ? zoom / 2 : 0); break;
      case "m": if (!detail.hidden) jumpToLargest(); break;
      case "b": if (!detail.hidden) toggleFlicker(); break;
      default: return;
    }
    e.preventDefault();
    if (to >= 0) open(to);
  }
  document.addEventListener("keydown", onKey);

  // --- every FAIL, NEW, WARN and ERROR case that passes the filter on one scrolling page: each with
  // its id, a box to select it, and its failing images' verdicts and pictures -----------------
  let onePage = false;
  let listed = []; // indices into data: the failing ones of `view`
  let listedDrawn = 0;
  const blockOf = new Map(); // index into data -> its <article>, once drawn
  const failures = $("failures"), failuresMore = $("failures-more");
  const BLOCKS = 20;
  function blockHtml(i) {
    const c = data[i];
    let h = `<article data-i=${i}><h2><input type=checkbox aria-label=select${c.status === "ERROR" ? " disabled" : ""}${selected.has(i) ? " checked" : ""}> ` +
      `<a href="#case=${esc(encodeURIComponent(c.id))}">${esc(c.id)}</a> <span class="${c.status}">${c.status}</span></h2>`;
    const shown = c.images.filter((v) => v.status !== "PASS");
    if (c.message && !shown.length) h += `<p>${esc(c.message)}</p>`; // else each image says why
    if (c.stderr) h += `<details><summary>stderr</summary><pre>${esc(c.stderr)}</pre></details>`;
    for (const v of shown) h += imageHtml(c, v, true);
    return h + "</article>";
  }
  function drawBlocksTo(count) {
    count = Math.min(count, listed.length);
    if (count > listedDrawn) {
      failures.insertAdjacentHTML("beforeend", listed.slice(listedDrawn, count).map(blockHtml).join(""));
      for (const art of Array.from(failures.children).slice(listedDrawn)) blockOf.set(+art.dataset.i, art);
      listedDrawn = count;
    }
    failuresMore.textContent = listedDrawn < listed.length ? `${listed.length - listedDrawn} more below` : listed.length ? "" : "No FAIL, NEW, WARN or ERROR case is shown.";
  }
  function listFailures() {
    listed = view.filter((i) => failing(data[i].status));
    $("failing").textContent = listed.length;
    failures.textContent = "";
    blockOf.clear();
    listedDrawn = 0;
    if (onePage) drawBlocksTo(BLOCKS);
  }
  function goToBlock(i) {
    const at = listed.indexOf(i);
    if (at < 0) return;
    if (at >= listedDrawn) drawBlocksTo(at + BLOCKS);
    if (blockOf.has(current)) blockOf.get(current).classList.remove("cur");
    current = i;
    blockOf.get(i).classList.add("cur");
    blockOf.get(i).scrollIntoView({ block: "start" });
  }
  function showView(all) {
    close();
    onePage = all;
    $("table-view").hidden = all;
    $("failures-view").hidden = !all;
    for (const b of document.querySelectorAll("#views button")) b.classList.toggle("on", (b.dataset.view === "failures") === all);
    listFailures();
    if (all && listed.includes(current)) goToBlock(current); // the case looked at stays in sight
    history.replaceState(null, "", all ? "#view=failures" : "#");
  }
  for (const b of document.querySelectorAll("#views button")) b.addEventListener("click", () => showView(b.dataset.view === "failures"));
  new IntersectionObserver((seen) => {
    if (onePage && seen.some((e) => e.isIntersecting)) drawBlocksTo(listedDrawn + BLOCKS);
  }).observe(failuresMore);
  failures.addEventListener("change", (e) => {
    if (e.target.tagName !== "INPUT") return;
    select(+e.target.closest("article").dataset.i, e.target.checked);
    updateCommand();
  });
  failures.addEventListener("click", (e) => {
    if (e.target.tagName !== "A" || !e.target.closest("h2")) return;
    e.preventDefault(); // the case's id opens it in the table view, beside the table
    const i = +e.target.closest("article").dataset.i;
    showView(false);
    open(i);
  });

  // --- start: #select=id,id preselects; #view=failures shows the page of failures; #case=id
  // opens one, else the first failure; #keys=... then presses those keys (a link to "the third
  // failure" is #keys=nnn) -----------------------------------------------------------------
  const hash = decodeURIComponent(location.hash.slice(1));
  const index = new Map(data.map((c, i) => [c.id, i]));
  if (hash.startsWith("select=")) {
    for (const id of hash.slice(7).split(",")) if (index.has(id)) select(index.get(id), true);
  }
  applyFilter();
  updateCommand();
  if (hash === "view=failures") showView(true);
  else if (hash.startsWith("case=") && index.has(hash.slice(5))) open(index.get(hash.slice(5)));
  else if (data.length && failing(data[0].status)) open(0);
  if (hash.startsWith("keys=")) {
    for (const key of hash.slice(5)) onKey({ key, target: document.body, preventDefault() {} });
  }
  document.documentElement.dataset.readyMs = performance.now().toFixed(0);
  // Whether anything (the case panel) lies over the approve bar's copy button: it never may.
  const copyButton = $("copy"), at = copyButton.getBoundingClientRect();
  const top = document.elementFromPoint(at.left + at.width / 2, at.top + at.height / 2);
  document.documentElement.dataset.copyCovered = String(top !== copyButton);
})();

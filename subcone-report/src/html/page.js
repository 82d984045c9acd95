// The report page: report.md's answer (laid out to be seen whole on the
// first screen) and verdict sections; per scene, a viewer of any two of its
// images (split, alone or their difference, zoom, pan, the classes and
// values of the pixel under the cursor, a colour bar per map and for the
// difference, a line on what the images are), the sortable results table,
// the motion animation and the plots.
// The whole state lives in the URL fragment, so a link (or a headless
// browser) opens any view. Plain DOM, no build step.
"use strict";

(function () {
  const body = document.body;
  const $ = (id) => document.getElementById(id);

  function fail(message) {
    body.dataset.error = message;
    $("error").textContent = "Error: " + message;
    $("error").hidden = false;
  }
  window.addEventListener("error", (e) => fail(e.message || "script error"));
  window.addEventListener("unhandledrejection", (e) => fail(String(e.reason)));

  const R = JSON.parse($("report-data").textContent);
  const ZOOMS = [1, 2, 3, 4, 6, 8, 12, 16];
  const MAX_ZOOM = 16;
  // Difference modes and their scales: |A − B| · scale, and
  // 128 + scale · (A − B) / 2, per 8-bit channel, clamped.
  const DIFF_MODES = ["diff", "signed"];
  const SCALES = [1, 2, 4, 8, 16, 32];
  const DEFAULT_SCALE = 4;
  const diffCanvas = $("diff-canvas");
  const viewport = $("viewport");
  const imgA = $("img-a");
  const imgB = $("img-b");
  const clipA = $("clip-a");
  const canvas = $("highlight-canvas");
  const handle = $("split-handle");

  // The view: the fragment's keys. `cx`, `cy` is the image point at the
  // viewport's centre (`x + 0.5`, `y + 0.5` for the fragment's pixel).
  const state = {
    scene: "", a: "", b: "", mode: "split", split: 0.5, zoom: 1,
    cx: 0, cy: 0, highlight: "", sort: "", selftest: false,
    scale: DEFAULT_SCALE, raw: false,
  };
  const isDiff = () => DIFF_MODES.includes(state.mode);

  const sceneOf = (name) => R.scenes.find((s) => s.name === name);
  const scene = () => sceneOf(state.scene);
  const layerOf = (sc, id) => sc.layers.find((l) => l.id === id);
  const clamp = (v, lo, hi) => Math.min(hi, Math.max(lo, v));

  // Zoom that fits the image in the viewport, in whole steps.
  function fitZoom(sc) {
    const z = Math.floor(Math.min(viewport.clientWidth / sc.width, viewport.clientHeight / sc.height));
    return clamp(z, 1, MAX_ZOOM);
  }

  // The first method image as A, the reference as B.
  function defaultLayers(sc) {
    const ids = sc.layers.map((l) => l.id);
    const b = ids.includes("reference") ? "reference" : ids[0] || "";
    const a = (sc.layers.find((l) => l.kind === "render" && l.id !== b) || sc.layers[0] || {}).id || "";
    return [a, b];
  }

  function centre(sc) {
    state.cx = sc.width / 2;
    state.cy = sc.height / 2;
  }

  // Read the fragment into `state`, replacing what is missing or invalid
  // by defaults.
  function readHash() {
    const p = new URLSearchParams(location.hash.replace(/^#/, ""));
    const sc = sceneOf(p.get("scene")) || R.scenes[0];
    if (!sc) return;
    const sceneChanged = sc.name !== state.scene;
    state.scene = sc.name;
    const [da, db] = defaultLayers(sc);
    state.a = layerOf(sc, p.get("a")) ? p.get("a") : sceneChanged || !layerOf(sc, state.a) ? da : state.a;
    state.b = layerOf(sc, p.get("b")) ? p.get("b") : sceneChanged || !layerOf(sc, state.b) ? db : state.b;
    state.mode = ["split", "a", "b", ...DIFF_MODES].includes(p.get("mode")) ? p.get("mode") : "split";
    const scale = parseInt(p.get("scale"), 10);
    state.scale = SCALES.includes(scale) ? scale : DEFAULT_SCALE;
    state.raw = p.get("raw") === "1";
    const split = parseFloat(p.get("split"));
    state.split = Number.isFinite(split) ? clamp(split, 0, 1) : 0.5;
    const zoom = parseInt(p.get("zoom"), 10);
    state.zoom = Number.isFinite(zoom) ? clamp(zoom, 1, MAX_ZOOM) : fitZoom(sc);
    const x = parseInt(p.get("x"), 10);
    const y = parseInt(p.get("y"), 10);
    centre(sc);
    if (Number.isFinite(x)) state.cx = clamp(x, 0, sc.width - 1) + 0.5;
    if (Number.isFinite(y)) state.cy = clamp(y, 0, sc.height - 1) + 0.5;
    state.highlight = R.classes.includes(p.get("highlight")) ? p.get("highlight") : "";
    // `pareto`, the one front column of earlier pages, is the FLIP front's.
    const [given, dir] = (p.get("sort") || "").split(":");
    const col = given === "pareto" ? "pareto_flip" : given;
    state.sort = allColumns().includes(col) ? col + ":" + (dir === "asc" ? "asc" : "desc") : "";
    state.selftest = p.get("selftest") === "1";
  }

  // The fragment of `state`; `:` kept readable.
  function hash() {
    const keys = {
      scene: state.scene, a: state.a, b: state.b, mode: state.mode,
      split: +state.split.toFixed(3), zoom: state.zoom,
      x: Math.floor(state.cx), y: Math.floor(state.cy),
      highlight: state.highlight, sort: state.sort,
      scale: isDiff() ? state.scale : "", raw: state.raw ? 1 : "",
    };
    return "#" + Object.entries(keys)
      .filter(([, v]) => v !== "")
      .map(([k, v]) => k + "=" + encodeURIComponent(v).replace(/%3A/g, ":"))
      .join("&");
  }

  function writeHash() {
    history.replaceState(null, "", hash());
    body.dataset.state = hash().slice(1);
  }

  // --- Scenes -------------------------------------------------------------

  function buildSceneButtons() {
    const nav = $("scenes");
    for (const sc of R.scenes) {
      const b = document.createElement("button");
      b.type = "button";
      b.textContent = sc.name;
      b.dataset.scene = sc.name;
      b.addEventListener("click", () => showScene(sc));
      nav.appendChild(b);
    }
  }

  // Another scene: its defaults, but the same layers where it has them.
  function showScene(sc) {
    const [da, db] = defaultLayers(sc);
    state.scene = sc.name;
    state.a = layerOf(sc, state.a) ? state.a : da;
    state.b = layerOf(sc, state.b) ? state.b : db;
    state.zoom = fitZoom(sc);
    centre(sc);
    render();
  }

  // --- Viewer -------------------------------------------------------------

  function fillLayerSelect(select, sc, value) {
    select.textContent = "";
    const groups = new Map();
    for (const l of sc.layers) {
      if (!groups.has(l.group)) {
        const g = document.createElement("optgroup");
        g.label = l.group;
        groups.set(l.group, g);
        select.appendChild(g);
      }
      groups.get(l.group).appendChild(new Option(l.label, l.id));
    }
    select.value = value;
  }

  function setImage(img, layer) {
    const src = layer ? layer.src : "";
    if (img.getAttribute("src") !== src) img.src = src;
  }

  // The class bitmask of a scene, decoded once.
  const classBits = new Map();
  function bitsOf(sc) {
    if (!sc.classes) return null;
    if (!classBits.has(sc.name)) {
      const s = atob(sc.classes);
      const a = new Uint8Array(s.length);
      for (let i = 0; i < s.length; i++) a[i] = s.charCodeAt(i);
      classBits.set(sc.name, a);
    }
    return classBits.get(sc.name);
  }

  function classesAt(sc, x, y) {
    const bits = bitsOf(sc);
    if (!bits) return null;
    const v = bits[y * sc.width + x];
    return R.classes.filter((_, i) => v & (1 << i));
  }

  // --- Pixel values -------------------------------------------------------

  // A page from file:// may not read the pixels of the images it shows, so
  // each of a scene's PNGs also comes as a data: URL in a script,
  // images/<scene>/pixels/<id>.js, loaded when the layer is first needed and
  // decoded once. `pixelUrls` maps "scene/id" to the URL (null when the
  // script cannot be loaded); `decoded` maps "scene/id" to { data, width }
  // once decoded, { error } when it cannot be, {} while decoding.
  const pixelUrls = new Map();
  const requested = new Set();
  const decoded = new Map();
  window.subconePixels = (name, id, url) => {
    pixelUrls.set(name + "/" + id, url);
    refreshValues();
  };

  function loadPixels(sc, id) {
    const key = sc.name + "/" + id;
    if (!sc.pixels || requested.has(key)) return;
    requested.add(key);
    const s = document.createElement("script");
    s.src = sc.pixels + encodeURIComponent(id) + ".js";
    s.addEventListener("error", () => { pixelUrls.set(key, null); refreshValues(); });
    document.head.appendChild(s);
  }

  // The decoded RGBA of a layer, or null while it is not (yet) there.
  function pixelsOf(sc, id) {
    if (!id) return null;
    const key = sc.name + "/" + id;
    const have = decoded.get(key);
    if (have) return have.data ? have : null;
    const url = pixelUrls.get(key);
    if (!url) {
      loadPixels(sc, id);
      return null;
    }
    const entry = {};
    decoded.set(key, entry);
    const img = new Image();
    img.addEventListener("load", () => {
      const c = document.createElement("canvas");
      c.width = img.naturalWidth;
      c.height = img.naturalHeight;
      const ctx = c.getContext("2d", { willReadFrequently: true });
      ctx.drawImage(img, 0, 0);
      entry.data = ctx.getImageData(0, 0, c.width, c.height).data;
      entry.width = c.width;
      entry.height = c.height;
      refreshValues();
    });
    img.addEventListener("error", () => { entry.error = true; refreshValues(); });
    img.src = url;
    return null;
  }

  // Whether the layer's pixels will not come: no pixel scripts, the
  // layer's failed to load, or its PNG to decode.
  function unavailable(sc, id) {
    const key = sc.name + "/" + id;
    const d = decoded.get(key);
    return !sc.pixels || pixelUrls.get(key) === null || (d && d.error);
  }

  function rgbAt(sc, id, x, y) {
    const p = pixelsOf(sc, id);
    if (!p || x >= p.width || y >= p.height) return null;
    const i = 4 * (y * p.width + x);
    return [p.data[i], p.data[i + 1], p.data[i + 2]];
  }

  // FLIP's colour map as [r, g, b] triples: colour k is the error k / 255.
  const LUT = [];
  for (let k = 0; k < 256; k++) {
    LUT.push([0, 2, 4].map((o) => parseInt(R.flip_lut.substr(6 * k + o, 2), 16)));
  }

  // The FLIP error a map pixel's colour stands for: the index of the
  // nearest colour of the map over 255 (exact for the map's own colours),
  // null for a colour far from every one.
  function decodeFlip(rgb) {
    let best = -1;
    let dist = Infinity;
    LUT.forEach((c, k) => {
      const d = (c[0] - rgb[0]) ** 2 + (c[1] - rgb[1]) ** 2 + (c[2] - rgb[2]) ** 2;
      if (d < dist) { dist = d; best = k; }
    });
    return dist <= 27 ? best / 255 : null;
  }

  // 1 − SSIM from its map's grey: 0 black, R.ssim_white and more white.
  function decodeSsim(rgb) {
    if (Math.max(...rgb) - Math.min(...rgb) > 2) return null;
    return (rgb[1] / 255) * R.ssim_white;
  }

  // A layer's values at (x, y): its RGB, and for a method's layer (render or
  // map) the FLIP and 1 − SSIM of the method there, from its maps.
  function valuesAt(sc, layer, x, y) {
    const v = { rgb: rgbAt(sc, layer.id, x, y), flip: null, ssim: null };
    const maps = layer.maps || {};
    const flip = maps.flip && rgbAt(sc, maps.flip, x, y);
    const ssim = maps.ssim && rgbAt(sc, maps.ssim, x, y);
    if (flip) v.flip = decodeFlip(flip);
    if (ssim) v.ssim = decodeSsim(ssim);
    v.ready = !!v.rgb && (!maps.flip || !!flip) && (!maps.ssim || !!ssim);
    v.missing = [layer.id, maps.flip, maps.ssim].some((id) => id && unavailable(sc, id));
    return v;
  }

  function drawHighlight(sc) {
    const bit = R.classes.indexOf(state.highlight);
    const bits = bitsOf(sc);
    canvas.hidden = bit < 0 || !bits;
    if (canvas.hidden) return;
    canvas.width = sc.width;
    canvas.height = sc.height;
    const ctx = canvas.getContext("2d");
    const img = ctx.createImageData(sc.width, sc.height);
    for (let i = 0; i < bits.length; i++) {
      if (bits[i] & (1 << bit)) img.data.set([255, 0, 255, 140], 4 * i);
    }
    ctx.putImageData(img, 0, 0);
    canvas.dataset.highlight = state.highlight;
  }

  // Image position: the image point (cx, cy) at the viewport's centre,
  // rounded to whole screen pixels so each image pixel covers exactly
  // zoom x zoom of them.
  function offset() {
    return [
      Math.round(viewport.clientWidth / 2 - state.cx * state.zoom),
      Math.round(viewport.clientHeight / 2 - state.cy * state.zoom),
    ];
  }

  function layout() {
    const sc = scene();
    const [ox, oy] = offset();
    for (const el of [imgA, imgB, canvas, diffCanvas]) {
      el.style.width = sc.width * state.zoom + "px";
      el.style.height = sc.height * state.zoom + "px";
      el.style.left = ox + "px";
      el.style.top = oy + "px";
    }
    const vw = viewport.clientWidth;
    const splitX = Math.round(state.split * vw);
    clipA.style.width = (state.mode === "split" ? splitX : state.mode === "a" ? vw : 0) + "px";
    imgB.style.visibility = state.mode === "a" || isDiff() ? "hidden" : "visible";
    handle.style.left = splitX + "px";
    handle.hidden = state.mode !== "split";
    $("label-a").hidden = state.mode === "b";
    $("label-b").hidden = state.mode === "a";
    $("zoom-label").textContent = state.zoom + "\u00d7";
    viewport.dataset.box = [viewport.getBoundingClientRect().left + window.scrollX,
      viewport.getBoundingClientRect().top + window.scrollY, vw, viewport.clientHeight]
      .map(Math.round).join(" ");
    viewport.dataset.offset = ox + " " + oy;
  }

  let shownPixel = null;

  function showPixel(x, y, hovered) {
    const sc = scene();
    const info = $("pixel-info");
    shownPixel = [x, y, hovered];
    if (x < 0 || y < 0 || x >= sc.width || y >= sc.height) {
      info.textContent = "outside the image";
      $("values").textContent = "";
      return;
    }
    showValues(sc, x, y);
    const cls = classesAt(sc, x, y);
    info.dataset.x = x;
    info.dataset.y = y;
    info.dataset.classes = cls ? cls.join(" ") : "";
    info.textContent = (hovered ? "pixel " : "centre pixel ") + "(" + x + ", " + y + ")" +
      (cls ? ": " + (cls.length ? cls.join(", ") : "no class") : ": no classes (not measured)");
  }

  // The values of A and B at (x, y), as text with the numbers in spans
  // (`#rgb-a`, `#flip-a`, `#ssim-a`, and `-b`), and as data attributes of
  // `#values` (`data-state` ready, loading or unavailable).
  function showValues(sc, x, y) {
    const out = $("values");
    out.textContent = "";
    const ds = out.dataset;
    for (const k of Object.keys(ds)) delete ds[k];
    ds.x = x;
    ds.y = y;
    let state_ = "ready";
    const span = (id, text) => {
      const s = document.createElement("span");
      s.id = id;
      s.textContent = text;
      return s;
    };
    for (const [which, id] of [["a", state.a], ["b", state.b]]) {
      const layer = layerOf(sc, id);
      if (!layer) continue;
      const v = valuesAt(sc, layer, x, y);
      if (!v.ready) state_ = v.missing && state_ !== "loading" ? "unavailable" : "loading";
      const part = document.createElement("span");
      part.className = "value-part";
      part.append(which.toUpperCase() + " (" + layer.label + "): RGB ");
      part.append(span("rgb-" + which, v.rgb ? v.rgb.join(" ") : v.missing ? "n/a" : "…"));
      if (v.rgb) ds["rgb" + which.toUpperCase()] = v.rgb.join(" ");
      if (layer.maps && layer.maps.flip) {
        part.append(", FLIP ");
        part.append(span("flip-" + which, v.flip === null ? (v.ready ? "?" : "…") : v.flip.toFixed(4)));
        if (v.flip !== null) ds["flip" + which.toUpperCase()] = String(v.flip);
      }
      if (layer.maps && layer.maps.ssim) {
        part.append(", 1 \u2212 SSIM ");
        const white = v.ssim !== null && v.ssim >= R.ssim_white;
        part.append(span("ssim-" + which, v.ssim === null ? (v.ready ? "?" : "…") :
          (white ? "\u2265 " : "") + v.ssim.toFixed(4)));
        if (v.ssim !== null) ds["ssim" + which.toUpperCase()] = String(v.ssim);
      }
      out.appendChild(part);
    }
    ds.state = state_;
  }

  // New pixels decoded: the readout and the difference again.
  function refreshValues() {
    if (!R.scenes.length || !state.scene) return;
    if (shownPixel) {
      const [x, y, hovered] = shownPixel;
      showPixel(x, y, hovered);
    }
    if (isDiff()) drawDiff(scene());
  }

  // The difference of A and B into the difference canvas, once both are
  // decoded; `data-ready` says when it shows them.
  function drawDiff(sc) {
    const pa = pixelsOf(sc, state.a);
    const pb = pixelsOf(sc, state.b);
    const key = [sc.name, state.a, state.b, state.mode, state.scale].join("/");
    diffCanvas.hidden = !isDiff();
    if (!isDiff()) return;
    if (!pa || !pb || pa.width !== pb.width || pa.height !== pb.height) {
      diffCanvas.dataset.ready = "";
      diffCanvas.dataset.key = "";
      return;
    }
    if (diffCanvas.dataset.key === key) return;
    diffCanvas.width = pa.width;
    diffCanvas.height = pa.height;
    const ctx = diffCanvas.getContext("2d");
    const img = ctx.createImageData(pa.width, pa.height);
    const k = state.scale;
    const signed = state.mode === "signed";
    for (let i = 0; i < pa.data.length; i += 4) {
      for (let c = 0; c < 3; c++) {
        const d = pa.data[i + c] - pb.data[i + c];
        img.data[i + c] = signed ? Math.round(128 + (k * d) / 2) : k * Math.abs(d);
      }
      img.data[i + 3] = 255;
    }
    ctx.putImageData(img, 0, 0);
    diffCanvas.dataset.key = key;
    diffCanvas.dataset.ready = "1";
  }

  // --- Colour bars ---------------------------------------------------------

  // A colour bar for each kind of image the viewer may show whose colours
  // stand for values: FLIP's map (magma, 0 to 1) and 1 − SSIM's (grey, 0 to
  // R.ssim_white), shown while a visible layer is such a map; and in a
  // difference mode the difference's own scaling, per 8-bit channel (0 to
  // 255), as drawDiff computes it: |A − B| × scale is black at 0 and white
  // from 255 / scale on; 128 + scale (A − B) / 2 is black at −256 / scale,
  // mid-grey (128) at 0 and white at 254 / scale. Each bar's colours are
  // drawn from the same mapping, and its ends name the values.
  const BAR_KINDS = ["flip", "ssim", "diff", "signed"];
  const levels = (v) => String(+v.toFixed(2));

  function barLabels(kind) {
    const k = state.scale;
    const w = R.ssim_white;
    return {
      flip: ["FLIP map (magma colour map):", "0", "1", "middle 0.5"],
      ssim: ["1 \u2212 SSIM map (grey):", "0", "\u2265 " + w, "middle " + w / 2],
      diff: ["|A \u2212 B| \u00d7 " + k + ", per channel (8-bit levels):", "0",
        "\u2265 " + levels(255 / k), "middle " + levels(127.5 / k)],
      signed: ["A \u2212 B, drawn 128 + " + k + " (A \u2212 B) / 2, per channel (8-bit levels):",
        "\u2264 \u2212" + levels(256 / k), "\u2265 +" + levels(254 / k), "mid-grey 0"],
    }[kind];
  }

  function buildBars() {
    const grey = (t) => [0, 1, 2].map(() => Math.round(t * 255));
    const colours = { flip: (t) => LUT[Math.round(t * 255)], ssim: grey, diff: grey, signed: grey };
    for (const kind of BAR_KINDS) {
      const div = document.createElement("div");
      div.className = "bar";
      div.id = "bar-" + kind;
      div.dataset.kind = kind;
      const c = document.createElement("canvas");
      c.width = 256;
      c.height = 1;
      const ctx = c.getContext("2d");
      const img = ctx.createImageData(256, 1);
      for (let i = 0; i < 256; i++) img.data.set([...colours[kind](i / 255), 255], 4 * i);
      ctx.putImageData(img, 0, 0);
      const part = (cls) => {
        const s = document.createElement("span");
        s.className = cls;
        return s;
      };
      div.append(part("bar-name"), " ", part("bar-lo"), " ", c, " ", part("bar-hi"), " (", part("bar-note"), ")");
      div.hidden = true;
      $("bars").appendChild(div);
    }
  }

  // The bars of what the viewer shows: in a difference mode the
  // difference's, otherwise one per map among the visible layers.
  function showBars(sc) {
    const visible = [];
    if (state.mode === "split" || state.mode === "a") visible.push(layerOf(sc, state.a));
    if (state.mode === "split" || state.mode === "b") visible.push(layerOf(sc, state.b));
    const kinds = isDiff() ? [state.mode] : visible.filter(Boolean).map((l) => l.kind);
    for (const bar of $("bars").children) {
      const kind = bar.dataset.kind;
      bar.hidden = !kinds.includes(kind);
      if (bar.hidden) continue;
      const [name, lo, hi, note] = barLabels(kind);
      bar.querySelector(".bar-name").textContent = name;
      bar.querySelector(".bar-lo").textContent = lo;
      bar.querySelector(".bar-hi").textContent = hi;
      bar.querySelector(".bar-note").textContent = note;
    }
    $("bars").dataset.shown = BAR_KINDS.filter((k) => kinds.includes(k)).join(" ");
  }

  // What the viewer's images are, beside the table's errors: the images
  // are camera offset 0 (the scene's camera) at the quality size, the
  // table's FLIP and SSIM means over the camera offsets each row was
  // measured at (its `offsets`), its edge FLIP offset 0's like the images.
  function showImagesNote(sc) {
    const counts = [...new Set(sc.rows.map((r) => r.offsets).filter((v) => typeof v === "number"))]
      .sort((p, q) => p - q);
    const note = $("images-note");
    note.dataset.offsets = counts.join(" ");
    let table;
    if (!counts.length || counts[counts.length - 1] <= 1) {
      table = "the table's errors are of the same offset, the only one measured";
    } else {
      const n = counts.length === 1 ? String(counts[0]) :
        counts[0] + " to " + counts[counts.length - 1] + " (per row: its offsets column)";
      table = "the table's FLIP and SSIM are means over " + n + " camera offsets" +
        (columnsOf(sc).includes("edge_flip_mean") ? " (its edge FLIP is offset 0's, like the images)" : "");
    }
    note.textContent = "Images: camera offset 0 (the scene's camera) at the quality size, " +
      sc.width + "\u00d7" + sc.height + "; " + table + ".";
  }

  function showCentre() {
    showPixel(Math.floor(state.cx), Math.floor(state.cy), false);
  }

  // Everything the state shows, after any change.
  function render() {
    const sc = scene();
    for (const b of $("scenes").children) b.setAttribute("aria-pressed", String(b.dataset.scene === sc.name));
    const hasImages = sc.layers.length > 0;
    $("viewer").hidden = !hasImages;
    if (hasImages) {
      fillLayerSelect($("layer-a"), sc, state.a);
      fillLayerSelect($("layer-b"), sc, state.b);
      setImage(imgA, layerOf(sc, state.a));
      setImage(imgB, layerOf(sc, state.b));
      const diffText = state.mode === "diff" ? "|A \u2212 B| \u00d7 " + state.scale :
        "128 + " + state.scale + " (A \u2212 B) / 2";
      $("label-a").textContent = (isDiff() ? diffText + ", A: " : "A: ") + layerOf(sc, state.a).label;
      $("label-b").textContent = "B: " + layerOf(sc, state.b).label;
      $("scale").value = String(state.scale);
      $("scale").disabled = !isDiff();
      drawDiff(sc);
      showBars(sc);
      showImagesNote(sc);
      for (const b of document.querySelectorAll("[data-mode]")) {
        b.setAttribute("aria-pressed", String(b.dataset.mode === state.mode));
      }
      $("highlight").value = state.highlight;
      drawHighlight(sc);
      layout();
      showCentre();
    }
    renderTable(sc);
    renderMotion(sc);
    renderPlots(sc);
    writeHash();
  }

  function setZoom(z, atX, atY) {
    // Keep the image point under (atX, atY) (viewport pixels) in place.
    const vw = viewport.clientWidth;
    const vh = viewport.clientHeight;
    const [ox, oy] = offset();
    const px = (atX - ox) / state.zoom;
    const py = (atY - oy) / state.zoom;
    state.zoom = clamp(z, 1, MAX_ZOOM);
    state.cx = clamp(px - (atX - vw / 2) / state.zoom, 0, scene().width);
    state.cy = clamp(py - (atY - vh / 2) / state.zoom, 0, scene().height);
    render();
  }

  function stepZoom(dir, atX, atY) {
    const next = dir > 0 ? ZOOMS.find((z) => z > state.zoom) : [...ZOOMS].reverse().find((z) => z < state.zoom);
    if (next) setZoom(next, atX ?? viewport.clientWidth / 2, atY ?? viewport.clientHeight / 2);
  }

  function toggle() {
    state.mode = state.mode === "a" ? "b" : "a";
    render();
  }

  function bindViewer() {
    $("layer-a").addEventListener("change", (e) => { state.a = e.target.value; render(); });
    $("layer-b").addEventListener("change", (e) => { state.b = e.target.value; render(); });
    for (const b of document.querySelectorAll("[data-mode]")) {
      b.addEventListener("click", () => { state.mode = b.dataset.mode; render(); });
    }
    $("toggle").addEventListener("click", toggle);
    $("zoom-in").addEventListener("click", () => stepZoom(1));
    $("zoom-out").addEventListener("click", () => stepZoom(-1));
    $("highlight").addEventListener("change", (e) => { state.highlight = e.target.value; render(); });
    for (const k of SCALES) $("scale").appendChild(new Option("\u00d7" + k, String(k)));
    $("scale").addEventListener("change", (e) => { state.scale = parseInt(e.target.value, 10); render(); });
    for (const [img, which] of [[imgA, "A"], [imgB, "B"]]) {
      img.addEventListener("error", () => fail("cannot load layer " + which + ": " + img.getAttribute("src")));
    }

    // Dragging: the split handle moves the split, anywhere else pans. The
    // move and up listeners sit on the window for the drag's length.
    viewport.addEventListener("pointerdown", (e) => {
      if (e.button !== 0) return;
      e.preventDefault();
      viewport.focus();
      const onHandle = e.target === handle;
      const start = { x: e.clientX, y: e.clientY, cx: state.cx, cy: state.cy };
      const rect = viewport.getBoundingClientRect();
      viewport.classList.toggle("panning", !onHandle);
      const move = (m) => {
        if (onHandle) {
          state.split = clamp((m.clientX - rect.left) / rect.width, 0, 1);
        } else {
          const sc = scene();
          state.cx = clamp(start.cx - (m.clientX - start.x) / state.zoom, 0, sc.width);
          state.cy = clamp(start.cy - (m.clientY - start.y) / state.zoom, 0, sc.height);
        }
        layout();
      };
      const up = () => {
        window.removeEventListener("pointermove", move);
        window.removeEventListener("pointerup", up);
        viewport.classList.remove("panning");
        render();
      };
      window.addEventListener("pointermove", move);
      window.addEventListener("pointerup", up);
    });
    viewport.addEventListener("pointermove", (e) => {
      const r = viewport.getBoundingClientRect();
      const [ox, oy] = offset();
      showPixel(Math.floor((e.clientX - r.left - ox) / state.zoom),
        Math.floor((e.clientY - r.top - oy) / state.zoom), true);
    });
    viewport.addEventListener("pointerleave", showCentre);
    viewport.addEventListener("wheel", (e) => {
      e.preventDefault();
      const r = viewport.getBoundingClientRect();
      stepZoom(e.deltaY < 0 ? 1 : -1, e.clientX - r.left, e.clientY - r.top);
    }, { passive: false });
    viewport.addEventListener("keydown", (e) => {
      if (e.key === "t") toggle();
      else if (e.key === "+" || e.key === "=") stepZoom(1);
      else if (e.key === "-") stepZoom(-1);
    });
  }

  // --- Results table ------------------------------------------------------

  function cellText(v) {
    if (v === null || v === undefined) return "";
    if (typeof v !== "number") return String(v);
    if (Number.isInteger(v)) return String(v);
    const a = Math.abs(v);
    return a >= 100 ? v.toFixed(1) : a >= 0.001 ? v.toPrecision(4) : v.toExponential(2);
  }

  // Rows in the state's order: missing values last either way, ties in the
  // results' order.
  function sortedRows(rows) {
    if (!state.sort) return rows;
    const [col, dir] = state.sort.split(":");
    const sign = dir === "asc" ? 1 : -1;
    return rows.slice().sort((p, q) => {
      const a = p[col];
      const b = q[col];
      const na = a === null || a === undefined;
      const nb = b === null || b === undefined;
      if (na || nb) return na - nb;
      if (typeof a === "number" && typeof b === "number") return sign * (a - b);
      return sign * String(a).localeCompare(String(b));
    });
  }

  // Every column the table may show: the summary's, then the raw ones.
  function allColumns() {
    return [...R.summary_columns.map(([k]) => k), ...R.columns];
  }

  const titleOf = (c) => (state.raw ? c : (R.summary_columns.find(([k]) => k === c) || [c, c])[1]);

  // The columns (the summary's, or with `raw` every one) with a value on
  // some row of the scene.
  function columnsOf(sc) {
    const cols = state.raw ? R.columns : R.summary_columns.map(([k]) => k);
    return cols.filter((c) => sc.rows.some((r) => r[c] !== null && r[c] !== undefined));
  }

  function renderTable(sc) {
    $("results-title").textContent = "Results: " + sc.name;
    $("raw").checked = state.raw;
    const [col, dir] = state.sort.split(":");
    const columns = columnsOf(sc);
    const head = document.createElement("tr");
    for (const c of columns) {
      const th = document.createElement("th");
      th.textContent = titleOf(c);
      th.dataset.column = c;
      if (c === col) th.setAttribute("aria-sort", dir === "asc" ? "ascending" : "descending");
      head.appendChild(th);
    }
    const thead = $("results-table").tHead;
    thead.textContent = "";
    thead.appendChild(head);
    const tbody = $("results-table").tBodies[0];
    tbody.textContent = "";
    for (const r of sortedRows(sc.rows)) {
      const tr = document.createElement("tr");
      tr.dataset.key = r.method + "/" + r.backend;
      for (const c of columns) {
        const td = document.createElement("td");
        // Verdict cells are report.md's, converted by the report (escaped).
        if (R.html_columns.includes(c)) td.innerHTML = r[c] || "";
        else td.textContent = cellText(r[c]);
        if (typeof r[c] === "number") td.className = "num";
        td.dataset.column = c;
        tr.appendChild(td);
      }
      tbody.appendChild(tr);
    }
  }

  function bindTable() {
    $("raw").addEventListener("change", (e) => { state.raw = e.target.checked; render(); });
    // Numbers sort descending first (largest error or time on top), text
    // ascending.
    $("results-table").tHead.addEventListener("click", (e) => {
      const c = e.target.dataset && e.target.dataset.column;
      if (!c) return;
      const [col, dir] = state.sort.split(":");
      const numeric = scene().rows.some((r) => typeof r[c] === "number");
      const first = numeric ? "desc" : "asc";
      state.sort = c + ":" + (col === c ? (dir === "asc" ? "desc" : "asc") : first);
      render();
    });
  }

  // --- Motion and report.md's sections -------------------------------------

  function renderMotion(sc) {
    $("motion").hidden = !sc.motion;
    if (!sc.motion) return;
    const img = $("motion-img");
    if (img.getAttribute("src") !== sc.motion.src) img.src = sc.motion.src;
    img.alt = sc.motion.caption;
    $("motion-caption").textContent = sc.motion.caption;
  }

  // The answer at a glance: its tables one under the other at the full
  // width, in a small font that wraps long cells; its prose folded into
  // <details> whose summaries sit on the heading's line. The prose before
  // the first table (the regime and the rule) is "how picks are made"; a
  // single short paragraph before a later table (a line on what it holds)
  // stays as its caption, other prose there is folded under the topics
  // its paragraphs begin with, and so is the prose after the last table
  // ("notes: ..."). The text is report.md's, unchanged.
  function compactAnswer(h, div) {
    const groups = [{ prose: [], table: null }];
    for (const el of [...div.children]) {
      if (el.classList.contains("table-wrap")) {
        groups[groups.length - 1].table = el;
        groups.push({ prose: [], table: null });
      } else {
        groups[groups.length - 1].prose.push(el);
      }
    }
    const tables = groups.filter((g) => g.table);
    if (!tables.length) return;
    const folds = [];
    const fold = (summary, els, name) => {
      const d = document.createElement("details");
      d.className = "answer-fold";
      d.dataset.fold = name;
      const s = document.createElement("summary");
      s.textContent = summary;
      d.append(s, ...els);
      folds.push(d);
    };
    const items = tables.map((g, i) => {
      const item = document.createElement("div");
      item.className = "glance-item";
      item.dataset.table = String(i);
      const text = g.prose.map((el) => el.textContent).join(" ");
      if (i === 0) {
        if (g.prose.length) fold("how picks are made", g.prose, "rule");
      } else if (g.prose.length === 1 && g.prose[0].tagName === "P" && text.length <= 300) {
        g.prose[0].classList.add("caption");
        item.appendChild(g.prose[0]);
      } else if (g.prose.length) {
        fold(noteTopics(g.prose) || "about the table below", g.prose, "table-" + (i + 1));
      }
      item.appendChild(g.table);
      return item;
    });
    const after = groups[groups.length - 1].prose;
    if (after.length) fold("notes" + (noteTopics(after) ? ": " + noteTopics(after) : ""), after, "notes");
    const head = document.createElement("div");
    head.className = "answer-head";
    h.replaceWith(head);
    head.append(h, ...folds);
    const glance = document.createElement("div");
    glance.className = "glance";
    glance.append(...items);
    div.textContent = "";
    div.append(glance);
  }

  // What prose is about, from how its paragraphs begin: each one's words
  // up to a colon near its start ("Left out of the fronts"), or its first
  // few words.
  function noteTopics(els) {
    return els.filter((el) => el.tagName === "P").map((el) => {
      const t = el.textContent.trim().replace(/\s+/g, " ");
      const colon = t.indexOf(":");
      if (colon > 0 && colon <= 40) return t.slice(0, colon);
      const words = t.split(" ");
      return words.slice(0, 4).join(" ") + (words.length > 4 ? "\u2026" : "");
    }).join("; ");
  }

  // The answer's font, from 12 px down to 9 px: the largest at which
  // the answer, its folds closed, ends within the window when the page is
  // at its top (so longer cells still leave every pick and front row in
  // sight); the smallest when none does. A window less than FIT_HEIGHT
  // tall (a laptop's 1280x800) is fitted as if it were that tall: no font
  // shrinks below what that needs, and the layout above the viewer is the
  // same in a headless browser's DOM dump (whose window is shorter than it
  // is told) as in its screenshot. `data-font` on #answer says which.
  const ANSWER_FONTS = [12, 11.5, 11, 10.5, 10, 9.5, 9];
  const FIT_HEIGHT = 800;
  function fitAnswer() {
    const box = $("answer");
    const open = [...box.querySelectorAll("details[open]")];
    for (const d of open) d.open = false;
    const height = Math.max(window.innerHeight, FIT_HEIGHT);
    const bottom = () => box.getBoundingClientRect().bottom + window.scrollY;
    let font = ANSWER_FONTS[0];
    for (font of ANSWER_FONTS) {
      box.style.setProperty("--answer-font", font + "px");
      if (bottom() <= height) break;
    }
    box.dataset.font = String(font);
    // Where each of the answer's tables ends (its last row's right and
    // bottom edges on the page, folds closed) and the size fitted to, for
    // checks in a headless browser.
    box.dataset.fit = window.innerWidth + " " + height;
    for (const t of box.querySelectorAll("table")) {
      if (!t.rows.length) continue;
      const r = t.rows[t.rows.length - 1].getBoundingClientRect();
      t.dataset.lastRow = [r.right + window.scrollX, r.bottom + window.scrollY].map(Math.ceil).join(" ");
    }
    for (const d of open) d.open = true;
  }

  // The first section (the report's answer) at the top, the others below
  // the plots; a section asked for that report.md lacks is named.
  function buildSections() {
    R.sections.forEach((s, i) => {
      const sec = document.createElement("section");
      sec.className = "md";
      sec.dataset.heading = s.heading;
      const h = document.createElement("h2");
      h.textContent = s.heading;
      const div = document.createElement("div");
      div.innerHTML = s.html;
      sec.append(h, div);
      if (i === 0) compactAnswer(h, div);
      $(i === 0 ? "answer" : "sections").appendChild(sec);
    });
    body.dataset.sections = R.sections.map((s) => s.heading).join("|");
    if (R.missing_sections.length) {
      body.dataset.missingSections = R.missing_sections.join("|");
      $("missing").textContent = "report.md has no section " +
        R.missing_sections.map((m) => "\u201c" + m + "\u201d").join(", ") + ": not shown here.";
      $("missing").hidden = false;
    }
  }

  // --- Plots --------------------------------------------------------------

  function figures(into, plots) {
    into.textContent = "";
    for (const p of plots) {
      const f = document.createElement("figure");
      const img = document.createElement("img");
      img.src = p.src;
      img.alt = p.title;
      img.loading = "lazy";
      const cap = document.createElement("figcaption");
      cap.textContent = p.title;
      f.append(img, cap);
      into.appendChild(f);
    }
  }

  function renderPlots(sc) {
    figures($("scene-plots"), sc.plots);
  }

  // --- Self-test ----------------------------------------------------------

  // `selftest=1` in the fragment: work every control as a user would and
  // check that the view changes; `data-selftest="pass"` on the body, or
  // `data-error` naming the control that did nothing.
  function selftest() {
    const check = (ok, what) => { if (!ok) throw new Error("selftest: " + what); };
    const pointer = (type, el, x, y) => el.dispatchEvent(new PointerEvent(type, {
      bubbles: true, cancelable: true, clientX: x, clientY: y, button: 0, pointerId: 1, isPrimary: true,
    }));
    const select = (id, value) => {
      $(id).value = value;
      $(id).dispatchEvent(new Event("change", { bubbles: true }));
    };
    const sc = scene();
    const other = sc.layers.find((l) => l.id !== state.a && l.id !== state.b);
    if (other) {
      select("layer-a", other.id);
      check(state.a === other.id && imgA.getAttribute("src") === other.src, "layer A");
      select("layer-b", other.id);
      check(state.b === other.id && imgB.getAttribute("src") === other.src, "layer B");
    }
    const z = state.zoom;
    $(z < MAX_ZOOM ? "zoom-in" : "zoom-out").click();
    check(state.zoom !== z && imgA.style.width === sc.width * state.zoom + "px", "zoom buttons");
    const r = viewport.getBoundingClientRect();
    const [ox, oy] = offset();
    pointer("pointermove", viewport, r.left + ox + 2.5 * state.zoom, r.top + oy + 1.5 * state.zoom);
    const info = $("pixel-info").dataset;
    check(info.x === "2" && info.y === "1" && info.classes === (classesAt(sc, 2, 1) || []).join(" "), "pixel under the cursor");
    $("mode-split").click();
    const hx = r.left + handle.offsetLeft;
    pointer("pointerdown", handle, hx, r.top + 10);
    pointer("pointermove", window, r.left + r.width * 0.25, r.top + 10);
    pointer("pointerup", window, r.left + r.width * 0.25, r.top + 10);
    check(Math.abs(state.split - 0.25) < 0.01 && clipA.style.width === Math.round(r.width * 0.25) + "px", "split drag");
    const cx = state.cx;
    pointer("pointerdown", viewport, r.left + 100, r.top + 100);
    pointer("pointermove", window, r.left + 100 - 4 * state.zoom, r.top + 100);
    pointer("pointerup", window, r.left + 100 - 4 * state.zoom, r.top + 100);
    check(state.cx !== cx || cx === sc.width, "pan drag");
    $("toggle").click();
    const m = state.mode;
    $("toggle").click();
    check(m !== state.mode && ["a", "b"].includes(state.mode), "toggle");
    $("mode-split").click();
    check(state.mode === "split" && !handle.hidden, "split button");
    if (sc.classes) {
      select("highlight", R.classes[0]);
      check(!canvas.hidden && canvas.dataset.highlight === R.classes[0], "highlight");
    }
    $("mode-diff").click();
    check(state.mode === "diff" && clipA.style.width === "0px" && imgB.style.visibility === "hidden" &&
      !diffCanvas.hidden && location.hash.includes("mode=diff"), "difference button");
    check(!$("bar-diff").hidden && $("bars").dataset.shown === "diff", "difference colour bar");
    select("scale", "8");
    check(state.scale === 8 && location.hash.includes("scale=8") &&
      $("bar-diff").querySelector(".bar-hi").textContent === "\u2265 " + levels(255 / 8), "scale");
    $("mode-signed").click();
    check(state.mode === "signed" && location.hash.includes("mode=signed") &&
      !$("bar-signed").hidden && $("bar-diff").hidden, "signed difference button");
    $("mode-split").click();
    const narrow = $("results-table").tHead.rows[0].cells.length;
    $("raw").click();
    const wide = $("results-table").tHead.rows[0].cells.length;
    $("raw").click();
    check(wide > narrow && $("results-table").tHead.rows[0].cells.length === narrow, "every-column toggle");
    const header = () => $("results-table").tHead.querySelector("th[data-column='ms_median']");
    header().click();
    const once = state.sort;
    header().click();
    const twice = state.sort;
    check(once.startsWith("ms_median:") && twice.startsWith("ms_median:") && once !== twice &&
      location.hash.includes("sort=" + twice), "sorting by a header");
    const col = columnsOf(sc).indexOf("ms_median");
    const times = [...$("results-table").tBodies[0].rows].map((tr) => parseFloat(tr.cells[col].textContent));
    const up = twice.endsWith(":asc");
    check(times.every((t, i) => i === 0 || (up ? times[i - 1] <= t : times[i - 1] >= t)), "sorted rows");
    const next = R.scenes.find((s) => s.name !== sc.name);
    if (next) {
      document.querySelector("#scenes button[data-scene='" + next.name + "']").click();
      check(state.scene === next.name && $("results-title").textContent.includes(next.name) &&
        imgB.getAttribute("src").includes("/" + next.name + "/"), "scene buttons");
    }
    body.dataset.selftest = "pass";
  }

  // --- Start --------------------------------------------------------------

  try {
    if (!R.scenes.length) throw new Error("the report has no scene");
    $("run").textContent = R.run;
    $("build").textContent = "build " + R.code;
    body.dataset.code = R.code;
    buildSections();
    fitAnswer();
    buildBars();
    buildSceneButtons();
    for (const c of R.classes) $("highlight").appendChild(new Option(c, c));
    bindViewer();
    bindTable();
    figures($("other-plots"), R.plots);
    readHash();
    render();
    window.addEventListener("hashchange", () => { readHash(); render(); });
    window.addEventListener("resize", () => { fitAnswer(); if (!$("viewer").hidden) layout(); });
    if (state.selftest) selftest();
    body.dataset.ready = "1";
  } catch (e) {
    fail(e.message || String(e));
  }
})();

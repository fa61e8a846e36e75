// The Tessera page: submits scenes, polls the job's small status JSON, and follows the units
// it merges (GET /api/jobs/{id}/tiles, a long poll, docs/SERVICE.md): each unit's 8-bit values
// are painted into a layer per block side as they come (a grid of canvases), finer layers
// stacked over coarser, so every level shows at any image size. The whole PNG is loaded only by a page that joins a
// job too late for the coordinator's log of recent units, and for normalized jobs.
"use strict";

const $ = (id) => document.getElementById(id);
const POLL_MS = 250;
const WORKERS_MS = 1000;
const TILES_WAIT_MS = 10000;  // how long the coordinator may hold a /tiles request
const RATE_WINDOW_MS = 5000;  // a worker's throughput: its pixels over the last few seconds
const PAINT_SLICE_MS = 8;     // script time painting tiles before the browser gets a turn

const view = {
  job: null,          // id of the job shown
  width: 0, height: 0,
  layers: new Map(),  // block side -> {element, step, width, height, tiles}: one pixel per block
  tilesNext: 0,       // the sequence number of the next merged unit to ask for
  levelsPainted: new Set(),        // levels painted while the job was running
  pending: [],        // records held back until their stage is complete ("once per level")
  usedWhole: false,   // the whole PNG was loaded: load the final one at the end too
  wholeIsFinal: false,
  wholeLoadedAt: 0,
  tiles: [],          // [x0, y0, x1, y1, worker, stage] of every unit seen, for the overlay
  latencies: [],      // ms from a unit's merge to its pixels painted
  longestPaintMs: 0,  // the longest script time one answer took to paint
  workerColours: new Map(),
  workerSamples: new Map(),        // worker id -> [[time, pixels_done], ...] within the window
  generation: 0,      // bumps with every job shown: an older /tiles loop stops
  polling: false,
  region: null,       // [x0, y0, x1, y1] of a region job shown over an earlier image (region.js)
  base: null,         // the id of the job whose image a region job is shown over
};

function setting(name) { return document.querySelector(`input[name=${name}]:checked`).value; }

function collectSettings() {
  const s = {
    width: +$("width").value, height: +$("height").value, aa: +$("aa").value,
    stochastic: $("stochastic").checked, jitter: +$("jitter").value, seed: +$("seed").value,
    passes: +$("passes").value, order: setting("order"), preview: setting("preview"),
    progressive: $("progressive").checked, bvh: $("bvh").checked, priority: +$("priority").value,
  };
  if ($("max-depth").value !== "") s.max_depth = +$("max-depth").value;
  if ($("min-weight").value !== "") s.min_weight = +$("min-weight").value;
  return s;
}

function describeError(status, body) {
  if (body && body.error) {
    const where = body.line ? ` (line ${body.line}, column ${body.column})` : "";
    return `${status} ${body.error}${where}: ${body.detail}`;
  }
  return `HTTP ${status}`;
}

// Requests that change state carry the coordinator's API token (--api-token) when it has
// one: asked once, when such a request answers 401, and kept in localStorage. `ask` is false
// for requests the page makes by itself (predictions), which never prompt.
async function fetchWithToken(path, init, ask = true) {
  const send = () => {
    const token = localStorage.getItem("tesseraApiToken");
    const headers = { ...(init.headers || {}) };
    if (token) headers.Authorization = `Bearer ${token}`;
    return fetch(path, { ...init, headers });
  };
  const response = await send();
  if (response.status !== 401 || !ask) return response;
  const token = window.prompt("This coordinator needs its API token (--api-token):");
  if (!token) return response;
  localStorage.setItem("tesseraApiToken", token.trim());
  return send();
}

// The scene format a file name says (as the coordinator and tessera-render read it), or null.
function formatOf(name) {
  const lower = name.toLowerCase();
  if (lower.endsWith(".sdl")) return "sdl";
  if (lower.endsWith(".wrl") || lower.endsWith(".wrl.gz") || lower.endsWith(".wrz")) return "vrml";
  return null;
}
const isText = (name) => /\.(sdl|wrl)$/i.test(name);
// A file's path in the bundle: relative to the chosen folder when a folder was picked.
const bundlePath = (f) => (f.webkitRelativePath || f.name).split("/").slice(
  f.webkitRelativePath ? 1 : 0).join("/");

// The format of a tar bundle's scene: its top-level scene files' (ustar names, 512-byte headers).
async function tarFormat(file) {
  const bytes = new Uint8Array(await file.arrayBuffer());
  const formats = new Set();
  for (let at = 0; at + 512 <= bytes.length;) {
    const header = bytes.subarray(at, at + 512);
    if (header.every((b) => b === 0)) break;
    const text = (from, length) => new TextDecoder().decode(header.subarray(from, from + length)).replace(/\0.*$/s, "");
    const prefix = text(345, 155);
    const name = (prefix ? prefix + "/" : "") + text(0, 100);
    const size = parseInt(text(124, 12).trim() || "0", 8);
    if (!name.includes("/") && formatOf(name)) formats.add(formatOf(name));
    at += 512 + Math.ceil(size / 512) * 512;
  }
  return formats.has("sdl") || formats.size === 0 ? "sdl" : "vrml";
}

// A scene file's text, gzip'd worlds (.wrl.gz, .wrz) inflated; "" when unreadable.
async function sceneText(file) {
  try {
    if (isText(file.name)) return await file.text();
    return await new Response(file.stream().pipeThrough(new DecompressionStream("gzip"))).text();
  } catch (e) {
    return "";
  }
}

// Of several files, the scene to render: the SDL file, else the VRML world that no other scene
// file names (the others being its Inlines), else the first.
async function mainScene(files) {
  const scenes = files.filter((f) => formatOf(f.name));
  const sdl = scenes.find((f) => formatOf(f.name) === "sdl");
  if (sdl) return sdl;
  const texts = await Promise.all(scenes.map(sceneText));
  const named = (f) => texts.some((t, i) => scenes[i] !== f && t.includes(f.name));
  return scenes.find((f) => !named(f)) || scenes[0] || files[0];
}

// POSTs the scene and settings of the form to `path` (/api/jobs, or /api/predict, which takes
// the same request and only answers how long it would take). SDL and VRML alike: a text scene
// as JSON, a compressed world or a scene with its files as a form (binary files stay binary),
// a tar as it is.
async function postScene(path, ask = true) {
  const settings = collectSettings();
  const files = [...$("scene-file").files];
  const file = files[0];
  if (file && file.name.toLowerCase().endsWith(".tar")) {
    const query = new URLSearchParams(Object.entries(settings).map(
      ([k, v]) => [k, Array.isArray(v) ? JSON.stringify(v) : String(v)]));
    query.set("format", await tarFormat(file));
    return fetchWithToken(`${path}?${query}`, {
      method: "POST", headers: { "Content-Type": "application/x-tar" }, body: file }, ask);
  }
  if (files.length > 1 || (file && !isText(file.name))) {
    // The scene and the files it names, as a form; file names are their bundle paths.
    const main = await mainScene(files);
    const form = new FormData();
    form.append("main", bundlePath(main));
    form.append("format", formatOf(main.name) || "sdl");
    form.append("settings", JSON.stringify(settings));
    for (const f of files) form.append("file", f, bundlePath(f));
    return fetchWithToken(path, { method: "POST", body: form }, ask);
  }
  const scene = file ? await file.text() : $("scene-text").value;
  const format = file ? formatOf(file.name) || "sdl" : /^\s*#VRML/.test(scene) ? "vrml" : "sdl";
  return fetchWithToken(path, {
    method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ scene, format, settings }) }, ask);
}

// The predicted time of the form's scene with its settings, shown beside the Render button
// and refreshed (debounced) whenever the scene or a setting changes.
let predictTimer = null;
function schedulePrediction() {
  clearTimeout(predictTimer);
  predictTimer = setTimeout(async () => {
    if (!$("scene-text").value.trim() && !$("scene-file").files.length) {
      $("prediction").textContent = "";
      return;
    }
    const response = await postScene("/api/predict", false);
    const body = await response.json().catch(() => null);
    if (response.status === 401) $("prediction").textContent = "needs the API token (asked on Render)";
    else if (response.status !== 200) $("prediction").textContent = "";
    else if (body.predicted_seconds === null) $("prediction").textContent = "no workers connected";
    else $("prediction").textContent =
      `about ${fmtSeconds(body.predicted_seconds)} on ${body.threads} worker threads`;
  }, 300);
}

async function submit(event) {
  event.preventDefault();
  $("submit-error").textContent = "";
  const response = await postScene("/api/jobs", true);
  const body = await response.json().catch(() => null);
  if (response.status !== 201) {
    $("submit-error").textContent = describeError(response.status, body);
    return;
  }
  navigationSubmitted(body.id);
  show(body.id);
  refreshJobs();
}

// A new job of job `id`'s scene and settings, `settings` replacing some (null: back to the
// default), from the coordinator's copy of its bundle: any job can be rendered again, however
// it was submitted (POST /api/jobs/{id}/rerender; navigation.js, region.js).
function rerender(id, settings) {
  return fetchWithToken(`/api/jobs/${id}/rerender`, {
    method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ settings }) });
}

// Shows job `id`. `keepImage`: the old job's pixels stay until the new job's first paint (a
// camera move); a region job (region.js) is shown over `under`, the image of job `base` it
// refines.
function show(id, { keepImage = false, under = null, region = null, base = null } = {}) {
  if (id === view.job) return;
  Object.assign(view, { job: id, width: 0, height: 0, tilesNext: 0, levelsPainted: new Set(),
                        pending: [], usedWhole: false, wholeIsFinal: false, wholeLoadedAt: 0, tiles: [],
                        latencies: [], longestPaintMs: 0, lastState: null, clearOnPaint: keepImage,
                        region, base });
  if (!keepImage) clearImage();
  if (under) {
    Object.assign($("base-canvas"), { width: under.width, height: under.height });
    $("base-canvas").getContext("2d").drawImage(under, 0, 0);
  }
  $("levels-seen").textContent = "";
  $("shown-level").textContent = "-";
  $("job-title").textContent = `Job ${id}`;
  $("download-png").href = `/api/jobs/${id}/image`;
  $("download-exr").href = `/api/jobs/${id}/image?format=exr`;
  $("download-png").classList.remove("disabled");
  $("download-exr").classList.remove("disabled");
  history.replaceState(null, "", `#job=${id}`);
  document.querySelectorAll("#jobs li").forEach((li) =>
    li.classList.toggle("current", +li.dataset.id === id));
  if (!view.polling) poll();
  followTiles(id, ++view.generation);
}

async function poll() {
  view.polling = true;
  const id = view.job;
  try {
    const response = await fetch(`/api/jobs/${id}`, { cache: "no-store" });
    if (response.ok && id === view.job) update(await response.json());
  } catch (e) { /* the coordinator restarted or the network hiccuped: try again */ }
  const job = view.job;
  const finished = view.lastState && !["queued", "running"].includes(view.lastState);
  if (job !== id || !finished) return setTimeout(poll, POLL_MS);
  view.polling = false;
}

function update(job) {
  view.lastState = job.state;
  renderStatus(job);
  navigationUpdate(job);
  if (view.width !== job.width || view.height !== job.height) sizeImage(job.width, job.height);
  if (["failed", "cancelled"].includes(job.state)) $("base-canvas").dataset.state = job.state;
}

// ---- The image: a layer per block side, painted from the tile records ----

// A new job's image starts empty.
function clearImage() {
  dropLayers();
  const base = $("base-canvas");
  base.width = base.height = 0;
  delete base.dataset.state;
  resizeOverlay();
}

// The base canvas stays empty (0 x 0) until a whole PNG is drawn into it.
function sizeImage(width, height) {
  Object.assign(view, { width, height });
  $("stage").style.aspectRatio = `${width} / ${height}`;
  for (const layer of view.layers.values()) placeLayer(layer);
  resizeOverlay();
}

// A layer holds one pixel per block of side `step`; it is shown scaled up by `step` (pixelated),
// so the last, clipped block column and row reach past the image and are cut off by #stage.
function placeLayer(layer) {
  if (!view.width) return;
  const { element, step } = layer;
  element.style.width = `${(100 * layer.width * step) / view.width}%`;
  element.style.height = `${(100 * layer.height * step) / view.height}%`;
  // A region's coarse blocks reach past it: only the region covers the image under it.
  const [x0, y0, x1, y1] = view.region || [0, 0, layer.width * step, layer.height * step];
  const w = layer.width * step, h = layer.height * step;
  element.style.clipPath = view.region ? `inset(${(100 * y0) / h}% ${100 - (100 * x1) / w}% ` +
    `${100 - (100 * y1) / h}% ${(100 * x0) / w}%)` : "";
}

function layerFor(step) {
  let layer = view.layers.get(step);
  if (layer) return layer;
  const element = document.createElement("div");
  element.className = "layer";
  element.dataset.step = step;
  element.style.zIndex = String(40 - Math.log2(step));  // finer over coarser
  layer = { element, step, width: Math.ceil(view.width / step), height: Math.ceil(view.height / step),
            tiles: new Map() };
  placeLayer(layer);
  $("stage").insertBefore(element, $("overlay-canvas"));
  view.layers.set(step, layer);
  return layer;
}

function dropLayers() {
  for (const { element } of view.layers.values()) element.remove();
  view.layers = new Map();
}

// A layer is a grid of canvases of at most LAYER_TILE pixels a side, made as units reach them:
// the browser re-uploads a painted canvas whole at its next frame, which for one 3840x2160
// canvas took Chromium 30 ms of the page's thread every frame while the finest level refined.
const LAYER_TILE = 512;

function layerTile(layer, column, row) {
  const key = row * 65536 + column;
  let tile = layer.tiles.get(key);
  if (tile) return tile;
  const canvas = document.createElement("canvas");
  const x = column * LAYER_TILE, y = row * LAYER_TILE;
  canvas.width = Math.min(LAYER_TILE, layer.width - x);
  canvas.height = Math.min(LAYER_TILE, layer.height - y);
  Object.assign(canvas.style, {
    left: `${(100 * x) / layer.width}%`, top: `${(100 * y) / layer.height}%`,
    width: `${(100 * canvas.width) / layer.width}%`, height: `${(100 * canvas.height) / layer.height}%`,
  });
  layer.element.append(canvas);
  tile = { canvas, ctx: canvas.getContext("2d"), x, y };
  layer.tiles.set(key, tile);
  return tile;
}

// Puts an image whose top left is the layer's pixel (x0, y0) into the tiles it covers.
function putIntoLayer(layer, image, x0, y0) {
  const x1 = x0 + image.width, y1 = y0 + image.height;
  for (let row = Math.floor(y0 / LAYER_TILE); row * LAYER_TILE < y1; ++row) {
    for (let column = Math.floor(x0 / LAYER_TILE); column * LAYER_TILE < x1; ++column) {
      const { ctx, x, y } = layerTile(layer, column, row);
      ctx.putImageData(image, x0 - x, y0 - y, Math.max(0, x - x0), Math.max(0, y - y0), LAYER_TILE, LAYER_TILE);
    }
  }
}

// Parses a /tiles answer (coordinator/http/tile_deltas.h): header, then records with their
// pixels as differences from the previous pixel's bytes.
function parseTiles(buffer) {
  const dv = new DataView(buffer);
  if (buffer.byteLength < 16 || dv.getUint32(0) !== 0x54534431) throw new Error("not a tiles answer");
  const answer = { next: dv.getUint32(4, true), flags: dv.getUint32(12, true), records: [] };
  let at = 16;
  for (let n = dv.getUint32(8, true); n > 0; --n) {
    const r = {
      x0: dv.getUint16(at, true), y0: dv.getUint16(at + 2, true),
      x1: dv.getUint16(at + 4, true), y1: dv.getUint16(at + 6, true),
      step: dv.getUint16(at + 8, true), level: dv.getUint8(at + 10), pass: dv.getUint8(at + 11),
      flags: dv.getUint8(at + 12), stage: dv.getUint16(at + 14, true),
      worker: dv.getUint32(at + 16, true), count: dv.getUint32(at + 20, true),
      mergedAt: dv.getFloat64(at + 24, true),
    };
    r.pixels = new Uint8Array(buffer, at + 32, 3 * r.count);
    at += 32 + 3 * r.count;
    answer.records.push(r);
  }
  return answer;
}

// Paints one record into its layer: each pixel fills its cell, the cells of coarser levels'
// anchors (flag 1) stay as they are.
function paintRecord(r) {
  if (view.clearOnPaint) clearImage();
  view.clearOnPaint = false;
  const layer = layerFor(r.step);
  // A region's units may start between anchors: their first cell is the first anchor inside.
  const x0 = Math.ceil(r.x0 / r.step), y0 = Math.ceil(r.y0 / r.step);
  const cols = Math.ceil(r.x1 / r.step) - x0, rows = Math.ceil(r.y1 / r.step) - y0;
  const skips = (r.flags & 1) !== 0;
  // Skipped cells stay transparent: no record of this layer paints them.
  const image = new ImageData(cols, rows);
  const out = image.data, d = r.pixels;
  let red = 0, green = 0, blue = 0, i = 0;
  for (let y = 0; y < rows; ++y) {
    const skipRow = skips && (y0 + y) % 2 === 0;
    for (let x = 0; x < cols; ++x) {
      if (skipRow && (x0 + x) % 2 === 0) continue;
      red = (red + d[i]) & 255; green = (green + d[i + 1]) & 255; blue = (blue + d[i + 2]) & 255;
      i += 3;
      const o = 4 * (y * cols + x);
      out[o] = red; out[o + 1] = green; out[o + 2] = blue; out[o + 3] = 255;
    }
  }
  putIntoLayer(layer, image, x0, y0);
}

// Follows a job's merged units: asks for those since the last, the coordinator holding the
// request until one merges; paints them; until the job is finished and nothing is left.
async function followTiles(id, generation) {
  const current = () => view.generation === generation;
  while (current()) {
    let answer;
    try {
      const response = await fetch(
        `/api/jobs/${id}/tiles?since=${view.tilesNext}&wait=${TILES_WAIT_MS}`, { cache: "no-store" });
      if (response.status === 404) return;
      if (!response.ok) throw new Error(`HTTP ${response.status}`);
      const buffer = await response.arrayBuffer();
      if (!current()) return;
      answer = parseTiles(buffer);
      if (!view.width) sizeImage(...await jobSize(id));
    } catch (e) {
      await new Promise((r) => setTimeout(r, 500));  // the coordinator restarted: try again
      continue;
    }
    const finished = (answer.flags & 2) !== 0;
    if (answer.flags & 1) await loadWhole(id, finished);
    else await paintAnswer(answer, finished, current);
    if (!current()) return;
    for (const r of answer.records) view.tiles.push([r.x0, r.y0, r.x1, r.y1, r.worker, r.stage]);
    if ($("overlay").checked && answer.records.length) drawOverlay();
    view.tilesNext = answer.next;
    if (finished && !answer.records.length) {
      if (view.usedWhole && !view.wholeIsFinal) await loadWhole(id, true);
      if (current()) $("base-canvas").dataset.state = "done";
      return;
    }
  }
}

async function jobSize(id) {
  const job = await (await fetch(`/api/jobs/${id}`, { cache: "no-store" })).json();
  return [job.width, job.height];
}

// Paints an answer's records, in slices of at most PAINT_SLICE_MS of script between which the
// browser may draw and take input, so that a large answer never holds the page.
async function paintAnswer(answer, finished, current) {
  // "Once per level": a stage's records are held until a later stage's arrive, or the end.
  const perLevel = setting("update") === "level";
  view.pending.push(...answer.records.filter((r) => r.count > 0));
  const newest = Math.max(...view.pending.map((r) => r.stage));
  const now = perLevel && !finished ? view.pending.filter((r) => r.stage < newest) : view.pending;
  view.pending = perLevel && !finished ? view.pending.filter((r) => r.stage >= newest) : [];
  let started = performance.now();
  for (const r of now) {
    if (performance.now() - started > PAINT_SLICE_MS) {
      view.longestPaintMs = Math.max(view.longestPaintMs, performance.now() - started);
      await new Promise((resolve) => setTimeout(resolve, 0));
      if (!current()) return;
      started = performance.now();
    }
    paintRecord(r);
    if (r.level > 0 && !finished) view.levelsPainted.add(r.level);
  }
  view.longestPaintMs = Math.max(view.longestPaintMs, performance.now() - started);
  if (!now.length) return;
  const last = now[now.length - 1];
  $("shown-level").textContent = last.level > 0 ? `level ${last.level}` : `pass ${last.pass + 1}`;
  $("levels-seen").textContent = [...view.levelsPainted].sort((a, b) => a - b).join(",");
  // Painted once the browser draws the next frame: the delay from the coordinator's merge.
  requestAnimationFrame(() => {
    const painted = Date.now();
    for (const r of now) view.latencies.push(painted - r.mergedAt);
    if (view.latencies.length > 100000) view.latencies.splice(0, 50000);
    $("paint-delay").textContent = `${Math.round(painted - last.mergedAt)} ms`;
  });
}

// The whole image as the coordinator has it, when the page is too far behind for the log of
// recent units (or the job is normalized): it becomes the base, the layers start again. While
// the job runs this is fetched at most about once per second per megapixel.
async function loadWhole(id, finished) {
  const interval = Math.max(0, (view.width * view.height) / 1e6 - 0.3) * 1000;
  const wait = view.wholeLoadedAt + interval - Date.now();
  if (!finished && wait > 0) await new Promise((r) => setTimeout(r, wait));
  view.usedWhole = true;
  view.wholeIsFinal = finished;
  view.wholeLoadedAt = Date.now();
  try {
    const response = await fetch(`/api/jobs/${id}/image`, { cache: "no-cache" });
    if (!response.ok || view.job !== id) return;
    const bitmap = await createImageBitmap(await response.blob());
    if (view.job !== id) return;
    sizeImage(bitmap.width, bitmap.height);
    dropLayers();
    view.pending = [];
    view.clearOnPaint = false;
    const base = $("base-canvas");
    if (view.region && base.width === bitmap.width && base.height === bitmap.height) {
      const [x0, y0, x1, y1] = view.region;  // the rest of a region job's image is black
      base.getContext("2d").drawImage(bitmap, x0, y0, x1 - x0, y1 - y0, x0, y0, x1 - x0, y1 - y0);
      return;
    }
    Object.assign(base, { width: bitmap.width, height: bitmap.height });  // cleared, too
    base.getContext("2d").drawImage(bitmap, 0, 0);
  } catch (e) { /* shown again with the next answer */ }
}

// What the page shows, as one full-size canvas: the base, then the layers coarsest first,
// each scaled up by its block side (for the test, and for "copy image").
function composite() {
  const canvas = document.createElement("canvas");
  Object.assign(canvas, { width: view.width, height: view.height });
  const ctx = canvas.getContext("2d");
  ctx.imageSmoothingEnabled = false;
  ctx.fillStyle = "#000";  // as #stage shows what nothing has painted yet
  ctx.fillRect(0, 0, view.width, view.height);
  if ($("base-canvas").width) ctx.drawImage($("base-canvas"), 0, 0);
  if (view.region) {  // as placeLayer clips the layers
    const [x0, y0, x1, y1] = view.region;
    ctx.beginPath();
    ctx.rect(x0, y0, x1 - x0, y1 - y0);
    ctx.clip();
  }
  for (const [step, layer] of [...view.layers].sort((a, b) => b[0] - a[0])) {
    for (const { canvas, x, y } of layer.tiles.values())
      ctx.drawImage(canvas, x * step, y * step, canvas.width * step, canvas.height * step);
  }
  return canvas;
}
window.tessera = {
  composite, show, rerender, view,
  stats: () => ({ latencies: view.latencies.slice(), longestPaintMs: view.longestPaintMs,
                  levelsPainted: [...view.levelsPainted], usedWhole: view.usedWhole,
                  tilesNext: view.tilesNext }),
};

function fmtSeconds(s) {
  if (s === null || s === undefined) return "—";
  if (s < 1) return `${(s * 1000).toFixed(0)} ms`;
  if (s < 120) return `${s.toFixed(1)} s`;
  return `${Math.floor(s / 60)} min ${Math.round(s % 60)} s`;
}

function fmtSmall(x) { return x === 0 ? "0" : x.toExponential(1); }

function renderStatus(job) {
  $("state").textContent = job.state;
  $("level").textContent = `${job.level} of ${job.levels}`;
  $("pass").textContent = `${job.pass + 1} of ${job.passes}`;
  $("percent").textContent = `${job.percent.toFixed(1)} %`;
  $("progress-bar").style.width = `${job.percent}%`;
  // The time left is the rate so far carried forward: it means little until a few percent
  // and about a second of the job are behind it (the coarse levels' first units cost little).
  const settled = job.state !== "running" || (job.percent >= 3 && job.elapsed_seconds >= 1);
  $("eta").textContent = settled ? fmtSeconds(job.eta_seconds) : "—";
  $("predicted").textContent = fmtSeconds(job.predicted_seconds);
  $("elapsed").textContent = fmtSeconds(job.elapsed_seconds);
  $("job-error").textContent = job.error || "";
  $("cancel").disabled = !["queued", "running"].includes(job.state);
  const rows = job.levels_table.map((r, i) => {
    const name = r.level > 0 ? `level ${r.level}${r.preview_only ? " (preview)" : ""}` : `pass ${r.pass + 1}`;
    return `<tr class="${i === job.stage && job.state === "running" ? "current" : ""}">
      <td>${name}</td><td>${r.blocks}</td><td>${r.pixels_per_block}</td><td>${r.traced}</td>
      <td>${r.seconds.toFixed(3)}</td><td>${fmtSmall(r.seconds_per_block)}</td>
      <td>${fmtSmall(r.seconds_per_pixel)}</td><td>${r.units_done}/${r.units}</td></tr>`;
  });
  $("levels-table").tBodies[0].innerHTML = rows.join("");
  drawLevelChart(job.levels_table);
  $("effects").textContent = `Effects: ${job.effects.join(", ") || "none"}` +
    (job.warnings.length ? ` — warnings: ${job.warnings.join("; ")}` : "");
  const s = job.stats;
  $("stats").textContent = `${s.camera_rays} camera, ${s.shadow_rays} shadow, ` +
    `${s.reflection_rays} reflection, ${s.refraction_rays} refraction rays; ` +
    `${s.shape_tests} shape tests, ${s.bvh_nodes} BVH nodes; ${s.nan_samples} NaN samples`;
  view.shares = new Map(job.workers.map((w) => [w.id, w]));
}

// Bars of time per level (and per pass), for the finished job's price of each refinement.
function drawLevelChart(rows) {
  const canvas = $("level-chart");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const longest = Math.max(...rows.map((r) => r.seconds), 1e-9);
  const slot = canvas.width / Math.max(rows.length, 1);
  ctx.font = "10px sans-serif";
  ctx.textAlign = "center";
  rows.forEach((r, i) => {
    const h = (canvas.height - 28) * (r.seconds / longest);
    ctx.fillStyle = r.level > 0 ? "#5b9bd5" : "#f0a35e";
    ctx.fillRect(i * slot + 3, canvas.height - 14 - h, slot - 6, h);
    ctx.fillStyle = "#ccc";
    ctx.fillText(r.level > 0 ? `L${r.level}` : `P${r.pass + 1}`, i * slot + slot / 2, canvas.height - 2);
    ctx.fillText(fmtSeconds(r.seconds), i * slot + slot / 2, canvas.height - 17 - h);
  });
}

function colourOf(worker) {
  if (!view.workerColours.has(worker)) {
    const hue = (view.workerColours.size * 137.508) % 360;  // golden angle: distinct hues
    view.workerColours.set(worker, `hsl(${hue}, 80%, 60%)`);
  }
  return view.workerColours.get(worker);
}

// A worker's recent throughput: pixels done over the last RATE_WINDOW_MS (its whole-life
// average, /api/workers' pixels_per_second, hides a worker that has just slowed down or joined).
function recentRate(w) {
  const now = performance.now();
  const samples = view.workerSamples.get(w.id) || [];
  samples.push([now, w.pixels_done]);
  while (samples.length > 2 && now - samples[1][0] >= RATE_WINDOW_MS) samples.shift();
  view.workerSamples.set(w.id, samples);
  const [t0, p0] = samples[0];
  return now - t0 > 0 ? ((w.pixels_done - p0) * 1000) / (now - t0) : 0;
}

async function refreshWorkers() {
  try {
    const workers = await (await fetch("/api/workers", { cache: "no-store" })).json();
    const ids = new Set(workers.map((w) => w.id));
    for (const id of view.workerSamples.keys()) if (!ids.has(id)) view.workerSamples.delete(id);
    const shares = view.shares || new Map();
    $("workers-table").tBodies[0].innerHTML = workers.map((w) => {
      const share = shares.get(w.id);
      return `<tr><td><span class="swatch" style="background:${colourOf(w.id)}"></span></td>
        <td>${w.name} <small>${w.address}</small></td><td>${w.threads}</td><td>${w.in_flight}</td>
        <td>${Math.round(recentRate(w))}</td>
        <td>${share ? (100 * share.share).toFixed(1) + " %" : "-"}</td></tr>`;
    }).join("");
  } catch (e) { /* shown again on the next tick */ }
}

async function refreshJobs() {
  try {
    const jobs = await (await fetch("/api/jobs", { cache: "no-store" })).json();
    $("jobs").innerHTML = jobs.reverse().map((j) =>
      `<li data-id="${j.id}" class="${j.id === view.job ? "current" : ""}">#${j.id}
        ${j.width}×${j.height} — ${j.state} ${j.percent.toFixed(0)} %</li>`).join("");
  } catch (e) { /* shown again on the next tick */ }
}

// The overlay is as large as the image only while it is shown: Chromium uploads a canvas that
// changed at the next frame, and a cleared 3840x2160 one takes it 30 ms.
function resizeOverlay() {
  const canvas = $("overlay-canvas");
  const [width, height] = $("overlay").checked ? [view.width, view.height] : [0, 0];
  if (canvas.width !== width || canvas.height !== height) Object.assign(canvas, { width, height });
  drawOverlay();
}

function drawOverlay() {
  const canvas = $("overlay-canvas");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  if (!$("overlay").checked) return;
  ctx.lineWidth = 1;
  // The latest stage's tiles: coarser stages' tiles would cover the whole picture.
  if (!view.tiles.length) return;
  const stage = Math.max(...view.tiles.map((t) => t[5]));
  for (const [x0, y0, x1, y1, worker] of view.tiles.filter((t) => t[5] === stage)) {
    ctx.fillStyle = colourOf(worker).replace("60%)", "60%, 0.18)").replace("hsl", "hsla");
    ctx.strokeStyle = colourOf(worker);
    ctx.fillRect(x0, y0, x1 - x0, y1 - y0);
    ctx.strokeRect(x0 + 0.5, y0 + 0.5, x1 - x0 - 1, y1 - y0 - 1);
  }
}

$("submit-form").addEventListener("submit", submit);
$("submit-form").addEventListener("input", schedulePrediction);
$("submit-form").addEventListener("change", schedulePrediction);
$("cancel").addEventListener("click", async () => {
  if (view.job !== null) await fetchWithToken(`/api/jobs/${view.job}`, { method: "DELETE" });
});
$("overlay").addEventListener("change", resizeOverlay);
$("jobs").addEventListener("click", (e) => {
  const li = e.target.closest("li");
  if (li) show(+li.dataset.id);
});
$("scene-file").addEventListener("change", async () => {
  const files = [...$("scene-file").files];
  if (files.length === 1 && isText(files[0].name)) $("scene-text").value = await files[0].text();
});

setInterval(refreshWorkers, WORKERS_MS);
setInterval(refreshJobs, 2000);
refreshWorkers();
// The job named in the address (#job=N, as scripts/run.sh prints it), else the newest one;
// a new #job=N typed or linked later is followed too.
const namedJob = () => {
  const named = /^#job=(\d+)$/.exec(location.hash);
  return named ? +named[1] : null;
};
window.addEventListener("hashchange", () => {
  if (namedJob() !== null) show(namedJob());
});
refreshJobs().then(() => {
  const first = document.querySelector("#jobs li");
  if (namedJob() !== null) show(namedJob());
  else if (first) show(+first.dataset.id);
});

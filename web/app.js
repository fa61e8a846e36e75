// The Tessera page: submits scenes, polls the job (small JSON) and fetches the image only when
// its version changed (per block) or its level changed (per level); the browser revalidates
// the PNG with its ETag, so an unchanged image is never sent twice.
"use strict";

const $ = (id) => document.getElementById(id);
const POLL_MS = 100;
const WORKERS_MS = 1000;

const view = {
  job: null,          // id of the job shown
  version: -1,        // image version shown
  shownLevel: null,   // level of the image shown (for "once per level" updates)
  levelsSeen: new Set(),
  tilesNext: 0,       // tiles fetched so far, for the overlay
  tiles: [],
  workerColours: new Map(),
  imageUrl: null,
  polling: false,
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

// POSTs the scene and settings of the form to `path` (/api/jobs, or /api/predict, which takes
// the same request and only answers how long it would take).
async function postScene(path, ask = true) {
  const settings = collectSettings();
  const files = [...$("scene-file").files];
  const file = files[0];
  if (files.length > 1) {
    // The scene and the files it names, as a form; file names are their bundle paths.
    const scene = files.find((f) => f.name.endsWith(".sdl")) || file;
    const form = new FormData();
    form.append("main", scene.name);
    form.append("settings", JSON.stringify(settings));
    for (const f of files) form.append("file", f, f.name);
    return fetchWithToken(path, { method: "POST", body: form }, ask);
  }
  if (file && file.name.endsWith(".tar")) {
    const query = new URLSearchParams(Object.entries(settings).map(([k, v]) => [k, String(v)]));
    return fetchWithToken(`${path}?${query}`, {
      method: "POST", headers: { "Content-Type": "application/x-tar" }, body: file }, ask);
  }
  const scene = file ? await file.text() : $("scene-text").value;
  return fetchWithToken(path, {
    method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ scene, format: "sdl", settings }) }, ask);
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
  const response = await postScene("/api/jobs");
  const body = await response.json().catch(() => null);
  if (response.status !== 201) {
    $("submit-error").textContent = describeError(response.status, body);
    return;
  }
  show(body.id);
  refreshJobs();
}

function show(id) {
  Object.assign(view, { job: id, version: -1, shownLevel: null, levelsSeen: new Set(),
                        tilesNext: 0, tiles: [], lastState: null, overlayJob: null });
  $("levels-seen").textContent = "";
  $("job-title").textContent = `Job ${id}`;
  $("download-png").href = `/api/jobs/${id}/image`;
  $("download-exr").href = `/api/jobs/${id}/image?format=exr`;
  $("download-png").classList.remove("disabled");
  $("download-exr").classList.remove("disabled");
  document.querySelectorAll("#jobs li").forEach((li) =>
    li.classList.toggle("current", +li.dataset.id === id));
  if (!view.polling) poll();
}

async function poll() {
  view.polling = true;
  const id = view.job;
  try {
    const response = await fetch(`/api/jobs/${id}`, { cache: "no-store" });
    if (response.ok && id === view.job) await update(await response.json());
  } catch (e) { /* the coordinator restarted or the network hiccuped: try again */ }
  const job = view.job;
  const finished = view.lastState && !["queued", "running"].includes(view.lastState);
  if (job !== id || !finished) return setTimeout(poll, POLL_MS);
  view.polling = false;
}

async function update(job) {
  view.lastState = job.state;
  renderStatus(job);
  const finished = !["queued", "running"].includes(job.state);
  const perLevel = setting("update") === "level";
  const levelChanged = job.level !== view.shownLevel || job.pass !== view.shownPass;
  // Large images cost the coordinator an encoding each: fetch them less often while running.
  const interval = Math.max(0, (job.width * job.height) / 1e6 - 0.3) * 1000;
  const due = finished || Date.now() - (view.loadedAt || 0) >= interval;
  if (job.version !== view.version && (!perLevel || levelChanged || finished) && due) {
    view.loadedAt = Date.now();
    await loadImage(job);
  }
  if ($("overlay").checked) await loadTiles(job);
}

async function loadImage(job) {
  const response = await fetch(`/api/jobs/${job.id}/image`, { cache: "no-cache" });
  if (!response.ok || job.id !== view.job) return;
  const url = URL.createObjectURL(await response.blob());
  const img = $("image");
  const loaded = await new Promise((resolve) => {
    img.onload = () => resolve(true);
    img.onerror = () => resolve(false);
    img.src = url;
  });
  // An image that did not load shows nothing new: the previous one stays, and no version or
  // level is recorded for it, so the next poll fetches it again.
  if (!loaded) {
    if (view.imageUrl) img.src = view.imageUrl;
    return URL.revokeObjectURL(url);
  }
  if (view.imageUrl) URL.revokeObjectURL(view.imageUrl);
  view.imageUrl = url;
  view.version = job.version;
  view.shownLevel = job.level;
  view.shownPass = job.pass;
  // The level whose blocks the picture shows: a finished level, or the one being refined.
  view.levelsSeen.add(job.level);
  $("levels-seen").textContent = [...view.levelsSeen].join(",");
  $("shown-level").textContent = `${job.level} / ${job.levels}`;
  img.dataset.state = job.state;
  img.dataset.version = job.version;
  resizeOverlay();
}

function fmtSeconds(s) {
  if (s === null || s === undefined) return "-";
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
  $("eta").textContent = fmtSeconds(job.eta_seconds);
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

async function refreshWorkers() {
  try {
    const workers = await (await fetch("/api/workers", { cache: "no-store" })).json();
    const shares = view.shares || new Map();
    $("workers-table").tBodies[0].innerHTML = workers.map((w) => {
      const share = shares.get(w.id);
      return `<tr><td><span class="swatch" style="background:${colourOf(w.id)}"></span></td>
        <td>${w.name} <small>${w.address}</small></td><td>${w.threads}</td><td>${w.in_flight}</td>
        <td>${Math.round(w.pixels_per_second)}</td>
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

async function loadTiles(job) {
  if (job.tiles === view.tilesNext) return;
  const response = await fetch(`/api/jobs/${job.id}/tiles?since=${view.tilesNext}`, { cache: "no-store" });
  if (!response.ok) return;
  const body = await response.json();
  view.tiles.push(...body.tiles);
  view.tilesNext = body.next;
  view.overlayJob = job;
  drawOverlay();
}

function resizeOverlay() {
  const canvas = $("overlay-canvas");
  const img = $("image");
  canvas.width = img.naturalWidth;
  canvas.height = img.naturalHeight;
  drawOverlay();
}

function drawOverlay() {
  const canvas = $("overlay-canvas");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  if (!$("overlay").checked) return;
  ctx.lineWidth = 1;
  // The latest stage's tiles: coarser stages' tiles would cover the whole picture.
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
$("overlay").addEventListener("change", () => {
  if (!$("overlay").checked) return drawOverlay();
  if (view.overlayJob && view.overlayJob.id === view.job) return drawOverlay();
  view.tiles = []; view.tilesNext = 0;
  fetch(`/api/jobs/${view.job}`).then((r) => r.json()).then(loadTiles);
});
$("jobs").addEventListener("click", (e) => {
  const li = e.target.closest("li");
  if (li) show(+li.dataset.id);
});
$("scene-file").addEventListener("change", async () => {
  const files = [...$("scene-file").files];
  if (files.length === 1 && !files[0].name.endsWith(".tar")) $("scene-text").value = await files[0].text();
});

setInterval(refreshWorkers, WORKERS_MS);
setInterval(refreshJobs, 2000);
refreshWorkers();
// The job named in the address (#job=N, as scripts/run.sh prints it), else the newest one.
refreshJobs().then(() => {
  const named = /^#job=(\d+)$/.exec(location.hash);
  const first = document.querySelector("#jobs li");
  if (named) show(+named[1]);
  else if (first) show(+first.dataset.id);
});

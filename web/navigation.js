// Moving through the scene on the image (issue 21 §3, Glazer's browser): examine (a drag orbits
// about the look-at point, the wheel zooms), walk (arrow keys or WASD move on the ground plane,
// a drag turns) and fly (as walk, and Q/E or PageUp/PageDown move up and down). Each move
// renders the job shown again with the new camera (POST /api/jobs/{id}/rerender with the job
// setting "camera", docs/SERVICE.md), so any job can be moved, whoever submitted it; the image
// keeps the old job's pixels until the new job's first level paints. A move cancels the job
// it leaves only when this page started that job: another client's job runs on for it.
// A drag with Shift held is left to other tools.
"use strict";

const NAV_TURN_PER_PIXEL = 0.005;  // radians a drag turns per pixel
const NAV_STEP = 0.1;              // a key's move, as a share of the eye's distance to look_at
const NAV_DRAG_SUBMIT_MS = 150;    // while dragging, a new job once the pointer rests this long

const nav = {
  job: null,            // the job whose camera is shown
  camera: null,         // {eye, look_at, up, fov}
  format: "sdl",
  viewpoints: [],
  own: new Set(),       // ids of the jobs this page started: a move may cancel them
  moved: new Set(),     // ids of the jobs moves made: their camera is the page's already
  drag: null,           // {x, y} of the last pointer position while dragging
  timer: null,
  busy: false, again: false,
};

// ---- Vectors as [x, y, z] ----
const add = (a, b) => a.map((v, i) => v + b[i]);
const sub = (a, b) => a.map((v, i) => v - b[i]);
const scale = (a, s) => a.map((v) => v * s);
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]];
const norm = (a) => scale(a, 1 / Math.hypot(...a));
// `v` turned by `angle` radians about the unit `axis` (Rodrigues).
function rotate(v, axis, angle) {
  const c = Math.cos(angle), s = Math.sin(angle);
  return add(add(scale(v, c), scale(cross(axis, v), s)), scale(axis, dot(axis, v) * (1 - c)));
}

// ---- The moves: each returns the new camera ----
function orbit(c, dx, dy) {
  const up = norm(c.up);
  let offset = rotate(sub(c.eye, c.look_at), up, -dx * NAV_TURN_PER_PIXEL);
  const right = norm(cross(up, offset));
  const pitched = rotate(offset, right, -dy * NAV_TURN_PER_PIXEL);
  // Never over the pole: the view would run along up.
  if (Math.abs(dot(norm(pitched), up)) < 0.99) offset = pitched;
  return { ...c, eye: add(c.look_at, offset) };
}

function zoom(c, wheelDelta) {
  const offset = scale(sub(c.eye, c.look_at), Math.exp(wheelDelta * 0.001));
  return { ...c, eye: add(c.look_at, offset) };
}

function turn(c, dx, dy, pitch) {
  const up = norm(c.up);
  let ahead = rotate(sub(c.look_at, c.eye), up, -dx * NAV_TURN_PER_PIXEL);
  if (pitch) {
    const pitched = rotate(ahead, norm(cross(ahead, up)), -dy * NAV_TURN_PER_PIXEL);
    if (Math.abs(dot(norm(pitched), up)) < 0.99) ahead = pitched;
  }
  return { ...c, look_at: add(c.eye, ahead) };
}

// Moves eye and look_at together: forward and right on the ground plane (across up), and
// along up when flying.
function step(c, forward, right, rise) {
  const up = norm(c.up), ahead = sub(c.look_at, c.eye);
  const distance = Math.hypot(...ahead) * NAV_STEP;
  const level = sub(ahead, scale(up, dot(ahead, up)));
  const front = Math.hypot(...level) > 1e-9 ? norm(level) : norm(cross(up, norm(cross(ahead, up))));
  const side = norm(cross(front, up));
  const move = scale(add(add(scale(front, forward), scale(side, right)), scale(up, rise)), distance);
  return { ...c, eye: add(c.eye, move), look_at: add(c.look_at, move) };
}

const NAV_KEYS = {  // key -> [forward, right, rise]
  ArrowUp: [1, 0, 0], w: [1, 0, 0], ArrowDown: [-1, 0, 0], s: [-1, 0, 0],
  ArrowLeft: [0, -1, 0], a: [0, -1, 0], ArrowRight: [0, 1, 0], d: [0, 1, 0],
  PageUp: [0, 0, 1], e: [0, 0, 1], PageDown: [0, 0, -1], q: [0, 0, -1],
};

// ---- Showing the camera, and the hooks app.js calls ----
function navMode() { return document.querySelector("input[name=nav-mode]:checked").value; }

function showCamera() {
  const c = nav.camera;
  const triple = (v) => `(${v.map((x) => +x.toFixed(3)).join(", ")})`;
  $("nav-camera").textContent = c
    ? `eye ${triple(c.eye)}, look-at ${triple(c.look_at)}, up ${triple(c.up)}, angle ` +
      `${+c.fov.toFixed(2)}° (${nav.format === "vrml" ? "smaller side" : "vertical"})`
    : "not known for this job";
}

// A job this page started (the form, a region): a move away from it cancels it.
function navigationSubmitted(id) { nav.own.add(id); }

// The job status (app.js update): a newly shown job's camera and Viewpoints.
function navigationUpdate(job) {
  if (job.id === nav.job) return;
  nav.job = job.id;
  // A job a move made keeps the page's camera: further moves may have come since.
  if (!nav.moved.has(job.id)) nav.camera = job.camera;
  nav.format = job.format;
  nav.viewpoints = job.viewpoints || [];
  const select = $("nav-viewpoint");
  select.replaceChildren(new Option("Viewpoints…", ""),
                         ...nav.viewpoints.map((v, i) => new Option(v.name, String(i))));
  select.disabled = nav.viewpoints.length === 0;
  showCamera();
}

// ---- Submitting the moved camera ----
// Renders the job shown again with the camera (a region job: the whole image of the job under
// it), cancelling the job shown if this page started it; one at a time, the latest camera last.
async function resubmit() {
  if (view.job === null || !nav.camera) return;
  if (nav.busy) { nav.again = true; return; }
  nav.busy = true;
  try {
    if (nav.own.has(view.job)) await fetchWithToken(`/api/jobs/${view.job}`, { method: "DELETE" });
    const response = await rerender(view.base ?? view.job, { camera: nav.camera });
    const body = await response.json().catch(() => null);
    if (response.status !== 201) {
      $("submit-error").textContent = describeError(response.status, body);
      return;
    }
    nav.own.add(body.id);
    nav.moved.add(body.id);
    nav.job = body.id;
    show(body.id, { keepImage: true });
    refreshJobs();
  } finally {
    nav.busy = false;
    if (nav.again) { nav.again = false; resubmit(); }
  }
}

function moveTo(camera, now) {
  nav.camera = camera;
  showCamera();
  clearTimeout(nav.timer);
  if (now) resubmit();
  else nav.timer = setTimeout(resubmit, NAV_DRAG_SUBMIT_MS);
}

// ---- Input on the image ----
const navStage = $("stage");
navStage.tabIndex = 0;  // takes the keys once clicked
navStage.addEventListener("pointerdown", (e) => {
  if (e.shiftKey || e.button !== 0 || !nav.camera) return;
  nav.drag = { x: e.clientX, y: e.clientY, moved: false };
  navStage.setPointerCapture(e.pointerId);
  navStage.focus();
});
navStage.addEventListener("pointermove", (e) => {
  if (!nav.drag) return;
  const dx = e.clientX - nav.drag.x, dy = e.clientY - nav.drag.y;
  if (dx === 0 && dy === 0) return;
  Object.assign(nav.drag, { x: e.clientX, y: e.clientY, moved: true });
  const mode = navMode();
  moveTo(mode === "examine" ? orbit(nav.camera, dx, dy) : turn(nav.camera, dx, dy, mode === "fly"),
         false);
});
navStage.addEventListener("pointerup", () => {
  if (nav.drag && nav.drag.moved) moveTo(nav.camera, true);
  nav.drag = null;
});
navStage.addEventListener("wheel", (e) => {
  if (!nav.camera || navMode() !== "examine") return;
  e.preventDefault();
  moveTo(zoom(nav.camera, e.deltaY), false);
}, { passive: false });
navStage.addEventListener("keydown", (e) => {
  const move = NAV_KEYS[e.key.length === 1 ? e.key.toLowerCase() : e.key];
  const mode = navMode();
  if (!move || !nav.camera || mode === "examine" || (move[2] !== 0 && mode !== "fly")) return;
  e.preventDefault();
  moveTo(step(nav.camera, ...move), true);
});
$("nav-viewpoint").addEventListener("change", (e) => {
  const chosen = nav.viewpoints[+e.target.value];
  if (e.target.value !== "" && chosen) moveTo({ ...chosen.camera }, true);
});

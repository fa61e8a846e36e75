// Rendering a region (issue 21 §4, docs/SERVICE.md): shift-drag a rectangle on a finished
// image and its job is rendered again (POST /api/jobs/{id}/rerender) in that rectangle only —
// with the job's settings, or at the higher accuracy chosen beside the image — and painted over
// the image as it refines. The region job's pixels are the whole image's bit for bit at the
// same settings. Any job shown works, however it was submitted.
"use strict";

(() => {
  const { view } = window.tessera;
  const stage = $("stage");
  let drag = null;  // {x, y, box}: where the drag started, in image pixels, and its outline

  // The image pixel under a pointer event, clamped into the image.
  function pixelAt(event) {
    const r = stage.getBoundingClientRect();
    const clamp = (v, n) => Math.min(n - 1, Math.max(0, Math.floor(v)));
    return [clamp(((event.clientX - r.left) / r.width) * view.width, view.width),
            clamp(((event.clientY - r.top) / r.height) * view.height, view.height)];
  }

  // [x0, y0, x1, y1], half open, of the rectangle between two pixels (both inside it).
  const rectangle = ([ax, ay], [bx, by]) =>
    [Math.min(ax, bx), Math.min(ay, by), Math.max(ax, bx) + 1, Math.max(ay, by) + 1];

  function placeBox(box, [x0, y0, x1, y1]) {
    Object.assign(box.style, {
      left: `${(100 * x0) / view.width}%`, top: `${(100 * y0) / view.height}%`,
      width: `${(100 * (x1 - x0)) / view.width}%`, height: `${(100 * (y1 - y0)) / view.height}%`,
    });
  }

  // What the region job changes of job `base`'s settings: the region, and the accuracy chosen
  // in #region-accuracy.
  async function regionSettings(base, region) {
    const settings = { region };
    const accuracy = $("region-accuracy").value;
    if (accuracy !== "same") settings.aa = 9;
    if (accuracy === "passes") {
      const job = await (await fetch(`/api/jobs/${base}`, { cache: "no-store" })).json();
      settings.passes = Math.min(256, 4 * job.settings.passes);
    }
    return settings;
  }

  async function renderRegion(region) {
    $("region-error").textContent = "";
    const under = window.tessera.composite();
    // A region over a region job refines the image under both: it starts from that job.
    const base = view.base ?? view.job;
    const response = await window.tessera.rerender(base, await regionSettings(base, region));
    const body = await response.json().catch(() => null);
    if (response.status !== 201) {
      $("region-error").textContent = describeError(response.status, body);
      return;
    }
    navigationSubmitted(body.id);
    window.tessera.show(body.id, { under, region, base });
    refreshJobs();
  }

  stage.addEventListener("pointerdown", (event) => {
    const finished = view.lastState === "done";
    if (!event.shiftKey || !finished || !view.width || event.button !== 0) return;
    event.preventDefault();
    stage.setPointerCapture(event.pointerId);
    const box = document.createElement("div");
    box.className = "region-box";
    stage.appendChild(box);
    drag = { from: pixelAt(event), box };
    placeBox(box, rectangle(drag.from, drag.from));
  });
  stage.addEventListener("pointermove", (event) => {
    if (drag) placeBox(drag.box, rectangle(drag.from, pixelAt(event)));
  });
  const end = (event, submit) => {
    if (!drag) return;
    const region = rectangle(drag.from, pixelAt(event));
    drag.box.remove();
    drag = null;
    // A click is no region: at least two pixels each way.
    if (submit && region[2] - region[0] > 1 && region[3] - region[1] > 1) renderRegion(region);
  };
  stage.addEventListener("pointerup", (event) => end(event, true));
  stage.addEventListener("pointercancel", (event) => end(event, false));
})();

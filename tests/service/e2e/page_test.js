// End-to-end test of the page (issue 4 item 7; issue 23 §2; issue 21 §1, §6, §7): a real
// coordinator and a worker, the page in headless Chromium (Debian's), scenes submitted through
// the form.
//
// 1. The demo scene at 1920x1080: the page paints the units as they merge (/tiles), and at
//    least six distinct levels are painted before the job is done. In three stages while the
//    job runs (the worker paused with SIGSTOP, so that nothing depends on timing) and at the end,
//    what the page shows is compared pixel for pixel with the server's PNG.
// 2. A gzip'd VRML world with an Inline and an image texture, chosen as three files in the
//    form's file input, is submitted as VRML and renders; the page shows its final PNG.
// 3. Navigation: a drag in examine mode on a running job the form submitted cancels it and
//    renders the same world and settings with another camera. A job submitted through the API
//    (not this page), shown after a reload, is moved the same way, and left running.
// 4. #job=N typed later is followed: the page switches to job 1, its canvas empty at first,
//    then job 1's final image.
//
// usage: node page_test.js BUILD_DIR SOURCE_DIR
"use strict";

const fs = require("fs");
const os = require("os");
const path = require("path");
const zlib = require("zlib");
const { sleep, until, startService, launchChromium, submitScene, submitForm } = require("./harness");

const [buildDir, sourceDir] = process.argv.slice(2);

// In the page: what it shows (its layers composited, tessera.composite()) against the server's
// PNG fetched afresh. Answers the sizes, the PNG's version and how many bytes differ.
async function comparePixels(page, jobId) {
  return page.evaluate(async (id) => {
    const rgba = (canvas) => canvas.width ?
      canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data : new Uint8ClampedArray(0);
    const shown = window.tessera.composite();
    const response = await fetch(`/api/jobs/${id}/image`, { cache: "no-store" });
    const bitmap = await createImageBitmap(await response.blob());
    const served = document.createElement("canvas");
    Object.assign(served, { width: bitmap.width, height: bitmap.height });
    served.getContext("2d").drawImage(bitmap, 0, 0);
    const a = rgba(shown), b = rgba(served);
    let differing = a.length === b.length ? 0 : Math.max(a.length, b.length);
    const colours = new Set();
    for (let i = 0; i < Math.min(a.length, b.length); ++i) {
      differing += a[i] !== b[i];
      if (i % 4 === 0) colours.add((a[i] << 16) | (a[i + 1] << 8) | a[i + 2]);
    }
    const etag = /-(\d+)-png/.exec(response.headers.get("ETag") || "");
    return { servedVersion: etag ? +etag[1] : -1, size: [shown.width, shown.height],
             servedSize: [served.width, served.height], differing, colours: colours.size };
  }, jobId);
}

async function main() {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "tessera-chromium-"));
  let context, service;
  try {
    service = await startService(buildDir, profile, 1);
    const { api, worker } = service;
    context = await launchChromium(profile);
    const page = context.pages()[0] || await context.newPage();
    const pageErrors = [];
    page.on("pageerror", (e) => pageErrors.push(e.message));
    await page.goto(service.base + "/");

    // 1. The demo scene at 1920x1080.
    // The predicted time shows beside the button before anything is submitted. The worker is
    // stopped until the loop below looks, so that the first levels are not over before it does.
    worker.kill("SIGSTOP");
    const jobId = await submitScene(
      page, api, fs.readFileSync(path.join(sourceDir, "scenes", "demo.sdl"), "utf8"), 1920, 1080, 1);
    // The page names the job in the address, so that a reload or a link shows it again.
    await page.waitForFunction((id) => location.hash === `#job=${id}`, jobId, { timeout: 5000 });

    const checked = [];
    for (;;) {
      const job = await api(`/api/jobs/${jobId}`);
      if (job.state !== "running" && job.state !== "queued") break;
      // A stage (level or pass) not checked yet, while the job runs: its picture mixes levels.
      if (job.state === "queued" || job.version === 0 || checked.includes(job.stage) ||
          checked.length >= 3) {
        // The worker runs a moment and, until three stages are checked, is stopped again before
        // the next look: on a loaded machine a look can take longer than several stages.
        worker.kill("SIGCONT");
        await sleep(5);
        if (checked.length < 3) worker.kill("SIGSTOP");
        continue;
      }
      worker.kill("SIGSTOP");
      try {
        // Results already sent still arrive: wait until the version holds still.
        let settled = job;
        for (;;) {
          await sleep(300);
          const again = await api(`/api/jobs/${jobId}`);
          if (again.version === settled.version) break;
          settled = again;
        }
        if (settled.state !== "running") break;
        // The page has painted every unit merged so far.
        await page.waitForFunction((n) => window.tessera.stats().tilesNext === n, settled.tiles,
                                   { timeout: 10000 });
        const seen = await comparePixels(page, jobId);
        console.log(`level ${settled.level} of ${settled.levels}, ${settled.tiles} units: ` +
                    `${seen.differing} bytes differ from the server's image`);
        if (seen.differing !== 0 || seen.servedVersion !== settled.version)
          throw new Error(`the page shows other pixels than the server's image: ${JSON.stringify(seen)}`);
        checked.push(settled.stage);
      } finally {
        worker.kill("SIGCONT");
      }
    }
    console.log(`stages checked pixel for pixel while running: ${checked.join(", ")}`);
    if (checked.length < 3) throw new Error(`only ${checked.length} intermediate stages checked`);

    await page.waitForSelector("#base-canvas[data-state=done]", { timeout: 120000 });
    const final = await comparePixels(page, jobId);
    if (final.size[0] !== 1920 || final.size[1] !== 1080 || final.differing !== 0)
      throw new Error(`the final image shown is not the server's: ${JSON.stringify(final)}`);
    const stats = await page.evaluate(() => window.tessera.stats());
    console.log(`levels painted before the job was done: ${stats.levelsPainted.join(", ")}`);
    if (stats.levelsPainted.length < 6)
      throw new Error(`only ${stats.levelsPainted.length} levels painted before the end`);
    if (stats.usedWhole) throw new Error("a page following from the start loaded the whole PNG");
    const rows = await page.$$eval("#levels-table tbody tr", (trs) => trs.length);
    if (rows < 3) throw new Error("the per-level table is missing");
    const predicted = await page.textContent("#predicted");
    if (!/\d/.test(predicted)) throw new Error(`no predicted time on the status: ${predicted}`);
    // The chart of time per level has drawn bars (some non-transparent pixels).
    const inked = await page.$eval("#level-chart", (c) =>
      c.getContext("2d").getImageData(0, 0, c.width, c.height).data.some((v, i) => i % 4 === 3 && v > 0));
    if (!inked) throw new Error("the chart of time per level is empty");
    // The overlay of which worker rendered each unit: drawn over the image while it is shown,
    // and then only (a hidden image-sized canvas would cost every frame an upload).
    const overlay = () => page.$eval("#overlay-canvas", (c) => ({
      size: [c.width, c.height],
      inked: c.width > 0 &&
        c.getContext("2d").getImageData(0, 0, c.width, c.height).data.some((v, i) => i % 4 === 3 && v > 0),
    }));
    await page.check("#overlay");
    const overlayShown = await overlay();
    await page.uncheck("#overlay");
    const overlayHidden = await overlay();
    if (overlayShown.size.join("x") !== "1920x1080" || !overlayShown.inked || overlayHidden.size[0] !== 0)
      throw new Error(`the worker overlay: ${JSON.stringify({ overlayShown, overlayHidden })}`);

    // 2. A gzip'd VRML world with an Inline and a texture, as three files.
    const world = path.join(profile, "world.wrl.gz");
    const vrml = path.join(sourceDir, "scenes", "vrml");
    fs.writeFileSync(world, zlib.gzipSync(fs.readFileSync(path.join(vrml, "world.wrl"), "utf8")
      .replace("parts/arch.wrl", "arch.wrl").replace("textures/gradient.bmp", "gradient.bmp")));
    fs.copyFileSync(path.join(vrml, "parts", "arch.wrl"), path.join(profile, "arch.wrl"));
    fs.copyFileSync(path.join(vrml, "textures", "gradient.bmp"), path.join(profile, "gradient.bmp"));
    await page.fill("#scene-text", "");
    await page.setInputFiles("#scene-file", ["arch.wrl", "gradient.bmp", "world.wrl.gz"].map(
      (f) => path.join(profile, f)));
    await page.fill("#width", "160");
    await page.fill("#height", "120");
    const vrmlId = await submitForm(page, api, 2);
    await page.waitForSelector("#base-canvas[data-state=done]", { timeout: 60000 });
    const vrmlJob = await api(`/api/jobs/${vrmlId}`);
    console.log(`VRML job ${vrmlId}: ${vrmlJob.state} ${vrmlJob.scene}, effects ${vrmlJob.effects.join(" ")}`);
    if (vrmlJob.state !== "done" || vrmlJob.scene !== "world.wrl.gz" ||
        !vrmlJob.effects.includes("image_texture"))
      throw new Error(`the VRML world did not render as submitted: ${JSON.stringify(vrmlJob)}`);
    const vrmlShown = await comparePixels(page, vrmlId);
    if (vrmlShown.differing !== 0 || vrmlShown.colours < 50)
      throw new Error(`the VRML world's image: ${JSON.stringify(vrmlShown)}`);

    // 3. Navigation: a drag in examine mode on a running job cancels it and submits the same
    // world and settings with another camera; the page shows the new job and its camera.
    worker.kill("SIGSTOP");
    let movedFrom, movedTo;
    try {
      movedFrom = await submitForm(page, api, 3);
      const before = await until("the camera shown", 10000, async () => {
        const shown = await page.textContent("#nav-camera");
        return shown.startsWith("eye") ? shown : null;
      });
      const box = await page.locator("#stage").boundingBox();
      await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
      await page.mouse.down();
      await page.mouse.move(box.x + box.width / 2 + 80, box.y + box.height / 2 + 20, { steps: 5 });
      await page.mouse.up();
      movedTo = await until("the moved job", 10000, async () => {
        const jobs = await api("/api/jobs");
        return jobs.length === 4 ? jobs[jobs.length - 1].id : null;
      });
      await page.waitForFunction((id) => location.hash === `#job=${id}`, movedTo, { timeout: 10000 });
      const from = await api(`/api/jobs/${movedFrom}`), to = await api(`/api/jobs/${movedTo}`);
      console.log(`moved from job ${movedFrom} (${from.state}, eye ${from.camera.eye}) to job ` +
                  `${movedTo} (eye ${to.camera.eye})`);
      if (from.state !== "cancelled") throw new Error(`the moved-from job is ${from.state}`);
      if (!to.settings.camera || JSON.stringify(to.camera) !== JSON.stringify(to.settings.camera) ||
          JSON.stringify(to.camera) === JSON.stringify(from.camera))
        throw new Error(`the new job's camera: ${JSON.stringify([from.camera, to.camera])}`);
      if (to.scene !== from.scene || to.width !== from.width || to.height !== from.height)
        throw new Error("the moved job is not the same request");
      // The page shows the new job's camera once it has fetched that job, a moment after the
      // address changes.
      await until("the camera shown to change", 10000, async () =>
        (await page.textContent("#nav-camera")) !== before);
    } finally {
      worker.kill("SIGCONT");
    }
    await page.waitForSelector("#base-canvas[data-state=done]", { timeout: 60000 });

    // A job submitted through the API, shown after a reload: moved from the coordinator's copy
    // of its scene (POST /api/jobs/{id}/rerender), and left running, since this page did not
    // submit it.
    worker.kill("SIGSTOP");
    try {
      const posted = await (await fetch(service.base + "/api/jobs", {
        method: "POST", headers: { "Content-Type": "application/json" },
        body: JSON.stringify({ scene: fs.readFileSync(path.join(sourceDir, "scenes", "demo.sdl"), "utf8"),
                               settings: { width: 200, height: 150, aa: 5 } }),
      })).json();
      await page.goto(`${service.base}/#job=${posted.id}`);
      await page.reload();
      await page.waitForFunction((n) => document.getElementById("job-title").textContent === `Job ${n}`,
                                 posted.id, { timeout: 10000 });
      await until("the API job's camera shown", 10000, async () =>
        (await page.textContent("#nav-camera")).startsWith("eye"));
      const box = await page.locator("#stage").boundingBox();
      await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
      await page.mouse.down();
      await page.mouse.move(box.x + box.width / 2 - 60, box.y + box.height / 2 - 10, { steps: 5 });
      await page.mouse.up();
      const moved = await until("the job moved from the API's", 10000, async () => {
        const jobs = await api("/api/jobs");
        return jobs.length === 6 ? jobs[jobs.length - 1].id : null;
      });
      await page.waitForFunction((id) => location.hash === `#job=${id}`, moved, { timeout: 10000 });
      const from = await api(`/api/jobs/${posted.id}`), to = await api(`/api/jobs/${moved}`);
      console.log(`moved API job ${posted.id} (${from.state}) to job ${moved} (eye ${to.camera.eye})`);
      if (from.state === "cancelled") throw new Error("the page cancelled a job it did not submit");
      const sorted = (o) => JSON.stringify(Object.entries(o).sort());
      if (sorted(to.settings) !== sorted({ ...from.settings, camera: to.camera }) ||
          JSON.stringify(to.camera) === JSON.stringify(from.camera) || to.scene !== from.scene)
        throw new Error(`the moved API job: ${JSON.stringify([from.settings, to.settings])}`);
    } finally {
      worker.kill("SIGCONT");
    }
    await page.waitForSelector("#base-canvas[data-state=done]", { timeout: 60000 });

    // 4. #job=1 typed later: the page follows it, starting from an empty canvas.
    const fresh = await page.evaluate((id) => new Promise((resolve) => {
      window.addEventListener("hashchange", () => resolve({
        title: document.getElementById("job-title").textContent,
        layers: document.querySelectorAll("#stage [data-step]").length,
        base: document.getElementById("base-canvas").width,
      }), { once: true });
      location.hash = `#job=${id}`;
    }), jobId);
    if (fresh.title !== `Job ${jobId}` || fresh.layers !== 0 || fresh.base !== 0)
      throw new Error(`the hash change did not start job ${jobId} afresh: ${JSON.stringify(fresh)}`);
    await page.waitForSelector("#base-canvas[data-state=done]", { timeout: 30000 });
    const again = await comparePixels(page, jobId);
    if (again.differing !== 0) throw new Error(`job ${jobId} shown again: ${JSON.stringify(again)}`);
    if (pageErrors.length) throw new Error(`errors in the page: ${pageErrors.join("; ")}`);
  } finally {
    if (context) await context.close();
    if (service) service.stop();
    fs.rmSync(profile, { recursive: true, force: true });
  }
}

main().then(() => console.log("page e2e passed"), (e) => {
  console.error(e);
  process.exit(1);
});

// End-to-end test of rendering a region from the page (issue 21 §4): a real coordinator and a
// worker, the page in headless Chromium.
//
// The demo scene at 160x120 is rendered; a shift-drag on the finished image submits the same
// scene with the settings of the job and the dragged rectangle as `region` ("same settings").
// The new job's region is the dragged pixels, it traces only them, and since a region's pixels
// are the whole image's bit for bit, what the page shows once it is done equals the first image
// everywhere: inside the rectangle the region's pixels, outside it the earlier image kept under.
//
// usage: node region_page_test.js BUILD_DIR SOURCE_DIR
"use strict";

const fs = require("fs");
const os = require("os");
const path = require("path");
const { until, startService, launchChromium, submitScene } = require("./harness");

const [buildDir, sourceDir] = process.argv.slice(2);

// What the page shows, as RGBA bytes.
const shown = (page) => page.evaluate(() => {
  const c = window.tessera.composite();
  return Array.from(c.getContext("2d").getImageData(0, 0, c.width, c.height).data);
});

async function main() {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "tessera-chromium-"));
  let context, service;
  try {
    service = await startService(buildDir, profile, 2);
    const { api } = service;
    context = await launchChromium(profile);
    const page = context.pages()[0] || await context.newPage();
    const pageErrors = [];
    page.on("pageerror", (e) => pageErrors.push(e.message));
    await page.goto(service.base + "/");
    const first = await submitScene(
      page, api, fs.readFileSync(path.join(sourceDir, "scenes", "demo.sdl"), "utf8"), 160, 120, 5);
    await page.waitForFunction(() => document.getElementById("base-canvas").dataset.state === "done",
                               null, { timeout: 60000 });
    const before = await shown(page);

    // Shift-drag from pixel (40, 30) to pixel (99, 79): the region [40, 30, 100, 80].
    await page.selectOption("#region-accuracy", "same");
    await page.locator("#stage").scrollIntoViewIfNeeded();
    const box = await page.locator("#stage").boundingBox();
    const at = (x, y) => [box.x + ((x + 0.5) * box.width) / 160, box.y + ((y + 0.5) * box.height) / 120];
    await page.keyboard.down("Shift");
    await page.mouse.move(...at(40, 30));
    await page.mouse.down();
    await page.mouse.move(...at(70, 50), { steps: 3 });
    await page.mouse.move(...at(99, 79), { steps: 3 });
    await page.mouse.up();
    await page.keyboard.up("Shift");

    const second = await until("the region job", 10000, async () => {
      const jobs = await api("/api/jobs");
      return jobs.length === 2 ? jobs[1].id : null;
    });
    await page.waitForFunction((n) => document.getElementById("job-title").textContent === `Job ${n}`,
                               second, { timeout: 10000 });
    const job = await until("the region job to finish", 60000, async () => {
      const j = await api(`/api/jobs/${second}`);
      return j.state === "done" ? j : null;
    });
    const region = job.settings.region;
    if (JSON.stringify(region) !== JSON.stringify([40, 30, 100, 80]))
      throw new Error(`the region job's region is ${JSON.stringify(region)}, not [40, 30, 100, 80]`);
    const firstJob = await api(`/api/jobs/${first}`);
    for (const key of ["width", "height", "aa", "seed", "passes"])
      if (job.settings[key] !== firstJob.settings[key]) throw new Error(`settings.${key} differs`);
    const traced = job.levels_table.reduce((n, row) => n + row.traced, 0);
    if (traced !== 60 * 50) throw new Error(`the region job traced ${traced} pixels, not 3000`);
    await page.waitForFunction(() => document.getElementById("base-canvas").dataset.state === "done",
                               null, { timeout: 60000 });
    const after = await shown(page);
    let differing = 0;
    for (let i = 0; i < before.length; ++i) differing += before[i] !== after[i];
    if (before.length !== 160 * 120 * 4 || differing !== 0)
      throw new Error(`the page shows ${differing} bytes other than the first image after the region`);
    if (pageErrors.length) throw new Error("page errors: " + pageErrors.join("; "));
    console.log("region page test passed");
  } finally {
    if (context) await context.close();
    if (service) service.stop();
    fs.rmSync(profile, { recursive: true, force: true });
  }
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});

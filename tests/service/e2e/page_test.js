// End-to-end test of the page (issue 4, item 7; issue 23, §2): a real coordinator and a worker,
// the page in headless Chromium (Debian's), a scene submitted through the form. The test reads
// the pixels the page shows and compares them with the server's image of the same version:
// at three or more intermediate levels (painted while the job runs, finer levels still to
// come) and at the end. So that this does not depend on timing, the test stops the worker
// (SIGSTOP) whenever the job reaches a level it has not checked yet, waits for the image to
// settle and the page to show it, compares, and lets the worker go on (SIGCONT).
//
// usage: node page_test.js BUILD_DIR SOURCE_DIR
"use strict";

const { chromium } = require("playwright-core");
const { spawn } = require("child_process");
const fs = require("fs");
const os = require("os");
const path = require("path");

const [buildDir, sourceDir] = process.argv.slice(2);

// The coordinator listens on ports the system picks and writes them to --port-file once both
// listen, so the test never races another program for a port.
async function readPortFile(file, coordinator, ms) {
  const deadline = Date.now() + ms;
  while (!fs.existsSync(file)) {
    if (coordinator.exitCode !== null) throw new Error(`the coordinator exited (${coordinator.exitCode})`);
    if (Date.now() > deadline) throw new Error("the coordinator did not write its ports");
    await new Promise((r) => setTimeout(r, 20));
  }
  return JSON.parse(fs.readFileSync(file, "utf8"));
}

async function waitForHttp(url, ms) {
  const deadline = Date.now() + ms;
  for (;;) {
    try {
      if ((await fetch(url)).ok) return;
    } catch (e) { /* not listening yet */ }
    if (Date.now() > deadline) throw new Error(`${url} did not answer`);
    await new Promise((r) => setTimeout(r, 50));
  }
}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function until(what, ms, test) {
  const deadline = Date.now() + ms;
  for (;;) {
    const value = await test();
    if (value) return value;
    if (Date.now() > deadline) throw new Error(`timed out waiting for ${what}`);
    await sleep(20);
  }
}

// In the page: the pixels of the image it shows, and those of the server's image fetched
// afresh (no cache, so no revalidation with an old ETag), decoded and drawn the same way.
// Answers both versions and how many bytes differ.
async function comparePixels(page, jobId) {
  return page.evaluate(async (id) => {
    const pixels = (img) => {
      if (!img.naturalWidth) return new Uint8ClampedArray(0);  // a broken or empty image
      const canvas = document.createElement("canvas");
      canvas.width = img.naturalWidth;
      canvas.height = img.naturalHeight;
      const ctx = canvas.getContext("2d");
      ctx.drawImage(img, 0, 0);
      return ctx.getImageData(0, 0, canvas.width, canvas.height).data;
    };
    const shown = document.getElementById("image");
    const response = await fetch(`/api/jobs/${id}/image`, { cache: "no-store" });
    const served = new Image();
    served.src = URL.createObjectURL(await response.blob());
    await served.decode().catch(() => {});
    const a = pixels(shown), b = pixels(served);
    let differing = a.length === b.length ? 0 : Math.max(a.length, b.length);
    for (let i = 0; i < Math.min(a.length, b.length); ++i) differing += a[i] !== b[i];
    const etag = /-(\d+)-png/.exec(response.headers.get("ETag") || "");
    return { shownVersion: +shown.dataset.version, servedVersion: etag ? +etag[1] : -1,
             size: [shown.naturalWidth, shown.naturalHeight], differing };
  }, jobId);
}

async function main() {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "tessera-chromium-"));
  const portFile = path.join(profile, "ports.json");
  // A long --silence-ms: the stopped worker must not be dropped while the test looks.
  const coordinator = spawn(path.join(buildDir, "coordinator", "tessera-coordinator"),
    ["--bind", "127.0.0.1", "--http-port", "0", "--worker-port", "0", "--port-file", portFile,
     "--insecure", "--silence-ms", "120000", "--data-dir", path.join(profile, "data")],
    { stdio: "inherit" });
  let context, worker;
  try {
    const { http_port: httpPort, worker_port: workerPort } =
      await readPortFile(portFile, coordinator, 10000);
    const base = `http://127.0.0.1:${httpPort}`;
    const env = { ...process.env };
    delete env.TESSERA_SECRET;
    worker = spawn(path.join(buildDir, "worker", "tessera-worker"),
      ["--coordinator", `127.0.0.1:${workerPort}`, "--threads", "1", "--name", "page-worker"],
      { stdio: "inherit", env });
    const api = async (route) => (await fetch(base + route, { cache: "no-store" })).json();
    await waitForHttp(`${base}/api/workers`, 10000);
    await until("the worker", 10000, async () => (await api("/api/workers")).length === 1);
    context = await chromium.launchPersistentContext(profile, {
      executablePath: "/usr/bin/chromium",
      headless: true,
      args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync"],
    });
    const page = context.pages()[0] || await context.newPage();
    await page.goto(base + "/");
    await page.fill("#scene-text", fs.readFileSync(path.join(sourceDir, "scenes", "demo.sdl"), "utf8"));
    await page.fill("#width", "640");
    await page.fill("#height", "480");
    await page.selectOption("#aa", "9");
    // The predicted time shows beside the button before anything is submitted.
    await page.waitForFunction(() => /^about .* on 1 worker threads$/.test(
      document.getElementById("prediction").textContent), null, { timeout: 10000 });
    await page.click("#submit");
    const jobId = await until("the job", 10000, async () => {
      const jobs = await api("/api/jobs");
      return jobs.length ? jobs[0].id : null;
    });

    // Every level below the last that the job is seen refining, checked while it is paused.
    const checked = [];
    for (;;) {
      const job = await api(`/api/jobs/${jobId}`);
      if (job.state !== "running" && job.state !== "queued") break;
      // Version 0 is the empty image before the first result: nothing of any level painted.
      if (job.state === "queued" || job.version === 0 || job.level >= job.levels ||
          checked.includes(job.level)) {
        await sleep(5);
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
        await page.waitForFunction((v) =>
          +document.getElementById("image").dataset.version === v, settled.version,
          { timeout: 10000 });
        const seen = await comparePixels(page, jobId);
        const shownLevel = await page.textContent("#shown-level");
        console.log(`level ${settled.level} of ${settled.levels}, version ${settled.version}: ` +
                    `page shows ${shownLevel}, ${seen.differing} bytes differ from the server's`);
        if (seen.differing !== 0)
          throw new Error(`the page shows other pixels than the server's image ${settled.version}`);
        if (seen.shownVersion !== settled.version || seen.servedVersion !== settled.version)
          throw new Error(`versions differ: ${JSON.stringify(seen)} at ${settled.version}`);
        if (shownLevel !== `${settled.level} / ${settled.levels}`)
          throw new Error(`the page names level ${shownLevel}, the job is at ${settled.level}`);
        checked.push(settled.level);
      } finally {
        worker.kill("SIGCONT");
      }
    }
    console.log(`intermediate levels checked pixel for pixel: ${checked.join(", ")}`);
    if (checked.length < 3) throw new Error(`only ${checked.length} intermediate levels checked`);

    await page.waitForSelector("#image[data-state=done]", { timeout: 90000 });
    const final = await comparePixels(page, jobId);
    const done = await api(`/api/jobs/${jobId}`);
    if (final.size[0] !== 640 || final.size[1] !== 480)
      throw new Error(`final image is ${final.size.join("x")}`);
    if (final.shownVersion !== done.version || final.differing !== 0)
      throw new Error(`the final image shown is not the server's: ${JSON.stringify(final)}`);
    const rows = await page.$$eval("#levels-table tbody tr", (trs) => trs.length);
    if (rows < 3) throw new Error("the per-level table is missing");
    const predicted = await page.textContent("#predicted");
    if (!/\d/.test(predicted)) throw new Error(`no predicted time on the status: ${predicted}`);
    // The chart of time per level has drawn bars (some non-transparent pixels).
    const inked = await page.$eval("#level-chart", (c) =>
      c.getContext("2d").getImageData(0, 0, c.width, c.height).data.some((v, i) => i % 4 === 3 && v > 0));
    if (!inked) throw new Error("the chart of time per level is empty");
  } finally {
    if (context) await context.close();
    if (worker) {
      worker.kill("SIGCONT");
      worker.kill("SIGKILL");
    }
    coordinator.kill("SIGTERM");
    fs.rmSync(profile, { recursive: true, force: true });
  }
}

main().then(() => console.log("page e2e passed"), (e) => {
  console.error(e);
  process.exit(1);
});

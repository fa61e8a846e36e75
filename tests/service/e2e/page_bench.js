// The page's figures of docs/PERFORMANCE.md ("The page", issue 21 §1): for the demo scene at
// each size, in headless Chromium with one local worker, the delay from a unit's merge to its
// pixels painted (median and 90th percentile over every unit), the bytes the page received for
// the image (/tiles answers and any PNG, as sent: gzip'd) against the final PNG, and the longest
// task on the page's main thread (Chromium's long tasks: 50 ms and over; 0 when none) and the
// most script in one frame (Chromium's long animation frames: 50 ms and over; 0 when none),
// while the form is filled and sent, and while the job refines. With
// --moves N, then N examine drags on the last size's finished image (issue 21 §3): the time
// from releasing the mouse to the new job's first pixels painted (the old job cancelled, the
// same scene resubmitted with the new camera, its first level rendered and polled).
//
// usage: node page_bench.js BUILD_DIR SOURCE_DIR [--threads N] [--aa A] [--moves N] WxH...
"use strict";

const fs = require("fs");
const os = require("os");
const path = require("path");
const { startService, launchChromium, submitScene } = require("./harness");

const [buildDir, sourceDir, ...rest] = process.argv.slice(2);
const option = (name, fallback) => {
  const i = rest.indexOf(name);
  return i < 0 ? fallback : rest.splice(i, 2)[1];
};
const threads = +option("--threads", "1");
const aa = +option("--aa", "1");
const moves = +option("--moves", "0");
const sizes = rest.length ? rest : ["1920x1080", "3840x2160"];

const quantile = (values, q) => {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted.length ? sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))] : NaN;
};

async function measure(page, service, scene, width, height) {
  let imageBytes = 0;
  const counting = async (request) => {
    if (!/\/api\/jobs\/\d+\/(tiles|image)/.test(request.url())) return;
    imageBytes += (await request.sizes()).responseBodySize;
  };
  page.on("requestfinished", counting);
  const takeLongest = () => page.evaluate(() => {
    const taken = { ...window.longest };
    window.longest = { task: 0, frameScript: 0 };
    return { task: Math.round(taken.task), frameScript: Math.round(taken.frameScript) };
  });
  await takeLongest();
  const id = await submitScene(page, service.api, scene, width, height, aa);
  // Long tasks from here on are the refinement's (before: the form being filled and sent).
  const submitting = await takeLongest();
  await page.waitForSelector("#base-canvas[data-state=done]", { timeout: 600000 });
  page.off("requestfinished", counting);
  const stats = await page.evaluate(() => window.tessera.stats());
  const refining = await takeLongest();
  const job = await service.api(`/api/jobs/${id}`);
  const png = (await (await fetch(`${service.base}/api/jobs/${id}/image`)).arrayBuffer()).byteLength;
  return {
    size: `${width}x${height}`, units: job.tiles, seconds: +job.elapsed_seconds.toFixed(1),
    delay_median_ms: quantile(stats.latencies, 0.5), delay_p90_ms: quantile(stats.latencies, 0.9),
    image_bytes: imageBytes, final_png_bytes: png, ratio: +(imageBytes / png).toFixed(2),
    longest_task_submitting_ms: submitting.task, longest_task_refining_ms: refining.task,
    longest_frame_script_submitting_ms: submitting.frameScript,
    longest_frame_script_refining_ms: refining.frameScript,
    longest_paint_ms: +stats.longestPaintMs.toFixed(1),
    levels_painted: stats.levelsPainted.length, whole_png_loaded: stats.usedWhole,
  };
}

// Drags in examine mode; answers each move's milliseconds from mouse up to the first paint.
async function measureMoves(page, count) {
  await page.locator("#stage").scrollIntoViewIfNeeded();
  const box = await page.locator("#stage").boundingBox();
  const x = box.x + box.width / 2, y = box.y + box.height / 2;
  const delays = [];
  for (let i = 0; i < count; ++i) {
    const before = await page.evaluate(() => window.tessera.view.job);
    await page.mouse.move(x, y);
    await page.mouse.down();
    await page.mouse.move(x + 30, y + 10, { steps: 3 });
    const released = await page.evaluate(() => performance.now());
    await page.mouse.up();
    const painted = await page.waitForFunction((old) => {
      const v = window.tessera.view;
      return v.job !== old && (v.latencies.length > 0 || v.usedWhole) && performance.now();
    }, before, { polling: "raf", timeout: 60000 });
    delays.push(+((await painted.jsonValue()) - released).toFixed(1));
    await page.waitForSelector("#base-canvas[data-state=done]", { timeout: 600000 });
  }
  return { moves: count, first_paint_median_ms: quantile(delays, 0.5),
           first_paint_max_ms: Math.max(...delays), delays_ms: delays };
}

async function main() {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "tessera-bench-"));
  let context, service;
  try {
    service = await startService(buildDir, profile, threads);
    context = await launchChromium(profile);
    const page = context.pages()[0] || await context.newPage();
    await page.addInitScript(() => {
      window.longest = { task: 0, frameScript: 0 };
      new PerformanceObserver((list) => {
        for (const e of list.getEntries()) window.longest.task = Math.max(window.longest.task, e.duration);
      }).observe({ type: "longtask", buffered: true });
      // A long animation frame's script: the scripts Chromium attributes to it (each of 5 ms
      // and over), added up.
      new PerformanceObserver((list) => {
        for (const e of list.getEntries()) {
          const script = e.scripts.reduce((sum, s) => sum + s.duration, 0);
          window.longest.frameScript = Math.max(window.longest.frameScript, script);
        }
      }).observe({ type: "long-animation-frame", buffered: true });
    });
    await page.goto(service.base + "/");
    const scene = fs.readFileSync(path.join(sourceDir, "scenes", "demo.sdl"), "utf8");
    for (const size of sizes) {
      const [width, height] = size.split("x").map(Number);
      console.log(JSON.stringify(await measure(page, service, scene, width, height)));
    }
    if (moves > 0) console.log(JSON.stringify(await measureMoves(page, moves)));
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

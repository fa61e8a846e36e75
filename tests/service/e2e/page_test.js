// End-to-end test of the page (issue 4, item 7): a real coordinator with a local worker, the
// page in headless Chromium (Debian's), a scene submitted through the form; the page must show
// at least three distinct refinement levels and then the final image.
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

async function main() {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "tessera-chromium-"));
  const portFile = path.join(profile, "ports.json");
  const coordinator = spawn(path.join(buildDir, "coordinator", "tessera-coordinator"),
    ["--bind", "127.0.0.1", "--http-port", "0", "--worker-port", "0", "--port-file", portFile,
     "--insecure", "--local-workers", "1", "--local-threads", "1"], { stdio: "inherit" });
  let context;
  try {
    const { http_port: httpPort } = await readPortFile(portFile, coordinator, 10000);
    const base = `http://127.0.0.1:${httpPort}`;
    await waitForHttp(`${base}/api/workers`, 10000);
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
    await page.waitForSelector("#image[data-state=done]", { timeout: 90000 });
    const seen = (await page.textContent("#levels-seen")).split(",").filter(Boolean);
    const size = await page.$eval("#image", (img) => [img.naturalWidth, img.naturalHeight]);
    const rows = await page.$$eval("#levels-table tbody tr", (trs) => trs.length);
    console.log(`levels shown: ${seen.join(", ")}; final image ${size.join("x")}; ${rows} table rows`);
    if (new Set(seen).size < 3) throw new Error(`only ${seen.length} distinct levels shown`);
    if (size[0] !== 640 || size[1] !== 480) throw new Error(`final image is ${size.join("x")}`);
    if (rows < 3) throw new Error("the per-level table is missing");
    const predicted = await page.textContent("#predicted");
    if (!/\d/.test(predicted)) throw new Error(`no predicted time on the status: ${predicted}`);
    // The chart of time per level has drawn bars (some non-transparent pixels).
    const inked = await page.$eval("#level-chart", (c) =>
      c.getContext("2d").getImageData(0, 0, c.width, c.height).data.some((v, i) => i % 4 === 3 && v > 0));
    if (!inked) throw new Error("the chart of time per level is empty");
  } finally {
    if (context) await context.close();
    coordinator.kill("SIGTERM");
    fs.rmSync(profile, { recursive: true, force: true });
  }
}

main().then(() => console.log("page e2e passed"), (e) => {
  console.error(e);
  process.exit(1);
});

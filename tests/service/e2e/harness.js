// What the page's test and its benchmark share: a coordinator with one worker on loopback (ports
// the system picks, read from --port-file so nothing races another program for a port), and
// Debian's Chromium driven by playwright-core.
"use strict";

const { chromium } = require("playwright-core");
const { spawn } = require("child_process");
const fs = require("fs");
const path = require("path");

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

async function readPortFile(file, coordinator, ms) {
  await until("the coordinator's ports", ms, async () => {
    if (coordinator.exitCode !== null) throw new Error(`the coordinator exited (${coordinator.exitCode})`);
    return fs.existsSync(file);
  });
  return JSON.parse(fs.readFileSync(file, "utf8"));
}

// Starts the coordinator (data in `profile`) and one worker of `threads` threads; answers
// {base, api(route) -> JSON, worker, stop()}. A long --silence-ms: a worker stopped with
// SIGSTOP by a test must not be dropped.
async function startService(buildDir, profile, threads, extra = []) {
  const portFile = path.join(profile, "ports.json");
  const coordinator = spawn(path.join(buildDir, "coordinator", "tessera-coordinator"),
    ["--bind", "127.0.0.1", "--http-port", "0", "--worker-port", "0", "--port-file", portFile,
     "--insecure", "--silence-ms", "120000", "--data-dir", path.join(profile, "data"), ...extra],
    { stdio: "inherit" });
  const service = {
    worker: null,
    stop() {
      if (service.worker) {
        service.worker.kill("SIGCONT");
        service.worker.kill("SIGKILL");
      }
      coordinator.kill("SIGTERM");
    },
  };
  try {
    const { http_port: httpPort, worker_port: workerPort } =
      await readPortFile(portFile, coordinator, 10000);
    service.base = `http://127.0.0.1:${httpPort}`;
    service.api = async (route) => (await fetch(service.base + route, { cache: "no-store" })).json();
    const env = { ...process.env };
    delete env.TESSERA_SECRET;
    service.worker = spawn(path.join(buildDir, "worker", "tessera-worker"),
      ["--coordinator", `127.0.0.1:${workerPort}`, "--threads", String(threads), "--name", "page-worker"],
      { stdio: "inherit", env });
    await until("the worker", 10000, async () => {
      try {
        return (await service.api("/api/workers")).length === 1;
      } catch (e) {
        return false;  // not listening yet
      }
    });
  } catch (e) {
    service.stop();
    throw e;
  }
  return service;
}

function launchChromium(profile) {
  return chromium.launchPersistentContext(profile, {
    executablePath: "/usr/bin/chromium",
    headless: true,
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
}

// Fills the form with a scene's text and an image size, waits for the prediction, submits, and
// answers the new job's id once the page shows it.
async function submitScene(page, api, scene, width, height, aa) {
  const before = (await api("/api/jobs")).length;
  await page.fill("#scene-text", scene);
  await page.fill("#width", String(width));
  await page.fill("#height", String(height));
  await page.selectOption("#aa", String(aa));
  await page.waitForFunction(() => /^about .* worker threads$/.test(
    document.getElementById("prediction").textContent), null, { timeout: 10000 });
  return submitForm(page, api, before + 1);
}

// Submits what the form holds; answers the new job's id once the page shows it.
async function submitForm(page, api, count) {
  await page.click("#submit");
  const id = await until("the job", 10000, async () => {
    const jobs = await api("/api/jobs");
    return jobs.length === count ? jobs[jobs.length - 1].id : null;
  });
  await page.waitForFunction((n) => document.getElementById("job-title").textContent === `Job ${n}`,
                             id, { timeout: 10000 });
  return id;
}

module.exports = { sleep, until, startService, launchChromium, submitScene, submitForm };

#!/usr/bin/env python3
"""The cost of durable jobs and of TLS (issue 17 §6), for docs/PERFORMANCE.md, measured side by
side in one run on the 4 s demo job (1280x960, aa 9 jittered: jittered samples are each the
pixel's own, so the job's length does not depend on shared grid samples) with two one-thread
local workers:

- throughput with the data directory on disk, on a tmpfs (/dev/shm: SQLite's and the files'
  writes cost no I/O), and on a tmpfs with TLS on both ports; runs interleaved, medians; the
  coordinator's own CPU seconds per job and per merged unit (tessera_units_finished_total),
  and the store's bytes per job and per unit (tessera_store_bytes after the job, less before);
- restart to the first unit dispatched again, with N finished jobs stored beside the running
  one (--stored 0,10,100): the job is SIGKILLed part way and the coordinator started again on
  the same data directory; from the new process's start to its port file (listening, every
  job restored), to its workers joined, and to the first unit sent
  (tessera_units_dispatched_total at /metrics, polled every 2 ms).

usage: bench/durable_bench.py --build BUILD_DIR [--source .] [--repeats 5] [--restarts 5]
       [--stored 0,10,100] [--width 1280 --height 960 --aa 9]
"""
import argparse
import json
import os
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "service"))
import service_test  # noqa: E402
import tls_test  # noqa: E402
from service_test import SECRET, Service  # noqa: E402

SETTINGS = {"width": 1280, "height": 960, "aa": 9, "stochastic": True}  # --width, --height, --aa
STORED = {"width": 32, "height": 24}  # the finished jobs stored beside the restarted one
WORKERS = ("--local-workers", "2", "--local-threads", "1")


def cpu_seconds(pid):
    """User and system time of a process and its waited-for children so far."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def metric(service, name):
    """A metric without labels from the service's /metrics."""
    status, _, body = service.request("GET", "/metrics")
    assert status == 200, status
    return float(re.search(r"^%s (\S+)$" % name, body.decode(), re.M).group(1))


def run_job(service, scene, settings=None):
    """Seconds from submission to done, and the coordinator's CPU seconds, units merged and
    store bytes added meanwhile."""
    cpu = cpu_seconds(service.coordinator.pid)
    units, stored = (metric(service, "tessera_units_finished_total"),
                     metric(service, "tessera_store_bytes"))
    start = time.perf_counter()
    job_id = service.submit(scene, settings or SETTINGS)["id"]
    while service.get("/api/jobs/%d" % job_id)["state"] in ("queued", "running"):
        time.sleep(0.01)
    seconds = time.perf_counter() - start
    assert service.get("/api/jobs/%d" % job_id)["state"] == "done"
    return (seconds, cpu_seconds(service.coordinator.pid) - cpu,
            metric(service, "tessera_units_finished_total") - units,
            metric(service, "tessera_store_bytes") - stored)


def throughput(args, scene):
    disk = tempfile.TemporaryDirectory(dir="/var/tmp")
    shm = tempfile.TemporaryDirectory(dir="/dev/shm")
    cert, key = tls_test.make_certificate(shm.name, "bench")
    services = {
        "disk": Service(*WORKERS, "--data-dir", os.path.join(disk.name, "data")),
        "tmpfs": Service(*WORKERS, "--data-dir", os.path.join(shm.name, "plain")),
        "tmpfs+TLS": tls_test.TlsService(cert, key, *WORKERS, "--data-dir",
                                         os.path.join(shm.name, "tls")),
    }
    runs = {name: [] for name in services}
    try:
        for service in services.values():
            service.wait_workers(2)
            run_job(service, scene)  # warm-up: page cache, the workers' first preparation
        for _ in range(args.repeats):
            for name, service in services.items():
                runs[name].append(run_job(service, scene))
    finally:
        for service in services.values():
            service.__exit__(None, None, None)
        disk.cleanup()
        shm.cleanup()
    base = statistics.median(r[0] for r in runs["tmpfs"])
    print("| data directory | job, median of %d | throughput / tmpfs | coordinator CPU | "
          "CPU per merged unit | store bytes per job | per unit |" % args.repeats)
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for name, rows in runs.items():
        median = statistics.median(r[0] for r in rows)
        cpu = statistics.median(r[1] for r in rows)
        units = statistics.median(r[2] for r in rows)
        stored = statistics.median(r[3] for r in rows)
        print("| %s | %.3f s (%s) | %.3f | %.3f s | %.0f µs (%d units) | %.0f KB | %.0f B |" % (
            name, median, " ".join("%.2f" % r[0] for r in rows), base / median, cpu,
            1e6 * cpu / units, units, stored / 1024, stored / units))


def dispatched(http_port):
    with urllib.request.urlopen("http://127.0.0.1:%d/metrics" % http_port, timeout=5) as r:
        text = r.read().decode()
    return float(re.search(r"^tessera_units_dispatched_total (\S+)$", text, re.M).group(1))


def restart_times(args, scene, stored):
    """Kill-and-restart cycles of a coordinator holding `stored` finished jobs and one running;
    returns the medians (listening, workers joined, first unit dispatched) in seconds."""
    rows = []
    with tempfile.TemporaryDirectory(dir="/var/tmp") as tmp:
        data = os.path.join(tmp, "data")
        ports = ["--http-port", "0", "--worker-port", "0"]
        log = open(os.path.join(tmp, "coordinator.log"), "w")
        for k in range(args.restarts + 1):
            port_file = os.path.join(tmp, "ports-%d.json" % k)
            start = time.perf_counter()
            proc = subprocess.Popen(
                [service_test.binary("coordinator", "tessera-coordinator"), "--bind", "127.0.0.1",
                 *ports, "--port-file", port_file, "--data-dir", data, "--secret", SECRET,
                 *WORKERS], stdout=log, stderr=subprocess.STDOUT)
            while not os.path.exists(port_file):
                time.sleep(0.002)
            listening = time.perf_counter() - start
            with open(port_file) as f:
                p = json.load(f)
            ports = ["--http-port", str(p["http_port"]), "--worker-port", str(p["worker_port"])]
            http = p["http_port"]

            def get(path):
                with urllib.request.urlopen("http://127.0.0.1:%d%s" % (http, path)) as r:
                    return json.loads(r.read())

            def submit(settings):
                body = json.dumps({"scene": scene, "settings": settings}).encode()
                req = urllib.request.Request("http://127.0.0.1:%d/api/jobs" % http, data=body,
                                             headers={"Content-Type": "application/json"})
                with urllib.request.urlopen(req) as r:
                    return json.loads(r.read())["id"]
            if k == 0:
                for _ in range(stored):
                    small = submit(STORED)
                    while get("/api/jobs/%d" % small)["state"] in ("queued", "running"):
                        time.sleep(0.01)
                job = submit(SETTINGS)
            else:
                while len(get("/api/workers")) < 2:
                    time.sleep(0.002)
                joined = time.perf_counter() - start
                while dispatched(http) < 1:
                    time.sleep(0.002)
                first = time.perf_counter() - start
                progress = get("/api/jobs/%d" % job)["progress"]
                rows.append((listening, joined, first, progress))
                print("%d stored, restart %d: listening %.0f ms, workers %.0f ms, first unit "
                      "%.0f ms (job at %.2f)" % (stored, k, listening * 1e3, joined * 1e3,
                                                 first * 1e3, progress))
            # Kill it again part way through what is left, a tick after the point.
            target = 0.3 + 0.6 * k / (args.restarts + 1)
            while get("/api/jobs/%d" % job)["progress"] < target:
                time.sleep(0.01)
            time.sleep(0.3)
            if get("/api/jobs/%d" % job)["state"] != "running":
                proc.kill()
                raise AssertionError("the job ended before its kill point: make it longer "
                                     "(--width, --height, --aa)")
            proc.send_signal(signal.SIGKILL)
            proc.wait()
    return tuple(statistics.median(r[i] for r in rows) for i in range(3))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", default=".")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--restarts", type=int, default=5)
    parser.add_argument("--stored", default="0,10,100",
                        help="finished jobs in the store at a restart, comma-separated")
    parser.add_argument("--width", type=int, default=SETTINGS["width"])
    parser.add_argument("--height", type=int, default=SETTINGS["height"])
    parser.add_argument("--aa", type=int, default=SETTINGS["aa"])
    args = parser.parse_args()
    service_test.ARGS = args
    SETTINGS.update(width=args.width, height=args.height, aa=args.aa)
    with open(os.path.join(args.source, "scenes", "demo.sdl")) as f:
        scene = f.read()
    throughput(args, scene)
    print("| finished jobs stored | listening | workers joined | first unit dispatched |")
    print("| --- | --- | --- | --- |")
    for stored in [int(n) for n in args.stored.split(",")]:
        medians = restart_times(args, scene, stored)
        print("| %d | %.0f ms | %.0f ms | %.0f ms |" % (stored, *(1e3 * m for m in medians)))


if __name__ == "__main__":
    sys.exit(main())

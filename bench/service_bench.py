#!/usr/bin/env python3
"""Service figures for docs/PERFORMANCE.md (issue 4, item 8), measured side by side in one run:

- latency: from POST /api/jobs to the first level's image in hand (the page's view of it),
  with the workers already connected;
- throughput: the demo scene through the coordinator with 1 and with 2 one-thread workers,
  against tessera-render with 1 and 2 threads on the same image, runs interleaved.

usage: bench/service_bench.py --build BUILD_DIR [--source .] [--repeats 3]
       [--width 640] [--height 480] [--aa 5]
"""
import argparse
import os
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "service"))
import service_test  # noqa: E402  (Service: the real processes on loopback)


def submit_and_time(service, scene, settings):
    """Seconds from submission to the first level's PNG, and to the job's end."""
    start = time.perf_counter()
    job_id = service.submit(scene, settings)["id"]
    first_level = None
    while True:
        job = service.get("/api/jobs/%d" % job_id)
        if first_level is None and job["levels_table"] and job["levels_table"][0]["complete"]:
            status, _, _ = service.request("GET", "/api/jobs/%d/image" % job_id)
            assert status == 200, status
            first_level = time.perf_counter() - start
        if job["state"] not in ("queued", "running"):
            assert job["state"] == "done", job
            return first_level, time.perf_counter() - start
        # Poll hard only for the latency; afterwards as gently as the page (every 100 ms would
        # blur the end time, every 10 ms costs next to nothing).
        time.sleep(0.001 if first_level is None else 0.01)


def cli_seconds(scene_path, settings, threads, out):
    """The CLI's wall time (process start, OpenImageIO, output file included) and the render
    time it reports."""
    argv = [service_test.binary("worker", "tessera-render"), scene_path, "-o", out,
            "--width", str(settings["width"]), "--height", str(settings["height"]),
            "--aa", str(settings["aa"]), "--threads", str(threads)]
    start = time.perf_counter()
    report = subprocess.run(argv, check=True, capture_output=True, text=True).stdout
    wall = time.perf_counter() - start
    render = next(float(line.split()[1]) for line in report.splitlines()
                  if line.startswith("time:"))
    return wall, render


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", default=".")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=480)
    parser.add_argument("--aa", type=int, default=5)
    args = parser.parse_args()
    service_test.ARGS = args
    scene_path = os.path.join(args.source, "scenes", "demo.sdl")
    scene = open(scene_path).read()
    settings = {"width": args.width, "height": args.height, "aa": args.aa}

    keys = ("first_level", "service_1", "service_2", "cli_1", "cli_2", "render_1", "render_2")
    times = {key: [] for key in keys}
    with service_test.Service() as one, service_test.Service() as two:
        one.worker("w1")
        two.worker("w1")
        two.worker("w2")
        one.wait_workers(1)
        two.wait_workers(2)
        for _ in range(args.repeats):
            first, total = submit_and_time(one, scene, settings)
            times["first_level"].append(first)
            times["service_1"].append(total)
            times["service_2"].append(submit_and_time(two, scene, settings)[1])
            for threads in (1, 2):
                wall, render = cli_seconds(scene_path, settings, threads, one.tmp.name + "/a.exr")
                times["cli_%d" % threads].append(wall)
                times["render_%d" % threads].append(render)

    med = {key: statistics.median(values) for key, values in times.items()}
    print("demo.sdl %dx%d aa %d, median of %d interleaved runs" %
          (args.width, args.height, args.aa, args.repeats))
    print("submission to first level's PNG (1 worker): %.1f ms" % (med["first_level"] * 1e3))
    print("service: POST to done; CLI wall: the whole process; CLI render: its reported time")
    print("%-24s %10s %10s %11s %15s" % ("", "service s", "CLI wall s", "CLI render s",
                                          "service/render"))
    for n in (1, 2):
        render = med["render_%d" % n]
        # The CLI reports milliseconds: a tiny smoke render may take "0.000 s".
        ratio = "%15.3f" % (med["service_%d" % n] / render) if render > 0 else "%15s" % "-"
        print("%-24s %10.3f %10.3f %11.3f %s" % (
            "%d worker(s) / %d thread(s)" % (n, n), med["service_%d" % n], med["cli_%d" % n],
            render, ratio))


if __name__ == "__main__":
    main()

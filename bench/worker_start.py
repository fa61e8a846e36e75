#!/usr/bin/env python3
"""Time from starting tessera-worker to the coordinator listing it (handshake done), and
tessera-render of a 1x1 image, each the median of N runs (issue 18 §5), and the coordinator's
own start to listening (its port file written), once.

    bench/worker_start.py BUILD_DIR [--runs N]

Starts a coordinator with no local workers on free ports, then N times: starts a worker,
polls GET /api/workers every millisecond until it appears, and stops it. The poll adds up to a
millisecond; the figure includes the coordinator's side of the handshake."""
import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time
import urllib.request


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("build")
    parser.add_argument("--runs", type=int, default=10)
    args = parser.parse_args()
    coordinator = os.path.join(args.build, "coordinator", "tessera-coordinator")
    worker = os.path.join(args.build, "worker", "tessera-worker")
    render = os.path.join(args.build, "worker", "tessera-render")
    with tempfile.TemporaryDirectory() as tmp:
        ports = os.path.join(tmp, "ports")
        coordinator_begin = time.monotonic()
        coord = subprocess.Popen(
            [coordinator, "--http-port", "0", "--worker-port", "0", "--insecure",
             "--local-workers", "0", "--port-file", ports, "--data-dir",
             os.path.join(tmp, "data")], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            while not os.path.exists(ports):
                time.sleep(0.001)
            coordinator_start = time.monotonic() - coordinator_begin
            port = json.load(open(ports))
            url = "http://127.0.0.1:%d/api/workers" % port["http_port"]
            starts = []
            for _ in range(args.runs):
                begin = time.monotonic()
                w = subprocess.Popen([worker, "--coordinator",
                                      "127.0.0.1:%d" % port["worker_port"], "--threads", "1"],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                while not json.load(urllib.request.urlopen(url)):
                    time.sleep(0.001)
                starts.append(time.monotonic() - begin)
                w.terminate()
                w.wait()
                while json.load(urllib.request.urlopen(url)):
                    time.sleep(0.005)
        finally:
            coord.terminate()
            coord.wait()
        scene = os.path.join(tmp, "one.sdl")
        open(scene, "w").write("sphere\n")
        renders = []
        for _ in range(args.runs):
            begin = time.monotonic()
            subprocess.run([render, scene, "-o", os.path.join(tmp, "one.png"), "--width", "1",
                            "--height", "1", "--quiet"], check=True)
            renders.append(time.monotonic() - begin)
    print("coordinator start to its ports written: %.1f ms (one start)" % (1e3 * coordinator_start))
    print("worker start to handshake: median %.1f ms (min %.1f, max %.1f, %d runs)" %
          (1e3 * statistics.median(starts), 1e3 * min(starts), 1e3 * max(starts), args.runs))
    print("tessera-render 1x1 PNG:    median %.1f ms (min %.1f, max %.1f, %d runs)" %
          (1e3 * statistics.median(renders), 1e3 * min(renders), 1e3 * max(renders), args.runs))


if __name__ == "__main__":
    main()

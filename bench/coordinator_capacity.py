#!/usr/bin/env python3
"""Coordinator capacity benchmark (issue 4, item 8): many fast synthetic workers that speak
the real protocol (docs/PROTOCOL.md) but answer every unit at once with black pixels, so the
coordinator's scheduling, merging and I/O are the only work. Prints work units per second.

usage: coordinator_capacity.py --build BUILD_DIR [--workers 32] [--threads 4] [--size 2048]
       [--passes 4]
The wall-clock rate is a lower bound: this script shares the machine with the coordinator. The
coordinator's own CPU time is reported too; units per coordinator CPU-second is its capacity on
a machine of its own.
"""
import argparse
import asyncio
import hashlib
import hmac
import json
import os
import secrets
import struct
import subprocess
import sys
import tempfile
import time
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "service"))
import service_test  # noqa: E402  (start_coordinator)

SECRET = "capacity-secret"
HELLO, CHALLENGE, AUTH, WELCOME, REJECT, HEARTBEAT, JOB, UNIT, RESULT = range(1, 10)


def frame(kind, header, payload=b""):
    head = json.dumps(header).encode()
    body = struct.pack(">BI", kind, len(head)) + head + payload
    return struct.pack(">I", len(body)) + body


async def read_frame(reader):
    (size,) = struct.unpack(">I", await reader.readexactly(4))
    body = await reader.readexactly(size)
    kind, head_len = struct.unpack(">BI", body[:5])
    return kind, json.loads(body[5:5 + head_len]), body[5 + head_len:]


def pixel_count(p):
    """common/progressive/unit_pixels.cpp's count, for the result's payload size."""
    x0, y0, x1, y1 = p["rect"]
    step, exclude = p["step"], p["exclude"]
    first = lambda v: (v + step - 1) // step * step
    n = 0
    for by in range(first(y0), y1, step):
        for bx in range(first(x0), x1, step):
            if p["pattern"] == "centres" or exclude <= 0 or bx % exclude or by % exclude:
                n += 1
    return n


async def worker(port, index, threads, counter):
    try:
        await serve(port, index, threads, counter)
    except asyncio.CancelledError:
        raise
    except Exception as e:  # a dropped synthetic worker must not go unnoticed
        print("synthetic worker %d: %r" % (index, e), file=sys.stderr)


async def serve(port, index, threads, counter):
    reader, writer = await asyncio.open_connection("127.0.0.1", port)
    nonce = secrets.token_hex(32)
    writer.write(frame(HELLO, {"version": 2, "name": "synthetic-%d" % index,
                               "threads": threads, "nonce": nonce, "cached": []}))
    _, challenge, _ = await read_frame(reader)
    message = "tessera-worker|1|%s|%s" % (challenge["nonce"], nonce)
    proof = hmac.new(SECRET.encode(), message.encode(), hashlib.sha256).hexdigest()
    writer.write(frame(AUTH, {"proof": proof}))
    stats = {"seconds": 0}
    while True:
        kind, header, _ = await read_frame(reader)
        if kind == UNIT:
            count = pixel_count(header["pixels"])
            writer.write(frame(RESULT, {"job": header["job"], "unit": header["unit"],
                                        "count": count, "stats": stats}, bytes(12 * count)))
            counter[0] += 1
        elif kind == REJECT:
            raise SystemExit("refused: %s" % header)
        elif kind == HEARTBEAT:
            writer.write(frame(HEARTBEAT, {}))


def cpu_seconds(pid):
    """User plus system CPU time of a process so far (Linux /proc)."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


async def main(args):
    with tempfile.TemporaryDirectory() as tmp:
        coordinator, http_port, worker_port = service_test.start_coordinator(
            args.build, ["--secret", SECRET], subprocess.DEVNULL, os.path.join(tmp, "ports.json"))
    try:
        get = lambda url: json.load(urllib.request.urlopen(url))
        workers_url = "http://127.0.0.1:%d/api/workers" % http_port
        counter = [0]
        tasks = [asyncio.create_task(worker(worker_port, i, args.threads, counter))
                 for i in range(args.workers)]
        while len(await asyncio.to_thread(get, workers_url)) < args.workers:
            await asyncio.sleep(0.05)
        scene = "sphere\n"
        body = json.dumps({"scene": scene, "settings": {"width": args.size, "height": args.size,
                                                         "passes": args.passes}}).encode()
        request = urllib.request.Request("http://127.0.0.1:%d/api/jobs" % http_port, body,
                                         {"Content-Type": "application/json"})
        job = json.load(urllib.request.urlopen(request))
        start = time.time()
        cpu_start = cpu_seconds(coordinator.pid)
        while True:
            await asyncio.sleep(0.05)
            url = "http://127.0.0.1:%d/api/jobs/%d" % (http_port, job["id"])
            status = await asyncio.to_thread(get, url)
            if status["state"] not in ("queued", "running"):
                break
        elapsed = time.time() - start
        cpu = cpu_seconds(coordinator.pid) - cpu_start
        units = sum(row["units"] for row in status["levels_table"])
        print("%d synthetic workers x %d slots: %d units (%dx%d, %d passes) in %.2f s: "
              "%.0f units/s, %.1f Mpixel/s merged; job %s"
              % (args.workers, args.threads, units, args.size, args.size, args.passes, elapsed,
                 units / elapsed, args.size * args.size * args.passes / elapsed / 1e6,
                 status["state"]))
        print("coordinator CPU: %.2f s, %.0f units per CPU-second" % (cpu, units / cpu))
        for t in tasks:
            t.cancel()
    finally:
        coordinator.kill()
        coordinator.wait()


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--workers", type=int, default=32)
    parser.add_argument("--threads", type=int, default=4)
    parser.add_argument("--size", type=int, default=2048)
    parser.add_argument("--passes", type=int, default=4)
    sys.exit(asyncio.run(main(parser.parse_args())))

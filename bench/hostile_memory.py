#!/usr/bin/env python3
"""Peak memory per hostile request (issue 16 §2, docs/SECURITY.md "Memory per hostile
request"): each hostile input of issue 16 goes to a fresh coordinator (no workers), which is
asked for its peak resident set (VmHWM in /proc/PID/status) before and after, and for the time
it took to answer. A request's peak must stay under the documented ceiling: 512 MB for what a
scene's intake produces, and for a frame the running job's buffers on top of that (14 B a
pixel and 8 MiB of tiles, docs/SERVICE.md "Memory").

usage: bench/hostile_memory.py --build BUILD_DIR [--source .] [--smoke] [--only CASE]
--smoke: smaller inputs and a 2 s intake deadline, for CTest (bench_smoke_hostile_memory);
the statuses are checked, the ceilings only in a full run.
"""
import argparse
import gzip
import io
import json
import os
import socket
import struct
import sys
import tarfile
import time
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "service"))
import hostile_test  # noqa: E402  (the hostile inputs)
import service_test  # noqa: E402
from service_test import Service  # noqa: E402

MB = 1 << 20
CEILING = 512 * MB  # docs/SECURITY.md: the peak of one request's intake
SMALL = {"width": 32, "height": 24}


def status_kb(pid, field):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1]) * 1024
    raise AssertionError("no " + field)


def post(service, path, body, content_type, query=""):
    start = time.perf_counter()
    status, _, reply = service.request("POST", path + query, body,
                                       {"Content-Type": content_type})
    return status, json.loads(reply), time.perf_counter() - start


def post_json(service, path, payload):
    return post(service, path, json.dumps(payload).encode(), "application/json")


def tar_of(files):
    out = io.BytesIO()
    with tarfile.open(fileobj=out, mode="w") as tar:
        for name, data in files.items():
            info = tarfile.TarInfo(name)
            info.size = len(data)
            tar.addfile(info, io.BytesIO(data))
    return out.getvalue()


def inline_world(points):
    """A gzip'd world of one mesh of `points` vertices (a strip of triangles), and a tar whose
    scene Inlines it 16 times, each moved: issue 16's "100 KB tar of 16 Inlines"."""
    coords = ",".join("%d %d %d" % (i % 97, i // 97 % 89, i % 7) for i in range(points))
    faces = ",".join("%d %d %d -1" % (i, i + 1, i + 2) for i in range(points - 2))
    big = gzip.compress(("#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { coord Coordinate "
                         "{ point [%s] } coordIndex [%s] } }\n" % (coords, faces)).encode(), 9)
    scene = "#VRML V2.0 utf8\n" + "".join(
        "Transform { translation %d 0 0 children Inline { url \"big.wrl.gz\" } }\n" % (3 * i)
        for i in range(16))
    return tar_of({"scene.wrl": scene.encode(), "big.wrl.gz": big})


def png_bomb(side):
    """An 8-bit RGB PNG of side x side black pixels: kilobytes that decode to side^2 pixels."""
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff))
    rows = (b"\0" + b"\0" * (3 * side)) * side
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", side, side, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def texture_tar(count, side):
    """An SDL scene naming `count` distinct texture files, each a PNG bomb."""
    png = png_bomb(side)
    lines = ["imageTexture t%d.png 1 1 1\nsphere\n" % i for i in range(count)]
    files = {"t%d.png" % i: png for i in range(count)}
    files["scene.sdl"] = "".join(lines).encode()
    return tar_of(files)


# ---- The cases: each returns (what the answer was, seconds to answer), and is run against a
# fresh coordinator whose peak is read afterwards.

def case_use_chain(service, smoke):
    status, reply, seconds = post_json(service, "/api/jobs", {
        "scene": hostile_test.def_use_bomb(), "format": "vrml", "settings": SMALL})
    # The smoke run's 2 s intake deadline may come first on a loaded machine.
    limits = ("use_replays", "max_intake_seconds") if smoke else ("use_replays",)
    assert status == 422 and reply["limit"] in limits, (status, reply)
    return "%d %s" % (status, reply["limit"]), seconds


def case_use_chain_shapes(service, smoke):
    world = hostile_test.def_use_bomb(12 if smoke else 22, "Shape { geometry Sphere {} }")
    status, reply, seconds = post_json(service, "/api/jobs",
                                       {"scene": world, "format": "vrml", "settings": SMALL})
    if smoke:  # 2**12 spheres fit the budget, in a tenth of the 2 s deadline
        assert status == 201, (status, reply)
        return "%d" % status, seconds
    assert status == 413 and reply["limit"] == "bytes_produced", (status, reply)
    return "%d %s" % (status, reply["limit"]), seconds


def case_inline_tar(service, smoke):
    body = inline_world(20000 if smoke else 400000)
    status, reply, seconds = post(service, "/api/jobs", body, "application/x-tar",
                                  "?format=vrml&main=scene.wrl&width=32&height=24")
    assert status in (201, 413, 422), (status, reply)
    return "%d %s (tar %d KB)" % (status, reply.get("limit", ""), len(body) // 1024), seconds


def case_texture_bomb(service, smoke):
    body = texture_tar(2 if smoke else 8, 1024 if smoke else 4096)
    status, reply, seconds = post(service, "/api/jobs", body, "application/x-tar",
                                  "?main=scene.sdl&width=32&height=24")
    assert status in (201, 413, 422), (status, reply)
    return "%d %s (tar %d KB)" % (status, reply.get("limit", ""), len(body) // 1024), seconds


def case_framing(service, smoke):
    world = hostile_test.framing_bomb(100 if smoke else 200, 10 if smoke else 13)
    status, reply, seconds = post_json(service, "/api/jobs",
                                       {"scene": world, "format": "vrml", "settings": SMALL})
    assert status in (201, 422), (status, reply)
    return "%d %s" % (status, reply.get("limit", "")), seconds


def case_mirror_predict(service, smoke):
    status, reply, seconds = post_json(service, "/api/predict", {
        "scene": hostile_test.MIRROR_HALL, "settings": hostile_test.RUNAWAY})
    assert status == 200 and reply["lower_bound"] is True, (status, reply)
    return "200 lower bound", seconds


def case_huge_frame_cancelled(service, smoke):
    side = {"width": 1024, "height": 1024} if smoke else {"width": 7680, "height": 4320}
    status, reply, submit = post_json(service, "/api/jobs", {"scene": "sphere\n",
                                                             "settings": side})
    assert status == 201, (status, reply)
    start = time.perf_counter()
    status, _, _ = service.request("DELETE", "/api/jobs/%d" % reply["id"])
    assert status == 200
    cancel = time.perf_counter() - start
    return "201, cancel 200 in %.0f ms" % (cancel * 1e3), submit


def case_strangers(service, smoke):
    """Strangers from 13 loopback addresses, each sending 60 KB that is no frame, while the
    API is asked for its workers."""
    count = 40 if smoke else 300
    peers = []
    for i in range(count):
        try:
            s = socket.create_connection(("127.0.0.1", service.worker_port),
                                         source_address=("127.0.0.%d" % (2 + i % 13), 0))
            s.setblocking(False)
            try:
                s.send(b"\xff" * 60000)
            except OSError:
                pass  # closed at once: over the cap
            peers.append(s)
        except OSError:
            pass
    worst = 0
    for _ in range(20):
        start = time.perf_counter()
        assert service.get("/api/workers") == []
        worst = max(worst, time.perf_counter() - start)
    for s in peers:
        s.close()
    return "%d strangers, workers 200" % count, worst


CASES = [("deep USE chain, no shapes (VRML)", case_use_chain),
         ("deep USE chain of spheres (VRML)", case_use_chain_shapes),
         ("Inline bomb tar (16 Inlines of one .wrl.gz)", case_inline_tar),
         ("texture bomb tar (PNGs of 4096x4096)", case_texture_bomb),
         ("framing bomb (no Viewpoint, USEd mesh)", case_framing),
         ("mirror-hall predict", case_mirror_predict),
         ("huge frame (7680x4320) cancelled", case_huge_frame_cancelled),
         ("many strangers on the worker port", case_strangers)]


def ceiling(func):
    """The documented peak for a case: a job's frame (14 B a pixel, 8 MiB of tiles) counts on
    top of the intake's ceiling."""
    if func is case_huge_frame_cancelled:
        return CEILING + 14 * 7680 * 4320 + 8 * MB
    return CEILING


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", default=".")
    parser.add_argument("--smoke", action="store_true")
    parser.add_argument("--only", help="a case's function name without case_")
    args = parser.parse_args()
    service_test.ARGS = args
    flags = ["--max-intake-seconds", "2"] if args.smoke else []
    print("| hostile input | answer | time to answer | RSS before | peak (VmHWM) | RSS after |")
    print("| --- | --- | --- | --- | --- | --- |")
    over = []
    for name, func in CASES:
        if args.only and func.__name__ != "case_" + args.only:
            continue
        with Service(*flags) as service:
            pid = service.coordinator.pid
            service.get("/api/jobs")
            before = status_kb(pid, "VmRSS")
            answer, seconds = func(service, args.smoke)
            time.sleep(0.3)  # let the intake thread finish what the answer did not wait for
            peak, after = status_kb(pid, "VmHWM"), status_kb(pid, "VmRSS")
        print("| %s | %s | %.3f s | %.0f MB | %.0f MB | %.0f MB |" % (
            name, answer, seconds, before / MB, peak / MB, after / MB))
        sys.stdout.flush()
        if peak > ceiling(func):
            over.append(name)
    if over and not args.smoke:
        print("over the ceiling: " + ", ".join(over))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""The page's tile deltas, GET /api/jobs/{id}/tiles (issue 21 §1; the format is in
coordinator/http/tile_deltas.h and docs/SERVICE.md), each by its own case:

  rebuild    a job followed with long polls from its start, gzip'd as a browser asks, its
             records painted as the page paints them (a layer per block side, finer over
             coarser), ends bit for bit on the final PNG's 8-bit pixels;
  long_poll  a caught-up request is held until a unit merges (a stopped worker is let go
             while it waits), or answered empty when its wait ends; a bad `wait` is a 400.

usage: tiles_test.py --build BUILD_DIR --source SOURCE_DIR CASE
"""
import gzip
import os
import signal
import struct
import sys
import threading
import time
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import service_test  # noqa: E402  (the Service helpers; ARGS is set below)
from service_test import Service, demo_scene  # noqa: E402

RECORD = struct.Struct("<5H4BHIId")  # 32 bytes: see coordinator/http/tile_deltas.h


def read_tiles(body):
    """A /tiles answer as {"next", "whole", "finished", "records": [dict]}; each record's
    "values" are its pixels' (r, g, b) bytes, the differences undone."""
    assert body[:4] == b"TSD1", body[:16]
    next_, count, flags = struct.unpack_from("<3I", body, 4)
    at, records = 16, []
    for _ in range(count):
        x0, y0, x1, y1, step, level, pass_, rflags, _, stage, worker, pixels, merged_at = \
            RECORD.unpack_from(body, at)
        at += RECORD.size
        values, rgb = [], [0, 0, 0]
        for i in range(pixels):
            rgb = [(rgb[c] + body[at + 3 * i + c]) & 255 for c in range(3)]
            values.append(tuple(rgb))
        at += 3 * pixels
        records.append({"rect": (x0, y0, x1, y1), "step": step, "level": level, "pass": pass_,
                        "skips": bool(rflags & 1), "stage": stage, "worker": worker,
                        "values": values, "merged_at_ms": merged_at})
    assert at == len(body), (at, len(body))
    return {"next": next_, "whole": bool(flags & 1), "finished": bool(flags & 2),
            "records": records}


def paint(layers, record):
    """Paints a record as the page does: its values into the cells of its layer."""
    x0, y0, x1, y1 = record["rect"]
    step, cells = record["step"], layers.setdefault(record["step"], {})
    values = iter(record["values"])
    for y in range(y0, y1, step):
        for x in range(x0, x1, step):
            if record["skips"] and x % (2 * step) == 0 and y % (2 * step) == 0:
                continue
            cells[(x // step, y // step)] = next(values)
    assert next(values, None) is None


def shown(layers, x, y):
    for step in sorted(layers):  # finest first
        value = layers[step].get((x // step, y // step))
        if value is not None:
            return value
    return (0, 0, 0)


def decode_png(data):
    """8-bit RGB or RGBA, non-interlaced PNG -> (width, height, rows of (r, g, b))."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat = 8, b""
    while at < len(data):
        length, kind = struct.unpack_from(">I4s", data, at)
        chunk = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">2I5B", chunk)
            assert depth == 8 and colour in (2, 6) and interlace == 0, (depth, colour)
        elif kind == b"IDAT":
            idat += chunk
        at += 12 + length
    channels = 3 if colour == 2 else 4
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        previous = line
    return width, height, rows


def get_tiles(service, job_id, since, wait=0, encoding="gzip"):
    status, headers, body = service.request(
        "GET", "/api/jobs/%d/tiles?since=%d&wait=%d" % (job_id, since, wait),
        headers={"Accept-Encoding": encoding})
    assert status == 200, (status, body)
    if headers.get("Content-Encoding") == "gzip":
        body = gzip.decompress(body)
    else:
        assert encoding != "gzip", headers
    return read_tiles(body)


def follow(service, job_id):
    """Paints a job's tile records as a page following it from the start does; the painted
    layers, the levels seen, the records' count and the answers, or None when the page fell
    behind as the job ended (docs/SERVICE.md "Tiles": once the final image is encoded, a page
    behind gets *whole* and loads the PNG)."""
    layers, since, answers, levels = {}, 0, 0, set()
    while True:
        answer = get_tiles(service, job_id, since, wait=10000)
        if answer["whole"]:
            assert answer["finished"], "a page following a running job needs no PNG"
            return None
        assert answer["next"] == since + len(answer["records"]), (since, answer["next"])
        for record in answer["records"]:
            paint(layers, record)
            levels.add(record["level"])
        since, answers = answer["next"], answers + 1
        if answer["finished"] and not answer["records"]:
            return layers, levels, since, answers


def case_rebuild():
    with Service() as service:
        for name in ("w1", "w2"):
            service.worker(name, threads=1)
        service.wait_workers(2)
        settings = {"width": 150, "height": 100, "aa": 5, "stochastic": True, "passes": 2,
                    "seed": 3}
        # A job this small ends in milliseconds: the page's last request may come after its
        # final image is encoded, which is allowed (it loads the PNG). Up to three jobs, so that
        # one is followed to its end by records.
        for attempt in range(3):
            job = service.submit(open(demo_scene()).read(), settings)
            followed = follow(service, job["id"])
            if followed:
                break
            print("job %d: the page fell behind as the job ended; again" % job["id"])
        assert followed, "three jobs in a row ended before the page caught up"
        layers, levels, since, answers = followed
        final = service.get("/api/jobs/%d" % job["id"])
        assert final["state"] == "done" and since == final["tiles"], (final["state"], since)
        status, _, png = service.request("GET", "/api/jobs/%d/image" % job["id"])
        assert status == 200
        width, height, rows = decode_png(png)
        assert (width, height) == (150, 100)
        wrong = [(x, y) for y in range(height) for x in range(width)
                 if shown(layers, x, y) != rows[y][x]]
        assert not wrong, "%d pixels differ, first %s: %s vs %s" % (
            len(wrong), wrong[0], shown(layers, *wrong[0]), rows[wrong[0][1]][wrong[0][0]])
        assert levels >= set(range(1, final["levels"] + 1)) | {0}, levels
        print("%d units in %d answers rebuild the final PNG bit for bit" % (since, answers))


def case_long_poll():
    with Service() as service:
        worker = service.worker("w1", threads=1)
        service.wait_workers(1)
        job = service.submit(open(demo_scene()).read(),
                             {"width": 320, "height": 240, "aa": 9, "passes": 4})
        since = 0
        while since < 3:
            since = get_tiles(service, job["id"], since, wait=10000)["next"]
        worker.send_signal(signal.SIGSTOP)
        time.sleep(0.5)  # results already sent are merged; no more come
        caught_up = get_tiles(service, job["id"], 0, encoding="identity")["next"]
        empty = get_tiles(service, job["id"], caught_up, wait=200)
        assert empty["records"] == [] and empty["next"] == caught_up, empty
        held = {}
        thread = threading.Thread(target=lambda: held.update(
            get_tiles(service, job["id"], caught_up, wait=20000)))
        thread.start()
        time.sleep(0.3)  # the request is held by now (were it not, it would answer empty)
        worker.send_signal(signal.SIGCONT)
        thread.join(30)
        assert held["records"], held  # woken by a merge, not by the end of its wait
        assert held["next"] > caught_up
        for query in ("wait=20001", "wait=-1", "since=abc", "wait=x"):
            status, _, reply = service.request(
                "GET", "/api/jobs/%d/tiles?%s" % (job["id"], query))
            assert status == 400, (query, status, reply)
        service.request("DELETE", "/api/jobs/%d" % job["id"])


if __name__ == "__main__":
    service_test.run_case(globals())

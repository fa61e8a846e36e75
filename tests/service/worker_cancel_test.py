#!/usr/bin/env python3
"""The worker's side of Cancel, end to end against a fake coordinator (issue 23 §3): the fake
speaks the real handshake, opens a job with its bundle and sends many units, then Cancel;
after a short grace no result of the job arrives, and the worker's thread is free for the next
job at once (its queue was emptied). The next job names the same bundle by hash only (the
worker's cache answers it), and a bundle that does not match its hash is refused.

usage: worker_cancel_test.py --build BUILD_DIR --source SOURCE_DIR
"""
import argparse
import hashlib
import json
import os
import struct
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import service_test  # noqa: E402
from worker_auth_test import (AUTH, CHALLENGE, VERSION, WELCOME, FakeCoordinator,  # noqa: E402
                              read_frame, send_frame)

JOB, UNIT, RESULT, JOB_FAILED, CANCEL = 7, 8, 9, 10, 11
SCENE = b"sphere\n"
SIZE = 64
SETTINGS = {"width": SIZE, "height": SIZE, "aa": 9, "stochastic": False, "jitter": 0.0,
            "seed": 1, "passes": 1, "time_samples": 1, "bvh": True, "shadows": "hard",
            "cone_samples": 1, "shadow_jitter": 0.0, "normalize": False, "brightness": 1.0}
UNITS = 400  # far more than one thread renders during the test
GRACE = 0.1  # a result already on its way when Cancel was sent


def content_hash(fmt, main, files):
    """common/protocol/bundle.cpp's content_hash: length-prefixed fields."""
    canonical = b""
    for field in [fmt.encode(), main.encode()] + [x for p, b in files for x in (p.encode(), b)]:
        canonical += b"%d:" % len(field) + field
    return hashlib.sha256(canonical).hexdigest()


HASH = content_hash("sdl", "scene.sdl", [("scene.sdl", SCENE)])


def send_payload_frame(sock, kind, header, payload):
    head = json.dumps(header).encode()
    body = struct.pack(">BI", kind, len(head)) + head + payload
    sock.sendall(struct.pack(">I", len(body)) + body)


def open_job(conn, job, with_bundle=True, bundle_hash=HASH):
    header = {"job": job, "hash": bundle_hash, "settings": SETTINGS}
    if with_bundle:
        header["bundle"] = {"main": "scene.sdl", "format": "sdl",
                            "files": [{"path": "scene.sdl", "size": len(SCENE)}]}
    send_payload_frame(conn, JOB, header, SCENE if with_bundle else b"")


def send_unit(conn, job, unit):
    send_frame(conn, UNIT, {"job": job, "unit": unit, "pass": 0, "pixels": {
        "rect": [0, 0, SIZE, SIZE], "step": 1, "exclude": 0, "pattern": "anchors"}})


def frames_for(conn, seconds):
    """Every frame but heartbeats that arrives within `seconds`."""
    frames = []
    deadline = time.time() + seconds
    while time.time() < deadline:
        conn.settimeout(max(0.01, deadline - time.time()))
        try:
            kind, header = read_frame(conn)
        except TimeoutError:
            break
        if kind != 6:
            frames.append((kind, header))
    conn.settimeout(10)
    return frames


def wait_results(conn, job, count, timeout=20):
    got = 0
    deadline = time.time() + timeout
    while got < count:
        assert time.time() < deadline, "the worker sent %d of %d results" % (got, count)
        kind, header = read_frame(conn)
        assert kind in (6, RESULT), (kind, header)
        got += kind == RESULT and header["job"] == job


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", required=True)
    service_test.ARGS = parser.parse_args()
    start = time.time()
    with FakeCoordinator("") as fake:
        conn, _ = fake.accept()
        with conn:
            send_frame(conn, CHALLENGE, {"version": VERSION, "nonce": "ab" * 32, "auth": "none"})
            assert read_frame(conn)[0] == AUTH
            send_frame(conn, WELCOME, {"worker": 1, "proof": ""})
            open_job(conn, 1)
            for unit in range(UNITS):
                send_unit(conn, 1, unit)
            wait_results(conn, 1, 2)
            send_frame(conn, CANCEL, {"job": 1})
            frames_for(conn, GRACE)
            late = [h for k, h in frames_for(conn, 1.0) if k == RESULT]
            assert not late, "%d results of the cancelled job after the grace" % len(late)
            # Same bundle by hash only: the cache answers; the freed thread renders it at once.
            open_job(conn, 2, with_bundle=False)
            send_unit(conn, 2, 0)
            frames = frames_for(conn, 2.0)
            assert frames and frames[0][0] == RESULT and frames[0][1]["job"] == 2, frames[:3]
            # A bundle whose bytes do not match the hash it is sent under is refused.
            open_job(conn, 3, bundle_hash="0" * 64)
            conn.settimeout(5)
            try:
                while read_frame(conn)[0] == 6:
                    pass
                raise AssertionError("the worker accepted a bundle that does not match its hash")
            except (EOFError, ConnectionResetError):
                pass
            deadline = time.time() + 5  # the worker logs the reason as it drops the connection
            while "does not match its hash" not in fake.log():
                assert time.time() < deadline, fake.log()
                time.sleep(0.02)
    print("worker_cancel passed in %.1f s" % (time.time() - start))


if __name__ == "__main__":
    sys.exit(main())

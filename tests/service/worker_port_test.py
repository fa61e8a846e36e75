#!/usr/bin/env python3
"""The worker port against hostile peers (issue 16, items 5 and 6): strangers that never
authenticate, a descriptor limit reached, and authenticated fake workers that speak the real
handshake but send forged results and failures. The real coordinator, worker and tessera-render
run as processes on loopback, as in service_test.py, whose helpers this uses.

usage: worker_port_test.py --build BUILD_DIR --source SOURCE_DIR CASE
CASE: caps | deadline | results | negative_colours | emfile
"""
import hashlib
import hmac
import json
import math
import os
import select
import socket
import struct
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import service_test as svc  # noqa: E402
from service_test import SECRET, SETTINGS, Service  # noqa: E402

PROTOCOL_VERSION = 2  # kProtocolVersion, common/protocol/handshake.h
HELLO, CHALLENGE, AUTH, WELCOME, REJECT, HEARTBEAT, JOB, UNIT, RESULT, JOB_FAILED, CANCEL = \
    range(1, 12)
MAX_UNAUTHENTICATED = 64  # WorkerPortLimits, coordinator/workers/worker_link.h
MAX_PER_ADDRESS = 8
HANDSHAKE_DEADLINE = 5.0


def frame(kind, header, payload=b""):
    head = json.dumps(header).encode()
    body = bytes([kind]) + struct.pack(">I", len(head)) + head + payload
    return struct.pack(">I", len(body)) + body


def unit_pixel_count(pixels):
    """pixel_count() of common/progressive/unit_pixels.cpp."""
    x0, y0, x1, y1 = pixels["rect"]
    step, exclude = pixels["step"], pixels["exclude"]
    first = lambda v: (v + step - 1) // step * step  # noqa: E731
    count = 0
    for by in range(first(y0), y1, step):
        for bx in range(first(x0), x1, step):
            if pixels["pattern"] == "centres" or exclude <= 0 or bx % exclude or by % exclude:
                count += 1
    return count


class FakeWorker:
    """A peer with the shared secret that does what the test says instead of rendering."""

    def __init__(self, port, name):
        self.name = name
        self.sock = socket.create_connection(("127.0.0.1", port))
        self.buf = b""
        self.units = []  # unit headers received, in order
        self.cancels = []
        self.last_sent = time.time()

    def send(self, kind, header, payload=b""):
        self.sock.sendall(frame(kind, header, payload))
        self.last_sent = time.time()

    def recv(self, timeout):
        """The next frame other than a heartbeat as (type, header, payload); None once the
        coordinator has closed the connection; raises TimeoutError after `timeout`."""
        deadline = time.time() + timeout
        while True:
            if len(self.buf) >= 4:
                size = struct.unpack(">I", self.buf[:4])[0]
                if len(self.buf) >= 4 + size:
                    body, self.buf = self.buf[4:4 + size], self.buf[4 + size:]
                    head = struct.unpack(">I", body[1:5])[0]
                    kind, header = body[0], json.loads(body[5:5 + head])
                    if kind == UNIT:
                        self.units.append(header)
                    elif kind == CANCEL:
                        self.cancels.append(header)
                    if kind != HEARTBEAT:
                        return kind, header, body[5 + head:]
                    continue
            if time.time() - self.last_sent > 1:  # the coordinator drops silent peers
                self.send(HEARTBEAT, {})
            left = deadline - time.time()
            if left <= 0:
                raise TimeoutError(self.name)
            ready, _, _ = select.select([self.sock], [], [], min(left, 0.5))
            if ready:
                try:
                    data = self.sock.recv(65536)
                except ConnectionResetError:
                    data = b""
                if not data:
                    return None
                self.buf += data

    def handshake(self):
        nonce = os.urandom(32).hex()
        self.send(HELLO, {"version": PROTOCOL_VERSION, "name": self.name, "threads": 1,
                          "nonce": nonce, "cached": []})
        kind, challenge, _ = self.recv(5)
        assert kind == CHALLENGE, kind
        proof = hmac.new(SECRET.encode(), ("tessera-worker|%d|%s|%s" % (
            PROTOCOL_VERSION, challenge["nonce"], nonce)).encode(), hashlib.sha256).hexdigest()
        self.send(AUTH, {"proof": proof})
        kind, welcome, _ = self.recv(5)
        assert kind == WELCOME, (kind, welcome)
        expected = hmac.new(SECRET.encode(), ("tessera-coordinator|%d|%s|%s" % (
            PROTOCOL_VERSION, nonce, challenge["nonce"])).encode(), hashlib.sha256).hexdigest()
        assert welcome["proof"] == expected
        return self

    def next_unit(self, timeout=10):
        while True:
            got = self.recv(timeout)
            assert got is not None, "%s was dropped before its first unit" % self.name
            if got[0] == UNIT:
                return got[1]

    def drain(self, seconds):
        """Reads what arrives for `seconds`; False if the connection closed."""
        deadline = time.time() + seconds
        try:
            while self.recv(max(0.0, deadline - time.time())) is not None:
                pass
            return False
        except TimeoutError:
            return True

    def dropped_within(self, timeout):
        """True when the coordinator closes the connection within `timeout` seconds."""
        return not self.drain(timeout)


def honest_stats(pixels, seconds=0.001):
    return {"camera_rays": pixels, "shadow_rays": 0, "reflection_rays": 0, "refraction_rays": 0,
            "shape_tests": 0, "triangle_tests": 0, "bvh_nodes": 0, "pixels": pixels,
            "samples": pixels, "nan_samples": 0, "seconds": seconds}


def result(unit, pixels, values=None, stats=None):
    values = [0.5] * (pixels * 3) if values is None else values
    return (RESULT, {"job": unit["job"], "unit": unit["unit"], "count": pixels,
                     "stats": stats or honest_stats(pixels)},
            struct.pack("<%df" % len(values), *values))


def peer_closed(sock):
    ready, _, _ = select.select([sock], [], [], 0)
    if not ready:
        return False
    try:
        return sock.recv(1, socket.MSG_PEEK) == b""
    except ConnectionResetError:
        return True


def coordinator_log(service):
    with open(os.path.join(service.tmp.name, "coordinator.log"), errors="replace") as f:
        return f.read()


def cpu_seconds(pid):
    """User and system time of a process so far."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def timed_get(service, path):
    start = time.time()
    body = service.get(path)
    return body, time.time() - start


def stranger(port, source):
    """A connection to the worker port from the loopback address `source` (all of 127/8 is
    this machine), which never says a word."""
    return socket.create_connection(("127.0.0.1", port), source_address=(source, 0))


def case_caps():
    """Strangers on the worker port: one address holds at most 8 places, so a real worker from
    another still joins; 100 from many addresses: 64 are held, the others closed at once; HTTP
    still answers; once they leave a real worker joins."""
    with Service() as service:
        one_host = [stranger(service.worker_port, "127.0.0.2") for _ in range(20)]
        time.sleep(0.5)  # well inside the handshake deadline
        closed = sum(peer_closed(s) for s in one_host)
        assert closed == 20 - MAX_PER_ADDRESS, closed
        service.worker("while-one-host-floods")  # from 127.0.0.1
        service.wait_workers(1)
        log = coordinator_log(service)
        assert "8 unauthenticated connections open from 127.0.0.2" in log, log[-2000:]
        for s in one_host:
            s.close()
        # The log allows one refusal line a second: the burst below starts a new second.
        time.sleep(1.1)
        refusals_before = coordinator_log(service).count("refused a connection")

        strangers = [stranger(service.worker_port, "127.0.0.%d" % (2 + i % 13))
                     for i in range(100)]
        time.sleep(0.5)
        closed = sum(peer_closed(s) for s in strangers)
        assert closed == 100 - MAX_UNAUTHENTICATED, closed
        _, seconds = timed_get(service, "/api/workers")
        assert seconds < 0.1, seconds
        # The cap is on strangers only: a worker that authenticates frees its place.
        for s in strangers:
            s.close()
        service.worker("real")
        service.wait_workers(2)
        # 36 refusals in a burst make one log line, not 36.
        refusals = coordinator_log(service).count("refused a connection") - refusals_before
        assert 1 <= refusals <= 2, refusals  # 2 if the burst spans a second
        print("%d of 100 closed at once; GET /api/workers in %.1f ms" % (closed, seconds * 1e3))


def case_deadline():
    """A peer that only sends heartbeats, and one that stops after its hello, are closed after
    the handshake deadline; an authenticated worker stays."""
    with Service() as service:
        service.worker("real")
        service.wait_workers(1)
        mute = FakeWorker(service.worker_port, "mute")
        halfway = FakeWorker(service.worker_port, "halfway")
        halfway.send(HELLO, {"version": PROTOCOL_VERSION, "name": "halfway", "threads": 1,
                             "nonce": os.urandom(32).hex(), "cached": []})
        start = time.time()
        for peer in (mute, halfway):  # recv() sends heartbeats while it waits
            assert peer.dropped_within(HANDSHAKE_DEADLINE + 3), peer.name
            elapsed = time.time() - start
            assert HANDSHAKE_DEADLINE - 0.5 < elapsed < HANDSHAKE_DEADLINE + 2, elapsed
        assert [w["name"] for w in service.get("/api/workers")] == ["real"]
        assert "did not authenticate within 5000 ms" in coordinator_log(service)
        print("strangers closed after %.2f s" % (time.time() - start))


def case_results():
    """Authenticated fake workers that send NaN pixels, too few pixels, a unit they were not
    sent or absurd statistics are dropped; one that fails a job it was never sent changes
    nothing; one that fails a job it was sent loses that job but not its connection. Both jobs
    finish bit-identical to tessera-render (a real worker renders them)."""
    with tempfile.TemporaryDirectory() as tmp, Service() as service:
        # Fakes first: they join with nothing to do and get the first job's units first.
        names = ["nan", "short", "unsent", "slow", "nojob", "failing"]
        fakes = {n: FakeWorker(service.worker_port, n).handshake() for n in names}
        service.worker("real")
        service.wait_workers(len(names) + 1)
        scene = open(svc.demo_scene()).read()
        # Enough units for every fake's slots and the real worker's: units are sized to about
        # 20 ms of the probe's cost, so a costlier pixel (aa 9) makes more of them.
        big = dict(SETTINGS, width=320, height=240, aa=9)
        first = service.submit(scene, big)
        units = {n: fakes[n].next_unit() for n in names}
        time.sleep(0.2)  # every fake has all the units it will get of the first job
        second = service.submit(scene, dict(big, seed=8))  # the fakes' slots are full
        assert fakes["failing"].drain(0.3)
        units_before_report = [u for u in fakes["failing"].units if u["job"] == first["id"]]
        reasons = {}

        unit = units["nan"]
        pixels = unit_pixel_count(unit["pixels"])
        fakes["nan"].send(*result(unit, pixels, [math.nan] + [0.5] * (pixels * 3 - 1)))
        reasons["nan"] = "pixel value nan at 0"

        unit = units["short"]
        pixels = unit_pixel_count(unit["pixels"])
        kind, header, payload = result(unit, pixels)
        fakes["short"].send(kind, header, payload[:-12])
        reasons["short"] = "pixels with a payload of"  # the header's count against the payload

        unit = units["unsent"]
        held = {u["unit"] for u in fakes["unsent"].units}
        other = next(i for i in range(10 ** 6) if i not in held)
        fakes["unsent"].send(*result(dict(unit, unit=other), unit_pixel_count(unit["pixels"])))
        reasons["unsent"] = "result for unit %d of job %d, which this worker does not hold" % (
            other, first["id"])

        unit = units["slow"]
        pixels = unit_pixel_count(unit["pixels"])
        fakes["slow"].send(*result(unit, pixels, stats=honest_stats(pixels, seconds=86400)))
        reasons["slow"] = "render time of 86400"

        fakes["nojob"].send(JOB_FAILED, {"job": second["id"], "error": "forged"})
        reasons["nojob"] = "job_failed for job %d, which was never sent" % second["id"]

        for name, reason in reasons.items():
            assert fakes[name].dropped_within(3), name
        log = coordinator_log(service)
        for name, reason in reasons.items():
            assert reason in log, (name, reason)

        # A failure report for a job it was sent: one worker's word, so the job goes on
        # elsewhere; the worker is told to drop it and stays connected. It reports every job it
        # is given as failing, so it ends up holding nothing.
        failing = fakes["failing"]
        reported = set()
        while True:
            for job_id in {u["job"] for u in failing.units} - reported:
                failing.send(JOB_FAILED, {"job": job_id, "error": "scene crashed here"})
                reported.add(job_id)
            assert failing.drain(0.2), "the failing worker was dropped"
            states = [service.get("/api/jobs/%d" % job["id"])["state"] for job in (first, second)]
            if not {"queued", "running"} & set(states):
                break
        assert states == ["done", "done"], states
        # Checked before the comparisons below, which take long on a busy machine: the fakes
        # send no heartbeats meanwhile, and the coordinator rightly drops silent peers.
        names_left = sorted(w["name"] for w in service.get("/api/workers"))
        assert names_left == ["failing", "real"], names_left
        assert [c["job"] for c in failing.cancels] == sorted(reported), failing.cancels
        withdrawn = len([u for u in failing.units if u["job"] == first["id"]])
        assert withdrawn == len(units_before_report), (withdrawn, units_before_report)
        for job, settings in ((first, big), (second, dict(big, seed=8))):
            status = service.get("/api/jobs/%d" % job["id"])
            assert any("scene crashed here" in w for w in status["warnings"]), status["warnings"]
            path = os.path.join(tmp, "svc%d.exr" % job["id"])
            service.exr(job["id"], path)
            svc.render_cli(svc.demo_scene(), settings, os.path.join(tmp, "cli.exr"))
            svc.assert_identical(path, os.path.join(tmp, "cli.exr"))


def case_negative_colours():
    """Negative pixel values are honest: a VRML world may have negative colours. The job
    finishes bit-identical to tessera-render and no worker is dropped for it."""
    world = "#VRML V2.0 utf8\nBackground { skyColor [-1 -0.5 0.25] }\n"
    settings = {"width": 16, "height": 16}
    with tempfile.TemporaryDirectory() as tmp, Service() as service:
        service.worker("real")
        service.wait_workers(1)
        body = json.dumps({"scene": world, "format": "vrml", "settings": settings}).encode()
        status, _, reply = service.request("POST", "/api/jobs", body,
                                           {"Content-Type": "application/json"})
        assert status == 201, (status, reply)
        job = json.loads(reply)
        assert service.wait_job(job["id"], timeout=20)["state"] == "done"
        assert service.get("/api/workers")[0]["units_done"] > 0
        assert "left" not in coordinator_log(service)  # "worker N ... left; units re-queued"
        path = os.path.join(tmp, "world.wrl")
        with open(path, "w") as f:
            f.write(world)
        service.exr(job["id"], os.path.join(tmp, "svc.exr"))
        svc.render_cli(path, settings, os.path.join(tmp, "cli.exr"))
        svc.assert_identical(os.path.join(tmp, "svc.exr"), os.path.join(tmp, "cli.exr"))


def case_emfile():
    """At the descriptor limit the worker port's accept errors are backed off and their log
    lines limited; HTTP answers again once the sockets close."""
    with Service(prefix=("prlimit", "--nofile=32:32", "--")) as service:
        peers = []
        for i in range(60):  # more than the coordinator has descriptors left, each address
            peers.append(stranger(service.worker_port, "127.0.1.%d" % (1 + i)))  # under its cap
        before = coordinator_log(service).count("\n")
        cpu_before = cpu_seconds(service.coordinator.pid)
        time.sleep(2)
        cpu = cpu_seconds(service.coordinator.pid) - cpu_before
        log = coordinator_log(service)
        lines = log.count("\n") - before
        assert "accept failed" in log, log[-2000:]
        assert lines < 50, "%d log lines in 2 s" % lines
        assert cpu < 0.25, "the coordinator spun: %.2f s of CPU in 2 s" % cpu
        for p in peers:
            p.close()
        deadline = time.time() + 5
        while True:
            try:
                _, seconds = timed_get(service, "/api/workers")
                break
            except OSError:
                assert time.time() < deadline, "HTTP did not come back"
        print("%d log lines and %.3f s of CPU in 2 s at the descriptor limit; HTTP back, "
              "answered in %.1f ms" % (lines, cpu, seconds * 1e3))


if __name__ == "__main__":
    svc.run_case(globals())

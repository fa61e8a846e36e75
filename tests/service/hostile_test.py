#!/usr/bin/env python3
"""The coordinator against hostile clients (issue 16 §1, §4, §7): requests that would stall it
never delay status answers, finished and cancelled jobs give their memory back, and only who
may submit can. The hostile inputs are generated here, small.

usage: hostile_test.py --build BUILD_DIR --source SOURCE_DIR CASE
CASE: intake | load_budget | framing | submit_rules | job_cap | memory | connections | descriptors
"""
import http.client
import json
import os
import signal
import socket
import threading
import time

import service_test
from service_test import Service

JSON = {"Content-Type": "application/json"}
SMALL = {"width": 32, "height": 24}
INTAKE_SECONDS = 2


def def_use_bomb(depth=60, leaf="Transform {}"):
    """Each level USEs the one before twice: 2**depth copies of the leaf (by default without a
    single shape)."""
    lines = ["#VRML V2.0 utf8", "DEF A0 " + leaf]
    lines += ["DEF A%d Transform { children [USE A%d USE A%d] }" % (i, i - 1, i - 1)
              for i in range(1, depth + 1)]
    return "\n".join(lines) + "\n"


def framing_bomb(side=200, levels=13, viewpoint=""):
    """A world without a Viewpoint, so the loader frames its bounds, that measures a mesh of
    side x side vertices once per object: 2**levels objects USE it. About a megabyte of text
    that loads in a second or two, then 13 s of framing (on the build machine) unless the
    framing watches the deadline. `viewpoint` (a Viewpoint node) skips the framing."""
    points = ",".join("%d %d 0" % (i % side, i // side) for i in range(side * side))
    faces = ",".join("%d %d %d -1" % (i, i + 1, i + side) for i in range(side * (side - 1) - 1))
    lines = ["#VRML V2.0 utf8", viewpoint,
             "DEF A0 Transform { children Shape { geometry IndexedFaceSet {"
             " coord Coordinate { point [%s] } coordIndex [%s] } } }" % (points, faces)]
    lines += ["DEF A%d Transform { translation 1 0 0 children [USE A%d USE A%d] }" %
              (i, i - 1, i - 1) for i in range(1, levels + 1)]
    return "\n".join(lines) + "\n"


# A glossy mirror hall: the camera inside a scaled sphere, every hit spawning 64 glossy rays,
# 16 deep, with nothing cut off by weight. One pixel of it takes minutes.
MIRROR_HALL = ("eyePoint 0 0 0\nviewPoint 0 0 -1\nlight 0 0 0 1 1 1\n"
               "reflectivity 0.95\nglossStrength 0.5\nscale 10 10 10\nsphere\n")
RUNAWAY = {"width": 32, "height": 24, "cone_samples": 64, "max_depth": 16, "min_weight": 0}


def post(service, path, payload, headers=None):
    start = time.time()
    status, _, reply = service.request("POST", path, json.dumps(payload).encode(),
                                       {**JSON, **(headers or {})})
    return status, json.loads(reply), time.time() - start


def case_intake():
    """While a DEF/USE bomb and several runaway predictions are in work, GET /api/workers and
    a job's status answer in under 100 ms (95th percentile; none near the intake deadline), and the hostile requests end with 422/413/503 and
    a JSON error within their budget."""
    with Service("--max-intake-seconds", str(INTAKE_SECONDS), "--local-workers", "1",
                 "--local-threads", "1") as service:
        service.wait_workers(1)
        job = service.submit("sphere\n", SMALL)
        hostile = [("/api/jobs", {"scene": def_use_bomb(), "format": "vrml", "settings": SMALL})]
        hostile += [("/api/predict", {"scene": MIRROR_HALL, "settings": RUNAWAY})] * 3
        outcomes = [None] * len(hostile)

        def send(i, path, payload):
            outcomes[i] = post(service, path, payload)

        threads = [threading.Thread(target=send, args=(i, *h)) for i, h in enumerate(hostile)]
        for t in threads:
            t.start()
        conn = http.client.HTTPConnection("127.0.0.1", service.http_port, timeout=10)
        latencies = []
        while any(t.is_alive() for t in threads):
            for path in ("/api/workers", "/api/jobs/%d" % job["id"]):
                start = time.time()
                conn.request("GET", path)
                response = conn.getresponse()
                response.read()
                latencies.append(time.time() - start)
                assert response.status == 200, (path, response.status)
            time.sleep(0.01)
        for t in threads:
            t.join()
        latencies.sort()
        p95 = latencies[int(0.95 * (len(latencies) - 1))]
        print("%d status requests, 95th percentile %.1f ms, slowest %.1f ms" %
              (len(latencies), 1000 * p95, 1000 * latencies[-1]))
        assert len(latencies) >= 50, len(latencies)
        # The promise is under 100 ms. This client shares two cores with the four busy
        # threads above (and, under ctest -j2, with another test), so the odd request waits
        # for the client itself to be scheduled: the 95th percentile holds the promise, and
        # the slowest may not reach the intake deadline, which a request waiting on the
        # hostile work (intake on the io thread, say) would (INTAKE_SECONDS).
        assert p95 < 0.1, latencies[-5:]
        assert latencies[-1] < 0.5, latencies[-5:]
        for (path, _), (status, reply, seconds) in zip(hostile, outcomes):
            print("%s: %d %s in %.2f s" % (path, status, reply, seconds))
            assert seconds < INTAKE_SECONDS + 1.5, (path, seconds)
            if path == "/api/jobs":
                # The load budget counts the bomb's USE replays and stops it, unless the intake
                # deadline comes first: on a busy machine the bomb may wait behind the three
                # predictions for an intake thread (the count itself: tests/loaders).
                assert status == 422, (status, reply)
                assert reply["error"] == "over_budget", reply
                assert reply["limit"] in ("use_replays", "max_intake_seconds"), reply
                if reply["limit"] == "use_replays":
                    assert reply["line"] > 1 and reply["detail"], reply
            else:
                # The probe stops inside the runaway pixel at its deadline: the prediction is
                # a lower bound, and says so. Its cost a pixel pass is the probing thread's CPU
                # time over the few pixels it began, and that thread shares the cores with the
                # other probes here: over 20 ms, where an ordinary pixel takes microseconds.
                assert status == 200, (status, reply)
                assert reply["lower_bound"] is True, reply
                assert reply["seconds_per_pixel_pass"] > 0.02, reply
                assert reply["predicted_seconds"] > 0, reply
        # The service itself is fine: the small job finished, a worker is still there.
        assert service.wait_job(job["id"])["state"] == "done"
        assert len(service.get("/api/workers")) == 1
        # SIGTERM ends it at once although the runaway scenes are still in work.
        start = time.time()
        service.coordinator.send_signal(signal.SIGTERM)
        assert service.coordinator.wait(timeout=5) == 0
        print("SIGTERM to exit: %.2f s" % (time.time() - start))
        assert time.time() - start < 1.0


def case_load_budget():
    """What a scene produces is bounded, not its size: a 2 KB world of 2**22 USEd spheres is
    refused with 413 over_budget naming bytes_produced and where, in seconds, and the service
    goes on. (About 0.6 s on a quiet machine; the intake deadline is raised so that a machine
    busy with other builds, seen to take over 10 s, still meets the byte budget first.)"""
    with Service("--local-workers", "1", "--local-threads", "1",
                 "--max-intake-seconds", "60") as service:
        service.wait_workers(1)
        world = def_use_bomb(22, "Shape { geometry Sphere {} }")
        assert len(world) < 4096
        status, reply, seconds = post(service, "/api/jobs",
                                      {"scene": world, "format": "vrml", "settings": SMALL})
        print("%d %s in %.2f s" % (status, reply, seconds))
        assert status == 413, (status, reply)
        assert reply["error"] == "over_budget" and reply["limit"] == "bytes_produced", reply
        assert reply["value"] == 384 << 20 and reply["file"] == "scene.wrl", reply
        job = service.submit("sphere\n", SMALL)
        assert service.wait_job(job["id"])["state"] == "done"


def case_framing():
    """The camera framing a world without a Viewpoint runs under the intake deadline: with one
    intake thread, a world whose framing alone takes many seconds ends 422 over_budget at its
    deadline, and the thread is free again for the next submission at once (before the fix it
    went on measuring the world and the next request timed out waiting for it)."""
    with Service("--max-intake-seconds", "3", "--intake-threads", "1") as service:
        world = framing_bomb()
        status, reply, seconds = post(service, "/api/jobs",
                                      {"scene": world, "format": "vrml", "settings": SMALL})
        print("%d %s in %.2f s" % (status, reply, seconds))
        assert status == 422 and reply["limit"] == "max_intake_seconds", (status, reply)
        status, reply, seconds = post(service, "/api/jobs", {"scene": "sphere\n",
                                                             "settings": SMALL})
        print("the next submission: %d in %.2f s" % (status, seconds))
        assert status == 201, (status, reply)


def non_loopback_address():
    """An address of this machine other than loopback, or None."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        try:
            s.connect(("192.0.2.123", 9))  # no packet is sent: it only picks the source address
            address = s.getsockname()[0]
        except OSError:
            return None
    return None if address.startswith("127.") else address


def case_submit_rules():
    """--api-token makes POST and DELETE need the bearer token; without one only loopback may
    submit unless --open-submit; foreign origins are refused unless --allow-origin."""
    scene = {"scene": "sphere\n", "settings": SMALL}
    with Service("--api-token", "tok3n") as service:
        for headers in ({}, {"Authorization": "Bearer wrong"}, {"Authorization": "tok3n"}):
            status, err, _ = post(service, "/api/jobs", scene, headers)
            assert status == 401 and err["error"] == "unauthorized", (headers, status, err)
        status, job, _ = post(service, "/api/jobs", scene, {"Authorization": "Bearer tok3n"})
        assert status == 201, job
        path = "/api/jobs/%d" % job["id"]
        status, _, reply = service.request("DELETE", path)
        assert status == 401 and json.loads(reply)["error"] == "unauthorized", reply
        assert service.get(path)["id"] == job["id"]  # reading needs no token
        status, _, _ = service.request("DELETE", path, None, {"Authorization": "Bearer tok3n"})
        assert status == 200
    os.environ["TESSERA_API_TOKEN"] = "from-env"
    try:
        with Service() as service:
            assert post(service, "/api/jobs", scene)[0] == 401
            assert post(service, "/api/jobs", scene,
                        {"Authorization": "Bearer from-env"})[0] == 201
    finally:
        del os.environ["TESSERA_API_TOKEN"]

    with Service("--allow-origin", "https://render.example") as service:
        own = "http://127.0.0.1:%d" % service.http_port
        for origin, expect in (("https://evil.example", 403), ("null", 403),
                               ("http://127.0.0.1:1", 403), (own, 201),
                               ("https://render.example", 201)):
            status, err, _ = post(service, "/api/jobs", scene, {"Origin": origin})
            assert status == expect, (origin, status, err)
            if expect == 403:
                assert err["error"] == "cross_origin" and origin in err["detail"], err
        status, _, reply = service.request("DELETE", "/api/jobs/1", None,
                                           {"Origin": "https://evil.example"})
        assert status == 403, reply
        assert service.get("/api/jobs/1")["state"] != "cancelled"

    address = non_loopback_address()
    if address is None:
        print("no non-loopback address: the loopback-only rule is covered by test_coordinator")
        return
    for flags, expect in (((), 403), (("--open-submit",), 201)):
        with Service(*flags, host=address) as service:
            status, err, _ = post(service, "/api/jobs", scene)
            assert status == expect, (address, flags, status, err)
            if expect == 403:
                assert err["error"] == "forbidden" and "--api-token" in err["detail"], err
            assert service.get("/api/workers") == []  # reading stays open


def case_job_cap():
    """One client holds at most --max-jobs-per-client unfinished jobs: 429 beyond."""
    with Service("--max-jobs-per-client", "2") as service:  # no workers: jobs stay queued
        first = service.submit("sphere\n", SMALL)
        service.submit("sphere\n", SMALL)
        status, err, _ = post(service, "/api/jobs", {"scene": "sphere\n", "settings": SMALL})
        assert status == 429 and err["error"] == "too_many_jobs", (status, err)
        assert err["value"] == 2, err
        status, _, _ = service.request("DELETE", "/api/jobs/%d" % first["id"])
        assert status == 200
        service.submit("sphere\n", SMALL)


def refused(port):
    """Whether a new connection is closed by the server without an answer."""
    with socket.create_connection(("127.0.0.1", port)) as s:
        s.settimeout(5)
        s.sendall(b"GET /api/workers HTTP/1.1\r\nHost: x\r\n\r\n")
        try:
            return s.recv(64) == b""
        except ConnectionResetError:
            return True


def case_connections():
    """Beyond --max-http-connections a new connection is closed at once; closing one makes
    room again."""
    with Service("--max-http-connections", "4") as service:
        idle = [socket.create_connection(("127.0.0.1", service.http_port)) for _ in range(4)]
        time.sleep(0.2)
        assert refused(service.http_port)
        idle.pop().close()
        time.sleep(0.2)
        assert not refused(service.http_port)
        for s in idle:
            s.close()
        assert service.get("/api/workers") == []


def cpu_seconds(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def case_descriptors():
    """At the descriptor limit the accept loop backs off instead of spinning, logs a line a
    second at most, and serves again once descriptors are free."""
    with Service(prefix=("prlimit", "--nofile=48:48")) as service:
        held = []
        for _ in range(80):  # beyond the limit: the kernel queues them, accept gets EMFILE
            held.append(socket.create_connection(("127.0.0.1", service.http_port)))
        time.sleep(0.5)
        pid = service.coordinator.pid
        cpu_before, start = cpu_seconds(pid), time.time()
        time.sleep(2)
        busy = (cpu_seconds(pid) - cpu_before) / (time.time() - start)
        log = open(os.path.join(service.tmp.name, "coordinator.log")).read()
        failures = log.count("HTTP accept failed")
        print("at the limit: %.1f%% of a core, %d log lines about it" % (100 * busy, failures))
        assert failures >= 1 and failures <= 5, failures
        assert busy < 0.1, busy
        for s in held:
            s.close()
        deadline = time.time() + 5
        while True:  # the next retry (at most a second away) accepts again
            try:
                assert service.get("/api/workers") == []
                break
            except (OSError, http.client.HTTPException):
                assert time.time() < deadline
                time.sleep(0.1)


def rss_mb(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    raise AssertionError("no VmRSS")


def case_memory():
    """Ten 2048x2048 jobs take memory only as their pixels merge (a frame buffer's zeros are
    the kernel's untouched pages), and cancelled they leave the coordinator's RSS within
    100 MB of what it was before."""
    with Service("--max-jobs-per-client", "16") as service:  # no workers: nothing renders
        service.get("/api/jobs")
        pid = service.coordinator.pid
        before = rss_mb(pid)
        big = {"width": 2048, "height": 2048}
        jobs = [service.submit("sphere\n", big) for _ in range(10)]
        held = rss_mb(pid)
        for job in jobs:
            status, _, _ = service.request("DELETE", "/api/jobs/%d" % job["id"])
            assert status == 200
        time.sleep(0.5)
        after = rss_mb(pid)
        print("RSS before %.0f MB, ten jobs held %.0f MB, cancelled %.0f MB" %
              (before, held, after))
        # 10 x 2048 x 2048 x 14 bytes is 587 MB of frame buffers, none of it merged yet.
        assert held < before + 100, (before, held)
        assert after < before + 100, (before, after)
        status, _, reply = service.request("GET", "/api/jobs/%d/image" % jobs[0]["id"])
        assert status == 404 and json.loads(reply)["error"] == "no_image", (status, reply)


if __name__ == "__main__":
    service_test.run_case(globals())

#!/usr/bin/env python3
"""POST /api/jobs/{id}/rerender (issue 21 §3, §4): any job, however it was submitted, rendered
again from the coordinator's copy of its bundle with its settings, some replaced. Each by its
own case:

  images   a job submitted by JSON, rerendered with a camera, is bit for bit tessera-render
           --camera; rerendered with no settings, bit for bit the original (and the same
           settings); a region over it is the same pixels, and without the region again the
           whole image; a VRML world sent by tessera-submit (an Inline, a texture) rerenders
           with a camera as tessera-render does.
  answers  what POST /api/jobs answers: a bad setting or body is a 400 JSON error naming it, an
           unknown job 404, another method 405, the per-client cap 429, and the submit policy
           (a token; only loopback without one) as for any POST.

usage: rerender_test.py --build BUILD_DIR --source SOURCE_DIR CASE
"""
import copy
import json
import os
import subprocess
import tempfile

import service_test
from hostile_test import non_loopback_address
from region_submit_test import assert_region_identical
from service_test import Service, assert_identical, binary, demo_scene, render_cli

SETTINGS = service_test.SETTINGS  # 96 x 72, aa 5, stochastic, 2 passes, seed 7
CAMERA = {"eye": [-2, 0.5, 6], "look_at": [0, -0.25, 0], "up": [0.1, 1, 0], "fov": 33.5}
JSON = {"Content-Type": "application/json"}


def rerender(service, job_id, body, expect=201, headers=None):
    """POSTs `body` (a dict, or bytes as they are) to the job's rerender route; answers the
    reply's JSON and headers."""
    data = body if isinstance(body, bytes) else json.dumps(body).encode()
    status, reply_headers, reply = service.request(
        "POST", "/api/jobs/%d/rerender" % job_id, data, {**JSON, **(headers or {})})
    assert status == expect, (job_id, body, status, reply)
    return json.loads(reply), reply_headers


def finished_exr(service, job_id, path):
    final = service.wait_job(job_id)
    assert final["state"] == "done", final
    service.exr(job_id, path)
    return final


def case_images():
    with tempfile.TemporaryDirectory() as tmp, Service("--local-workers", "2",
                                                       "--local-threads", "1") as service:
        path = lambda name: os.path.join(tmp, name)  # noqa: E731
        original = service.submit(open(demo_scene()).read(), SETTINGS)
        first = finished_exr(service, original["id"], path("original.exr"))

        same, headers = rerender(service, original["id"], {"settings": {}})
        assert headers["Location"] == "/api/jobs/%d" % same["id"], headers
        assert same["id"] != original["id"] and same["settings"] == first["settings"], same
        finished_exr(service, same["id"], path("same.exr"))
        assert_identical(path("same.exr"), path("original.exr"))

        moved, _ = rerender(service, original["id"], {"settings": {"camera": CAMERA}})
        assert moved["settings"] == {**first["settings"], "camera": CAMERA}, moved["settings"]
        assert moved["camera"] == CAMERA and moved["scene"] == first["scene"], moved
        finished_exr(service, moved["id"], path("moved.exr"))
        render_cli(demo_scene(), {**SETTINGS, "camera": CAMERA}, path("moved-cli.exr"))
        assert_identical(path("moved.exr"), path("moved-cli.exr"))
        # The move changed the image: the comparison above is not of two copies of the first.
        result = subprocess.run([binary("tests", "service", "exr_equal"), path("moved.exr"),
                                 path("original.exr")], capture_output=True)
        assert result.returncode == 1, "the camera changed nothing"

        # A region at the moved camera, from the moved job; then back to the whole image.
        region = [13, 9, 70, 50]
        part, _ = rerender(service, moved["id"], {"settings": {"region": region}})
        assert part["settings"]["region"] == region and part["camera"] == CAMERA, part
        finished_exr(service, part["id"], path("part.exr"))
        assert_region_identical(path("part.exr"), path("moved-cli.exr"), region)
        whole, _ = rerender(service, part["id"], {"settings": {"region": None}})
        assert "region" not in whole["settings"], whole["settings"]
        finished_exr(service, whole["id"], path("whole.exr"))
        assert_identical(path("whole.exr"), path("moved-cli.exr"))

        # A VRML world sent by tessera-submit, its Inline and texture in the bundle, moved.
        world = os.path.join(service_test.ARGS.source, "scenes", "vrml", "world.wrl")
        flags = {"width": 64, "height": 48, "aa": 5}
        result = subprocess.run(
            [binary("client", "tessera-submit"), world, "--coordinator",
             "http://127.0.0.1:%d" % service.http_port, "--quiet",
             *[arg for key, value in flags.items() for arg in ("--" + key, str(value))]],
            capture_output=True, text=True, timeout=100)
        assert result.returncode == 0, result.stdout + result.stderr
        submitted = max(service.get("/api/jobs"), key=lambda j: j["id"])
        assert service.wait_job(submitted["id"])["state"] == "done"
        camera = {"eye": [1.5, 3, 8], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov": 35}
        world_moved, _ = rerender(service, submitted["id"], {"settings": {"camera": camera}})
        assert "image_texture" in world_moved["effects"], world_moved["effects"]
        finished_exr(service, world_moved["id"], path("world.exr"))
        render_cli(world, {**flags, "camera": camera}, path("world-cli.exr"))
        assert_identical(path("world.exr"), path("world-cli.exr"))


def case_answers():
    with Service("--max-jobs-per-client", "2") as service:  # no workers: jobs stay queued
        job = service.submit("sphere\n", {"width": 32, "height": 24})["id"]
        for body, says in [({"settings": {"aa": 4}}, "settings.aa"),
                           ({"settings": {"camera": {"eye": [0, 0, 1]}}}, "settings.camera"),
                           ({"settings": {"region": [0, 0, 33, 8]}}, "settings.region"),
                           ({"settings": {"colour": 1}}, "unknown setting \"colour\""),
                           ({"settings": {"colour": None}}, "unknown setting \"colour\""),
                           ({"scene": "sphere\n"}, "unknown field \"scene\""),
                           ({"settings": []}, "settings must be an object")]:
            error, _ = rerender(service, job, body, expect=400)
            assert error["error"] == "bad_request" and says in error["detail"], (body, error)
        error, _ = rerender(service, job, b"[1, 2", expect=400)
        assert error["error"] == "bad_json", error
        error, _ = rerender(service, 999, {}, expect=404)
        assert error["error"] == "not_found", error
        status, _, reply = service.request("GET", "/api/jobs/%d/rerender" % job)
        assert status == 405 and json.loads(reply)["error"] == "method_not_allowed", reply
        # An empty body is no change; the client's second unfinished job, then the cap.
        status, _, reply = service.request("POST", "/api/jobs/%d/rerender" % job)
        assert status == 201, (status, reply)
        error, _ = rerender(service, job, {}, expect=429)
        assert error["error"] == "too_many_jobs", error

    with Service("--api-token", "tok3n") as service:
        token = {"Authorization": "Bearer tok3n"}
        status, _, reply = service.request(
            "POST", "/api/jobs", json.dumps({"scene": "sphere\n"}).encode(), {**JSON, **token})
        assert status == 201, reply
        job = json.loads(reply)["id"]
        error, _ = rerender(service, job, {}, expect=401)
        assert error["error"] == "unauthorized", error
        error, _ = rerender(service, job, {}, expect=403, headers={**token,
                                                                   "Origin": "https://evil.example"})
        assert error["error"] == "cross_origin", error
        rerender(service, job, {}, headers=token)

    address = non_loopback_address()
    if address is None:
        print("no non-loopback address: the loopback-only rule is covered by test_coordinator")
        return
    with Service(host=address) as service:
        loopback = copy.copy(service)  # the same coordinator, reached over loopback
        loopback.host = "127.0.0.1"
        job = loopback.submit("sphere\n", {"width": 32, "height": 24})["id"]
        error, _ = rerender(service, job, {}, expect=403)
        assert error["error"] == "forbidden" and "--api-token" in error["detail"], error
        rerender(loopback, job, {})


if __name__ == "__main__":
    service_test.run_case(globals())

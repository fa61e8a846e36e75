#!/usr/bin/env python3
"""Integration tests of the distributed service (issue 4, item 7): the real coordinator,
workers and tessera-render as processes on loopback, on ports the system picks (port 0; the
coordinator tells them through --port-file, so no test races another program for a port).

usage: service_test.py --build BUILD_DIR --source SOURCE_DIR CASE
CASE: bit_identical | bundle | worker_faults | auth | http_errors | cancel | prediction
"""
import argparse
import io
import json
import math
import os
import signal
import socket
import subprocess
import tarfile
import tempfile
import time
import urllib.error
import urllib.request

ARGS = None
SECRET = "integration-secret"
# Small enough to be quick on two cores, large enough to have several levels and passes.
SETTINGS = {"width": 96, "height": 72, "aa": 5, "stochastic": True, "passes": 2, "seed": 7}


def binary(*parts):
    return os.path.join(ARGS.build, *parts)


def start_coordinator(build, argv, log, port_file, timeout=10, prefix=(), bind="127.0.0.1"):
    """Starts tessera-coordinator on ports the system picks; returns (process, http_port,
    worker_port) once both listen, or kills it and raises. `prefix` runs it under another
    command (tests/multihost: `ip netns exec NS`)."""
    proc = subprocess.Popen(
        [*prefix, os.path.join(build, "coordinator", "tessera-coordinator"), "--bind", bind,
         "--http-port", "0", "--worker-port", "0", "--port-file", port_file,
         # Each coordinator its own job store, unless the test names one (durable_test.py).
         "--data-dir", os.path.join(os.path.dirname(port_file), "data"), *argv],
        stdout=log, stderr=subprocess.STDOUT)
    deadline = time.time() + timeout
    while not os.path.exists(port_file):
        if proc.poll() is not None or time.time() > deadline:
            proc.kill()
            proc.wait()
            raise RuntimeError("the coordinator did not start (exit %s); see its log" %
                               proc.returncode)
        time.sleep(0.02)
    with open(port_file) as f:
        ports = json.load(f)
    return proc, ports["http_port"], ports["worker_port"]


class Service:
    """A coordinator and its workers; everything it started is killed on exit. By default all
    on loopback; tests/multihost runs the coordinator in a network namespace (`prefix`),
    listening on every address, and reaches its API at `host`."""

    def __init__(self, *extra, secret=SECRET, prefix=(), host="127.0.0.1"):
        self.host = host
        self.procs = []
        self.tmp = tempfile.TemporaryDirectory()
        auth = ["--secret", secret] if secret else ["--insecure"]
        log_path = os.path.join(self.tmp.name, "coordinator.log")
        with open(log_path, "w") as log:
            try:
                self.coordinator, self.http_port, self.worker_port = start_coordinator(
                    ARGS.build, [*auth, *extra], log, os.path.join(self.tmp.name, "ports.json"),
                    prefix=prefix, bind="127.0.0.1" if host == "127.0.0.1" else "0.0.0.0")
            except RuntimeError:
                print(open(log_path).read()[-3000:])
                self.tmp.cleanup()
                raise
        self.procs.append(self.coordinator)

    def spawn(self, argv, name):
        log = open(os.path.join(self.tmp.name, name + ".log"), "w")
        proc = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT)
        self.procs.append(proc)
        return proc

    def worker(self, name, secret=SECRET, threads=1, prefix=(), address="127.0.0.1", port=None,
               extra=()):
        argv = [*prefix, binary("worker", "tessera-worker"), "--coordinator",
                "%s:%d" % (address, port or self.worker_port), "--threads", str(threads),
                "--name", name, *extra]
        if secret:
            argv += ["--secret", secret]
        return self.spawn(argv, name)

    def wait_workers(self, count, timeout=10):
        deadline = time.time() + timeout
        while len(self.get("/api/workers")) < count:
            if time.time() > deadline:
                raise AssertionError("workers did not join: %s" % self.get("/api/workers"))
            time.sleep(0.05)

    def request(self, method, path, body=None, headers=None):
        req = urllib.request.Request("http://%s:%d%s" % (self.host, self.http_port, path),
                                     data=body, method=method, headers=headers or {})
        try:
            with urllib.request.urlopen(req, timeout=30) as r:
                return r.status, dict(r.headers), r.read()
        except urllib.error.HTTPError as e:
            return e.code, dict(e.headers), e.read()

    def get(self, path):
        status, _, body = self.request("GET", path)
        assert status == 200, (path, status, body)
        return json.loads(body)

    def submit(self, scene, settings, expect=201):
        body = json.dumps({"scene": scene, "settings": settings}).encode()
        status, _, reply = self.request("POST", "/api/jobs", body,
                                        {"Content-Type": "application/json"})
        assert status == expect, (status, reply)
        return json.loads(reply)

    def wait_job(self, job_id, timeout=60):
        deadline = time.time() + timeout
        while True:
            job = self.get("/api/jobs/%d" % job_id)
            if job["state"] not in ("queued", "running"):
                return job
            if time.time() > deadline:
                raise AssertionError("job %d still %s" % (job_id, job["state"]))
            time.sleep(0.05)

    def exr(self, job_id, path):
        status, _, body = self.request("GET", "/api/jobs/%d/image?format=exr" % job_id)
        assert status == 200, status
        with open(path, "wb") as f:
            f.write(body)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        for p in self.procs:
            if p.poll() is None:
                p.send_signal(signal.SIGCONT)
                p.kill()
            p.wait()
        if exc[0] is not None:  # show the logs of a failing case
            for name in sorted(os.listdir(self.tmp.name)):
                if os.path.isdir(os.path.join(self.tmp.name, name)):
                    continue  # the coordinator's data directory
                print("----- %s" % name)
                print(open(os.path.join(self.tmp.name, name)).read()[-3000:])
        self.tmp.cleanup()


def render_cli(scene_path, settings, out):
    argv = [binary("worker", "tessera-render"), scene_path, "-o", out, "--quiet"]
    for key in ("width", "height", "aa", "jitter", "seed", "passes", "time_samples", "shadows",
                "cone_samples", "shadow_jitter", "brightness"):
        if key in settings:
            argv += ["--" + key.replace("_", "-"), str(settings[key])]
    if settings.get("stochastic"):
        argv.append("--stochastic")
    if settings.get("normalize"):
        argv.append("--normalize")
    if "camera" in settings:
        c = settings["camera"]
        argv += ["--camera", *(repr(float(v)) for v in c["eye"] + c["look_at"] + c["up"]),
                 repr(float(c["fov"]))]
    subprocess.run(argv, check=True)


def assert_identical(a, b):
    result = subprocess.run([binary("tests", "service", "exr_equal"), a, b],
                            capture_output=True, text=True)
    assert result.returncode == 0, "images differ: " + result.stdout + result.stderr


def demo_scene():
    return os.path.join(ARGS.source, "scenes", "demo.sdl")


def render_and_compare(service, settings, tmp, name, scene=None):
    scene = scene or demo_scene()
    job = service.submit(open(scene).read(), settings)
    final = service.wait_job(job["id"])
    assert final["state"] == "done", final
    assert final["progress"] == 1.0
    service.exr(job["id"], os.path.join(tmp, name + ".exr"))
    render_cli(scene, settings, os.path.join(tmp, name + "-cli.exr"))
    assert_identical(os.path.join(tmp, name + ".exr"), os.path.join(tmp, name + "-cli.exr"))
    return final


def case_bit_identical():
    """1 and 3 workers give images bit-identical to tessera-render, in both unit orders, for a
    scene with boolean objects, and with soft shadows and post-normalization."""
    with tempfile.TemporaryDirectory() as tmp:
        for workers in (1, 3):
            with Service() as service:
                for i in range(workers):
                    service.worker("w%d" % i)
                service.wait_workers(workers)
                final = render_and_compare(service, SETTINGS, tmp, "w%d" % workers)
                # Every worker usually takes units; on a loaded machine a late one may find
                # none left, so two of three must have (the image is the same either way).
                assert len(final["workers"]) >= min(workers, 2), final["workers"]
                table = final["levels_table"]
                assert [row["level"] for row in table[:final["levels"]]] == \
                    list(range(1, final["levels"] + 1))
                assert table[0]["blocks"] in (2, 4)
                scan = dict(SETTINGS, order="scanline", preview="area", passes=1)
                render_and_compare(service, scan, tmp, "scan%d" % workers)
                # Boolean objects travel as SDL and are rebuilt by every worker alike.
                render_and_compare(service, SETTINGS, tmp, "csg%d" % workers,
                                   os.path.join(ARGS.source, "scenes", "features", "csg.sdl"))
                # Soft shadows' cones and the post-normalized final image match too.
                shaded = dict(SETTINGS, aa=1, passes=1, shadows="soft", cone_samples=5,
                              normalize=True, brightness=0.9)
                final = render_and_compare(service, shaded, tmp, "shaded%d" % workers)
                assert "soft_shadows" in final["effects"], final["effects"]
                # The PNG carries an ETag; asking again with it gets 304, not the image again.
                status, headers, _ = service.request("GET", "/api/jobs/%d/image" % final["id"])
                assert status == 200 and headers.get("ETag"), headers
                status, _, _ = service.request("GET", "/api/jobs/%d/image" % final["id"],
                                               headers={"If-None-Match": headers["ETag"]})
                assert status == 304, status


def case_bundle():
    """A tar bundle with a scene and its mesh, one with its image texture, a scene of
    --scenes-dir with an include, a moving scene with its time samples, and the same scene as
    a multipart form render like tessera-render on the folder."""
    features = os.path.join(ARGS.source, "scenes", "features")
    buf = io.BytesIO()
    with tarfile.open(fileobj=buf, mode="w", format=tarfile.USTAR_FORMAT) as tar:
        tar.add(os.path.join(features, "mesh.sdl"), "mesh.sdl")
        tar.add(os.path.join(features, "meshes", "icosphere.obj"), "meshes/icosphere.obj")
    image_buf = io.BytesIO()
    with tarfile.open(fileobj=image_buf, mode="w", format=tarfile.USTAR_FORMAT) as tar:
        tar.add(os.path.join(features, "image_texture.sdl"), "image_texture.sdl")
        tar.add(os.path.join(features, "textures", "gradient.bmp"), "textures/gradient.bmp")
    settings = {"width": 64, "height": 48}
    with tempfile.TemporaryDirectory() as tmp, Service("--local-workers", "2",
                                                       "--local-threads", "1",
                                                       "--scenes-dir", features) as service:
        status, _, body = service.request(
            "POST", "/api/jobs?main=mesh.sdl&width=64&height=48", buf.getvalue(),
            {"Content-Type": "application/x-tar"})
        assert status == 201, (status, body)
        job = json.loads(body)
        final = service.wait_job(job["id"])
        assert final["state"] == "done", final
        service.exr(job["id"], os.path.join(tmp, "svc.exr"))
        render_cli(os.path.join(features, "mesh.sdl"), settings, os.path.join(tmp, "cli.exr"))
        assert_identical(os.path.join(tmp, "svc.exr"), os.path.join(tmp, "cli.exr"))

        # The image texture travels in the bundle: the workers read no files of their own.
        status, _, body = service.request(
            "POST", "/api/jobs?main=image_texture.sdl&width=64&height=48", image_buf.getvalue(),
            {"Content-Type": "application/x-tar"})
        assert status == 201, (status, body)
        job = json.loads(body)
        final = service.wait_job(job["id"])
        assert final["state"] == "done", final
        assert "image_texture" in final["effects"], final["effects"]
        service.exr(job["id"], os.path.join(tmp, "image.exr"))
        render_cli(os.path.join(features, "image_texture.sdl"), settings,
                   os.path.join(tmp, "image-cli.exr"))
        assert_identical(os.path.join(tmp, "image.exr"), os.path.join(tmp, "image-cli.exr"))

        status, _, body = service.request(
            "POST", "/api/jobs", json.dumps({"scene_file": "macros.sdl", "settings": settings}).encode(),
            {"Content-Type": "application/json"})
        assert status == 201, (status, body)
        job = json.loads(body)
        assert service.wait_job(job["id"])["state"] == "done"
        service.exr(job["id"], os.path.join(tmp, "dir.exr"))
        render_cli(os.path.join(features, "macros.sdl"), settings, os.path.join(tmp, "dir-cli.exr"))
        assert_identical(os.path.join(tmp, "dir.exr"), os.path.join(tmp, "dir-cli.exr"))

        # Motion blur: moving shapes and their time samples give the same pixels everywhere.
        blur = dict(settings, time_samples=3)
        status, _, body = service.request(
            "POST", "/api/jobs", json.dumps({"scene_file": "motion_blur.sdl", "settings": blur}).encode(),
            {"Content-Type": "application/json"})
        assert status == 201, (status, body)
        job = json.loads(body)
        final = service.wait_job(job["id"])
        assert final["state"] == "done" and "motion_blur" in final["effects"], final
        service.exr(job["id"], os.path.join(tmp, "blur.exr"))
        render_cli(os.path.join(features, "motion_blur.sdl"), blur, os.path.join(tmp, "blur-cli.exr"))
        assert_identical(os.path.join(tmp, "blur.exr"), os.path.join(tmp, "blur-cli.exr"))

        # The same scene as a form: the scene text and its included file as a file part.
        boundary = "tessera-test-boundary"
        fields = [('name="scene"', open(os.path.join(features, "macros.sdl")).read()),
                  ('name="file"; filename="parts/lamp_post.sdl"',
                   open(os.path.join(features, "parts", "lamp_post.sdl")).read()),
                  ('name="settings"', json.dumps(settings))]
        form = "".join("--%s\r\nContent-Disposition: form-data; %s\r\n\r\n%s\r\n" %
                       (boundary, disposition, data) for disposition, data in fields)
        form += "--%s--\r\n" % boundary
        status, _, body = service.request(
            "POST", "/api/jobs", form.encode(),
            {"Content-Type": "multipart/form-data; boundary=" + boundary})
        assert status == 201, (status, body)
        job = json.loads(body)
        assert service.wait_job(job["id"])["state"] == "done"
        service.exr(job["id"], os.path.join(tmp, "form.exr"))
        assert_identical(os.path.join(tmp, "form.exr"), os.path.join(tmp, "dir-cli.exr"))


def case_vrml():
    """VRML worlds as tar bundles, the single top-level world the scene: one with an Inline and
    a texture, and a gzip-compressed one as modelling tools export them. Each renders
    bit-identical to tessera-render on its folder; the effects include the directional light,
    and the ignored ROUTEs come back as one warning."""
    folder = os.path.join(ARGS.source, "scenes", "vrml")
    worlds = {"world.wrl": ["world.wrl", "parts/arch.wrl", "textures/gradient.bmp"],
              "exported.wrl.gz": ["exported.wrl.gz", "textures/gradient.bmp"]}
    settings = {"width": 64, "height": 48}
    with tempfile.TemporaryDirectory() as tmp, Service("--local-workers", "2",
                                                       "--local-threads", "1") as service:
        for main, files in worlds.items():
            buf = io.BytesIO()
            with tarfile.open(fileobj=buf, mode="w", format=tarfile.USTAR_FORMAT) as tar:
                for name in files:
                    tar.add(os.path.join(folder, name), name)
            status, _, body = service.request(
                "POST", "/api/jobs?format=vrml&width=64&height=48", buf.getvalue(),
                {"Content-Type": "application/x-tar"})
            assert status == 201, (main, status, body)
            job = json.loads(body)
            assert "directional_light" in job["effects"], job
            assert any("ROUTE (2)" in w for w in job["warnings"]), job["warnings"]
            final = service.wait_job(job["id"])
            assert final["state"] == "done", final
            service.exr(job["id"], os.path.join(tmp, "svc.exr"))
            render_cli(os.path.join(folder, main), settings, os.path.join(tmp, "cli.exr"))
            assert_identical(os.path.join(tmp, "svc.exr"), os.path.join(tmp, "cli.exr"))


CAMERA_SDL = """eyePoint 0 1 8
viewPoint 0 1 0
upDirection 0 1 0
viewAngle 40
light 3 4 5 1 1 1
diffuse 1 0.2 0.2 specular 0.5 0.5 0.5 specularExponent 20
sphere
push translate 1.5 0 -1 diffuse 0.2 0.2 1 cube pop
"""

CAMERA_VRML = """#VRML V2.0 utf8
Viewpoint { position 0 0 10 description "Start" }
Viewpoint { position 0 4 4 orientation 1 0 0 -0.7853981633974483 description "Above" }
Shape { appearance Appearance { material Material { diffuseColor 1 0.3 0.3 } }
        geometry Sphere {} }
Billboard { children Transform { translation 0 0 -2 children Shape {
  appearance Appearance { material Material { diffuseColor 0.3 0.3 1 } }
  geometry Box { size 3 0.5 0.1 } } } }
"""


def submit_format(service, scene, fmt, settings, expect=201):
    body = json.dumps({"scene": scene, "format": fmt, "settings": settings}).encode()
    status, _, reply = service.request("POST", "/api/jobs", body,
                                       {"Content-Type": "application/json"})
    assert status == expect, (status, reply)
    return json.loads(reply)


def case_camera():
    """A job's camera setting renders bit-identical to the scene file edited to that camera,
    and so does tessera-render --camera, for SDL (vertical viewAngle) and for VRML
    (fieldOfView; the headlight and a Billboard follow the camera). The job's status shows the
    camera in effect and the world's Viewpoints; a degenerate camera is a 400 naming it."""
    sdl_camera = {"eye": [-2, 0.5, 6], "look_at": [0, -0.25, 0], "up": [0.1, 1, 0], "fov": 33.5}
    sdl_edited = (CAMERA_SDL.replace("eyePoint 0 1 8", "eyePoint -2 0.5 6")
                  .replace("viewPoint 0 1 0", "viewPoint 0 -0.25 0")
                  .replace("upDirection 0 1 0", "upDirection 0.1 1 0")
                  .replace("viewAngle 40", "viewAngle 33.5"))
    # A Viewpoint's camera looks at the point one unit ahead; fieldOfView 0.5 rad in degrees
    # as the loader converts it.
    vrml_camera = {"eye": [2, 1, 8], "look_at": [2, 1, 7], "up": [0, 1, 0],
                   "fov": 0.5 * 180 / math.pi}
    vrml_edited = CAMERA_VRML.replace('position 0 0 10 description "Start"',
                                      'position 2 1 8 fieldOfView 0.5')
    cases = [("sdl", "scene.sdl", CAMERA_SDL, sdl_edited, sdl_camera),
             ("vrml", "world.wrl", CAMERA_VRML, vrml_edited, vrml_camera)]
    with tempfile.TemporaryDirectory() as tmp, Service("--local-workers", "2",
                                                       "--local-threads", "1") as service:
        for fmt, name, original, edited, camera in cases:
            settings = {"width": 48, "height": 64, "aa": 5}  # portrait: VRML's angle is across
            original_path = os.path.join(tmp, name)
            edited_path = os.path.join(tmp, "edited-" + name)
            with open(original_path, "w") as f:
                f.write(original)
            with open(edited_path, "w") as f:
                f.write(edited)
            render_cli(edited_path, settings, os.path.join(tmp, "edited.exr"))
            render_cli(original_path, {**settings, "camera": camera},
                       os.path.join(tmp, "cli.exr"))
            assert_identical(os.path.join(tmp, "cli.exr"), os.path.join(tmp, "edited.exr"))
            render_cli(original_path, settings, os.path.join(tmp, "unmoved.exr"))
            result = subprocess.run([binary("tests", "service", "exr_equal"),
                                     os.path.join(tmp, "unmoved.exr"),
                                     os.path.join(tmp, "edited.exr")], capture_output=True)
            assert result.returncode == 1, "the camera changed nothing in " + fmt

            job = submit_format(service, original, fmt, {**settings, "camera": camera})
            final = service.wait_job(job["id"])
            assert final["state"] == "done", final
            assert final["settings"]["camera"] == camera, final["settings"]
            assert final["camera"] == camera, final["camera"]
            assert final["format"] == fmt
            service.exr(job["id"], os.path.join(tmp, "svc.exr"))
            assert_identical(os.path.join(tmp, "svc.exr"), os.path.join(tmp, "edited.exr"))

        plain = service.get("/api/jobs/%d" % submit_format(service, CAMERA_VRML, "vrml",
                                                            {"width": 8, "height": 8})["id"])
        assert [v["name"] for v in plain["viewpoints"]] == ["Start", "Above"], plain
        assert plain["camera"] == plain["viewpoints"][0]["camera"], plain
        assert plain["camera"]["eye"] == [0, 0, 10], plain["camera"]
        sdl = service.get("/api/jobs/%d" % service.submit(CAMERA_SDL, {"width": 8})["id"])
        assert sdl["camera"] == {"eye": [0, 1, 8], "look_at": [0, 1, 0], "up": [0, 1, 0],
                                 "fov": 40}, sdl["camera"]
        assert sdl["viewpoints"] == []

        for bad, says in [({**sdl_camera, "look_at": sdl_camera["eye"]}, "eye apart"),
                          ({**sdl_camera, "up": [4, -1.5, -12]}, "up direction"),
                          ({**sdl_camera, "fov": 180}, "fov in (0, 180)"),
                          ({"eye": [0, 0, 1], "look_at": [0, 0, 0]}, "\"fov\": degrees")]:
            reply = service.submit(CAMERA_SDL, {"camera": bad}, expect=400)
            assert reply["error"] == "bad_request", reply
            assert reply["detail"].startswith("settings.camera ") and says in reply["detail"], \
                reply


def case_worker_faults():
    """A worker killed with SIGKILL mid-level, and one that goes silent (SIGSTOP), lose their
    units to the others; the image is still identical to tessera-render."""
    # Large enough that the job is still running when the test sees both victims busy: at
    # 320x240 it took 0.6 s once pixels shared their grid samples, and about one run in 20
    # finished before that.
    settings = dict(SETTINGS, width=480, height=360, aa=9, passes=3)
    with tempfile.TemporaryDirectory() as tmp, Service("--heartbeat-ms", "200",
                                                       "--silence-ms", "1500") as service:
        victims = [service.worker("victim"), service.worker("sleeper")]
        service.worker("survivor")
        service.wait_workers(3)
        job = service.submit(open(demo_scene()).read(), settings)
        deadline = time.time() + 30
        while True:
            status = service.get("/api/jobs/%d" % job["id"])
            busy = {w["name"]: w["in_flight"] for w in service.get("/api/workers")}
            if 0.05 < status["progress"] < 0.6 and busy.get("victim") and busy.get("sleeper"):
                break
            assert status["state"] == "running" or status["progress"] < 0.05, status
            assert time.time() < deadline, "job never got under way"
            time.sleep(0.01)
        level = status["level"]
        victims[0].send_signal(signal.SIGKILL)
        victims[1].send_signal(signal.SIGSTOP)
        final = service.wait_job(job["id"])
        assert final["state"] == "done", final
        # The job may end before the sleeper's silence runs out (the others finish its units);
        # it must still be dropped once --silence-ms has passed.
        deadline = time.time() + 5
        while {"victim", "sleeper"} & {w["name"] for w in service.get("/api/workers")}:
            assert time.time() < deadline, service.get("/api/workers")
            time.sleep(0.05)
        print("killed at level %s, progress %.2f" % (level, status["progress"]))
        service.exr(job["id"], os.path.join(tmp, "svc.exr"))
        render_cli(demo_scene(), settings, os.path.join(tmp, "cli.exr"))
        assert_identical(os.path.join(tmp, "svc.exr"), os.path.join(tmp, "cli.exr"))


def case_auth():
    """A worker with the wrong secret, or none, is refused and exits; the right one joins."""
    with Service() as service:
        wrong = service.worker("wrong", secret="not-the-secret")
        missing = service.worker("missing", secret="")
        assert wrong.wait(timeout=10) != 0
        assert missing.wait(timeout=10) != 0
        assert service.get("/api/workers") == []
        service.worker("right")
        service.wait_workers(1)
        assert [w["name"] for w in service.get("/api/workers")] == ["right"]
    # A raw peer that sends garbage instead of a hello is dropped; the coordinator lives on.
    with Service() as service:
        with socket.create_connection(("127.0.0.1", service.worker_port)) as s:
            s.sendall(b"\xff\xff\xff\xff" + b"x" * 64)
            s.settimeout(5)
            assert s.recv(16) == b""
        assert service.get("/api/workers") == []


def case_http_errors():
    """Malformed requests and scenes get their 4xx with JSON errors; nothing breaks."""
    with Service("--max-body-bytes", "65536") as service:
        def post(body, content_type="application/json"):
            status, _, reply = service.request("POST", "/api/jobs", body,
                                               {"Content-Type": content_type})
            return status, json.loads(reply)

        status, err = post(b"{not json")
        assert status == 400 and err["error"] == "bad_json", err
        status, err = post(json.dumps({"scene": "sphere\nfrobnicate 1 2\n"}).encode())
        assert status == 400 and err["error"] == "scene_error", err
        assert err["line"] == 2 and err["column"] >= 1 and "detail" in err, err
        for settings in ({"aa": 3}, {"width": 100000}, {"passes": 0}, {"colour": 1},
                         {"order": "spiral"}, {"seed": -1}, {"max_depth": 99}):
            status, err = post(json.dumps({"scene": "sphere", "settings": settings}).encode())
            assert status == 400 and err["error"] == "bad_request", (settings, err)
        status, err = post(json.dumps({"scene": "maxRecursionDepth 1000\nsphere"}).encode())
        assert status == 400, err
        status, err = post(json.dumps({"scene": "include ../../etc/passwd\n"}).encode())
        assert status == 400 and err["error"] == "scene_error", err
        status, err = post(json.dumps({"scene": "sphere", "files": {"../x": "y"}}).encode())
        assert status == 400 and err["error"] == "bad_bundle", err
        status, err = post(json.dumps({"scene": "sphere", "format": "vrml"}).encode())
        assert status == 400 and err["error"] == "scene_error" and err["line"] == 1, err
        status, err = post(json.dumps({"scene": "sphere", "format": "obj"}).encode())
        assert status == 400 and err["error"] == "bad_request", err
        status, err = post(b"scene", "text/plain")
        assert status == 415, err
        status, err = post(json.dumps({"scene": "!" * 100000}).encode())
        assert status == 413 and err["error"] == "payload_too_large", err
        for method, path, code in (("GET", "/api/jobs/999", 404), ("GET", "/api/jobs/abc", 404),
                                   ("DELETE", "/api/workers", 405), ("GET", "/api/nothing", 404),
                                   ("GET", "/../etc/passwd", 404),
                                   ("GET", "/api/jobs/1/image?format=gif", 404)):
            status, _, reply = service.request(method, path)
            assert status == code, (method, path, status, reply)
            assert "error" in json.loads(reply), reply
        status, _, page = service.request("GET", "/")
        assert status == 200 and b"<html" in page.lower(), status
        assert service.get("/api/jobs") == []


def case_cancel():
    """DELETE cancels a running job and frees its workers at once."""
    with Service("--local-workers", "2", "--local-threads", "1") as service:
        service.wait_workers(2)
        job = service.submit(open(demo_scene()).read(),
                             {"width": 1024, "height": 768, "aa": 9, "passes": 8})
        deadline = time.time() + 20
        while service.get("/api/jobs/%d" % job["id"])["progress"] <= 0:
            assert time.time() < deadline
            time.sleep(0.05)
        status, _, body = service.request("DELETE", "/api/jobs/%d" % job["id"])
        assert status == 200 and json.loads(body)["state"] == "cancelled", body
        workers = service.get("/api/workers")
        assert all(w["in_flight"] == 0 for w in workers), workers
        time.sleep(1.0)  # a unit already being traced may finish; nothing new starts
        before = sum(w["units_done"] for w in service.get("/api/workers"))
        time.sleep(1.0)
        after = sum(w["units_done"] for w in service.get("/api/workers"))
        assert before == after, (before, after)
        assert service.get("/api/jobs/%d" % job["id"])["state"] == "cancelled"
        # The freed workers take the next job straight away.
        small = service.submit(open(demo_scene()).read(), {"width": 32, "height": 24})
        assert service.wait_job(small["id"], timeout=20)["state"] == "done"


def case_prediction():
    """A job's time is predicted at submission (and on demand), then learnt from."""
    with Service() as service:
        scene = open(demo_scene()).read()
        body = json.dumps({"scene": scene, "settings": SETTINGS}).encode()
        headers = {"Content-Type": "application/json"}

        def predict():
            status, _, reply = service.request("POST", "/api/predict", body, headers)
            assert status == 200, (status, reply)
            return json.loads(reply)

        alone = predict()  # no worker connected: nothing to predict with
        assert alone["predicted_seconds"] is None and alone["threads"] == 0, alone
        assert alone["seconds_per_pixel_pass"] > 0 and alone["pixel_passes"] == 96 * 72 * 2
        service.worker("w1", threads=2)
        service.wait_workers(1)
        first = predict()
        assert first["threads"] == 2 and first["calibration"] == 1, first
        assert first["predicted_seconds"] > 0
        job = service.submit(scene, SETTINGS)
        assert job["predicted_seconds"] > 0, job
        done = service.wait_job(job["id"])
        assert done["predicted_seconds"] == job["predicted_seconds"]
        assert predict()["calibration"] != 1  # the finished job taught the estimator
        bad = json.dumps({"scene": "sphere\ntranslate 1 x 0"}).encode()
        status, _, reply = service.request("POST", "/api/predict", bad, headers)
        assert status == 400 and json.loads(reply)["line"] == 2, (status, reply)
        status, _, _ = service.request("GET", "/api/predict")
        assert status == 405


def run_case(cases):
    """The command line every service test script takes, `--build DIR --source DIR CASE`: runs
    the function `case_CASE` of `cases` (the script's globals()) and says how long it took.
    Sets ARGS first: the helpers here, and the cases, find the binaries through it."""
    global ARGS
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("case")
    ARGS = parser.parse_args()
    start = time.time()
    cases["case_" + ARGS.case]()
    print("%s passed in %.1f s" % (ARGS.case, time.time() - start))


if __name__ == "__main__":
    run_case(globals())

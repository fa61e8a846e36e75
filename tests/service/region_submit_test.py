#!/usr/bin/env python3
"""Regions and tessera-submit (issue 21 §4, §5), each by its own case:

  region  a region's pixels are bit for bit the whole image's and the rest is black, through
          tessera-render --region and through the service (JSON and a tar's query); the
          service's plan traces only the region's pixels; a bad region is a 400 naming it.
  submit  tessera-submit sends a VRML world with its Inline and texture, and an SDL scene with
          its include as a region, and writes images bit-identical to tessera-render's; plain
          progress lines when stdout is not a terminal; bad flags and scenes are named; Ctrl-C
          cancels the job.

usage: region_submit_test.py --build BUILD_DIR --source SOURCE_DIR CASE
"""
import argparse
import io
import json
import os
import signal
import subprocess
import sys
import tarfile
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import service_test  # noqa: E402  (the Service helpers; ARGS is set below)
from service_test import Service, binary, demo_scene, render_cli  # noqa: E402

SETTINGS = service_test.SETTINGS  # 96 x 72, aa 5, stochastic, 2 passes
REGION = [13, 9, 70, 50]


def assert_region_identical(part, whole, region):
    result = subprocess.run([binary("tests", "service", "exr_equal"), part, whole,
                             *map(str, region)], capture_output=True, text=True)
    assert result.returncode == 0, "region differs: " + result.stdout + result.stderr


def render_region_cli(scene, settings, region, out):
    """tessera-render with --region: render_cli's flags plus the region."""
    argv = [binary("worker", "tessera-render"), scene, "-o", out, "--quiet",
            "--region", *map(str, region)]
    for key, value in settings.items():
        if value is True:
            argv.append("--" + key)
        else:
            argv += ["--" + key.replace("_", "-"), str(value)]
    subprocess.run(argv, check=True)


def case_region():
    with tempfile.TemporaryDirectory() as tmp:
        whole = os.path.join(tmp, "whole.exr")
        render_cli(demo_scene(), SETTINGS, whole)
        cli = os.path.join(tmp, "cli-region.exr")
        render_region_cli(demo_scene(), SETTINGS, REGION, cli)
        assert_region_identical(cli, whole, REGION)

        with Service("--local-workers", "2", "--local-threads", "1") as service:
            job = service.submit(open(demo_scene()).read(), dict(SETTINGS, region=REGION))
            assert job["settings"]["region"] == REGION, job["settings"]
            final = service.wait_job(job["id"])
            assert final["state"] == "done" and final["progress"] == 1.0, final
            # Only the region's pixels are traced: pass 0 once over the levels, then pass 1.
            area = (REGION[2] - REGION[0]) * (REGION[3] - REGION[1])
            traced = sum(row["traced"] for row in final["levels_table"])
            assert traced == SETTINGS["passes"] * area, (traced, area)
            svc = os.path.join(tmp, "svc-region.exr")
            service.exr(job["id"], svc)
            assert_region_identical(svc, whole, REGION)

            # A tar's settings come as query values: the region as JSON there too.
            buf = io.BytesIO()
            with tarfile.open(fileobj=buf, mode="w", format=tarfile.USTAR_FORMAT) as tar:
                tar.add(demo_scene(), "demo.sdl")
            query = "&".join("%s=%s" % (k, json.dumps(v).replace(" ", ""))
                             for k, v in dict(SETTINGS, region=REGION).items())
            status, _, body = service.request("POST", "/api/jobs?" + query, buf.getvalue(),
                                              {"Content-Type": "application/x-tar"})
            assert status == 201, (status, body)
            tar_job = json.loads(body)
            assert service.wait_job(tar_job["id"])["state"] == "done"
            service.exr(tar_job["id"], os.path.join(tmp, "tar-region.exr"))
            assert_region_identical(os.path.join(tmp, "tar-region.exr"), whole, REGION)

            bad = {"outside": [0, 0, 97, 10], "empty": [5, 5, 5, 9], "reversed": [9, 0, 5, 4],
                   "short": [0, 0, 4], "text": "0 0 4 4", "negative": [-1, 0, 4, 4]}
            for name, region in bad.items():
                body = json.dumps({"scene": open(demo_scene()).read(),
                                   "settings": dict(SETTINGS, region=region)}).encode()
                status, _, reply = service.request("POST", "/api/jobs", body,
                                                   {"Content-Type": "application/json"})
                error = json.loads(reply)
                assert status == 400 and "settings.region" in error["detail"], \
                    (name, status, error)
            body = json.dumps({"scene": open(demo_scene()).read(),
                               "settings": dict(SETTINGS, region=REGION, normalize=True)}).encode()
            status, _, reply = service.request("POST", "/api/jobs", body,
                                               {"Content-Type": "application/json"})
            assert status == 400 and "region" in json.loads(reply)["detail"], (status, reply)


def submit(service, argv, **kwargs):
    return subprocess.run([binary("client", "tessera-submit"), *argv, "--coordinator",
                           "http://127.0.0.1:%d" % service.http_port],
                          capture_output=True, text=True, timeout=100, **kwargs)


def case_submit():
    flags = ["--width", "64", "--height", "48", "--aa", "5", "--stochastic", "--passes", "2",
             "--seed", "7"]
    settings = {"width": 64, "height": 48, "aa": 5, "stochastic": True, "passes": 2, "seed": 7}
    world = os.path.join(ARGS.source, "scenes", "vrml", "world.wrl")  # an Inline, a texture
    macros = os.path.join(ARGS.source, "scenes", "features", "macros.sdl")  # an include
    with tempfile.TemporaryDirectory() as tmp, Service("--local-workers", "2",
                                                       "--local-threads", "1") as service:
        out = os.path.join(tmp, "world.exr")
        result = submit(service, [world, "-o", out, *flags])
        assert result.returncode == 0, result.stdout + result.stderr
        render_cli(world, settings, os.path.join(tmp, "world-cli.exr"))
        service_test.assert_identical(out, os.path.join(tmp, "world-cli.exr"))
        # Not a terminal: plain lines, one per level, pass or state, the last one "done".
        lines = result.stdout.splitlines()
        assert lines[0].startswith("submitted %s as http://" % world), lines
        progress = [line for line in lines if line.startswith(("queued:", "running:", "done:"))]
        assert progress[-1].startswith("done: level 6/6, pass 2/2, 100%"), lines
        assert len(progress) == len(set(progress)), lines
        assert lines[-1].startswith("wrote %s" % out), lines
        # The job holds exactly the files the world read.
        job = service.get("/api/jobs/1")
        assert job["scene"] == "world.wrl", job

        region = os.path.join(tmp, "macros-region.exr")
        result = submit(service, [macros, "-o", region, "--quiet", "--region", "3", "5", "40",
                                  "29", *flags])
        assert result.returncode == 0 and result.stdout == "", result.stdout + result.stderr
        render_cli(macros, settings, os.path.join(tmp, "macros-cli.exr"))
        assert_region_identical(region, os.path.join(tmp, "macros-cli.exr"), [3, 5, 40, 29])

        # Errors name what is wrong: a flag's value (exit 2), a scene's line (exit 1).
        result = submit(service, [macros, "--width", "64", "--region", "0", "0", "65", "8"])
        assert result.returncode == 2 and "--region [0, 0, 65, 8] must lie inside" in \
            result.stderr, result.stderr
        broken = os.path.join(tmp, "broken.sdl")
        with open(broken, "w") as f:
            f.write("sphere {\n  translate 1 2\n}\n")
        result = submit(service, [broken])
        assert result.returncode == 1 and "broken.sdl:" in result.stderr, result.stderr
        result = subprocess.run([binary("client", "tessera-submit"), macros, "--coordinator",
                                 "ftp://127.0.0.1:1"], capture_output=True, text=True)
        assert result.returncode == 1 and "expected http://HOST:PORT or https://" in \
            result.stderr, result.stderr

        # Ctrl-C while the job runs cancels it on the coordinator; exit status 130.
        proc = subprocess.Popen([binary("client", "tessera-submit"), service_test.demo_scene(),
                                 "--coordinator", "http://127.0.0.1:%d" % service.http_port,
                                 "--width", "1024", "--height", "1024", "--aa", "9", "--passes",
                                 "16", "--quiet"], stderr=subprocess.PIPE, text=True)
        deadline = time.time() + 30
        while not [j for j in service.get("/api/jobs") if j["state"] == "running"]:
            assert time.time() < deadline and proc.poll() is None, "the job never ran"
            time.sleep(0.05)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
        assert proc.returncode == 130 and "interrupted" in err, (proc.returncode, err)
        last = max(service.get("/api/jobs"), key=lambda j: j["id"])
        assert last["state"] == "cancelled", last


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("case")
    global ARGS
    ARGS = parser.parse_args()
    service_test.ARGS = ARGS
    start = time.time()
    globals()["case_" + ARGS.case]()
    print("%s passed in %.1f s" % (ARGS.case, time.time() - start))


if __name__ == "__main__":
    sys.exit(main())

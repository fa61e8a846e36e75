#!/usr/bin/env python3
"""Integration tests of interruptible units (issue 16 §3): a job with a few pixels of runaway
cost, which the cost probe does not see, holds the only worker thread of a coordinator until it
is cancelled or reaches its time limit; then the worker stops within 100 ms and the next job
runs at once.

usage: interrupt_test.py --build BUILD_DIR --source SOURCE_DIR CASE
CASE: cancel | time_limit
"""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import service_test  # noqa: E402  (the Service helpers; ARGS is set below)
from service_test import Service, demo_scene  # noqa: E402

# The eye inside a glossy mirror sphere, with two matte boxes in front of it that hide the hall
# from every pixel but the 2 x 2 in the top-left corner of a 128 x 128 image: the probe's grid
# (pixels 2, 6, 10, ...) sees only boxes, so the job is accepted as cheap. Each of those four
# pixels' samples spends the whole ray budget (common/render/tracer.h).
RUNAWAY_SCENE = """
eyePoint 0 0 0
viewPoint 0 0 -1
upDirection 0 1 0
viewAngle 90
light 0 0.5 0  1 1 1
! matte boxes whose edges fall on the image's pixel lines x = 2 and y = 2 (at z = -1,
! sx = sy = -0.96875 and 0.96875)
push translate 1.015625 0 -1.5  scale 1.984375 3 0.5  cube pop
push translate 0 -1.015625 -1.5  scale 3 1.984375 0.5  cube pop
push scale 10 10 10  reflectivity 0.95 glossStrength 0.5  sphere pop
"""
RUNAWAY = {"width": 128, "height": 128, "aa": 9, "passes": 4, "cone_samples": 64,
           "max_depth": 16, "min_weight": 0}
SMALL = {"width": 32, "height": 24}
# The next job's whole run: submission, probe, preparation on the worker and 768 pixels take
# a fraction of a second; a unit of the runaway job left running would take several seconds.
PROMPT_SECONDS = 2.0


def start_runaway(service):
    """Submits the runaway job and returns it once the worker has been tracing its corner for
    a while (the rest of the image takes milliseconds)."""
    job = service.submit(RUNAWAY_SCENE, RUNAWAY)
    deadline = time.time() + 10
    while service.get("/api/jobs/%d" % job["id"])["state"] != "running":
        assert time.time() < deadline, "the runaway job never started"
        time.sleep(0.02)
    time.sleep(1.0)
    status = service.get("/api/jobs/%d" % job["id"])
    assert status["state"] == "running" and status["progress"] < 1, status
    return job


def assert_next_job_is_prompt(service):
    start = time.time()
    small = service.submit(open(demo_scene()).read(), SMALL)
    final = service.wait_job(small["id"], timeout=30)
    took = time.time() - start
    assert final["state"] == "done", final
    assert took < PROMPT_SECONDS, "the next job took %.2f s: a unit kept the worker" % took
    print("next job done %.2f s after submission" % took)


def case_cancel():
    """DELETE of the runaway job stops the worker's unit in the middle of its pixels."""
    with Service("--local-workers", "1", "--local-threads", "1") as service:
        service.wait_workers(1)
        job = start_runaway(service)
        status, _, _ = service.request("DELETE", "/api/jobs/%d" % job["id"])
        assert status == 200, status
        assert_next_job_is_prompt(service)


def case_time_limit():
    """--max-job-seconds fails the runaway job with its time-limit error and frees the worker."""
    with Service("--local-workers", "1", "--local-threads", "1",
                 "--max-job-seconds", "1") as service:
        service.wait_workers(1)
        job = service.submit(RUNAWAY_SCENE, RUNAWAY)
        final = service.wait_job(job["id"], timeout=10)
        assert final["state"] == "failed", final
        assert "time limit of 1 s exceeded" in final["error"], final
        assert_next_job_is_prompt(service)


if __name__ == "__main__":
    service_test.run_case(globals())

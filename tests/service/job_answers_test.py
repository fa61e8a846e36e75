#!/usr/bin/env python3
"""What the HTTP API answers about jobs (issue 23 §3), each by its own case: a full job store,
`/api/jobs/{id}/tiles?since=` after a job's merges, and an image format it does not encode,
asked of a job that exists (so the 404 of a missing job cannot answer first).

usage: job_answers_test.py --build BUILD_DIR --source SOURCE_DIR CASE
CASE: full_store | tiles_since | image_format
"""
import json
import os
import signal
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import service_test  # noqa: E402  (the Service helpers; ARGS is set below)
from service_test import SETTINGS, Service, demo_scene  # noqa: E402
from tiles_test import get_tiles  # noqa: E402

SMALL = {"width": 32, "height": 24}
STORE_JOBS = 64  # ServiceLimits::max_jobs (coordinator/jobs/limits.h)


def case_full_store():
    """With the store full of unfinished jobs a submission gets 503 busy; a cancelled job makes
    room, and the next submission takes its place (the oldest finished job goes first)."""
    # No workers: every job stays queued. The per-client cap is raised above the store's.
    with Service("--max-jobs-per-client", "100") as service:
        ids = [service.submit("sphere\n", SMALL)["id"] for _ in range(STORE_JOBS)]
        body = json.dumps({"scene": "sphere\n", "settings": SMALL}).encode()
        headers = {"Content-Type": "application/json"}
        status, _, reply = service.request("POST", "/api/jobs", body, headers)
        err = json.loads(reply)
        assert status == 503 and err["error"] == "busy" and err["detail"], (status, err)
        assert len(service.get("/api/jobs")) == STORE_JOBS
        status, _, _ = service.request("DELETE", "/api/jobs/%d" % ids[0])
        assert status == 200
        status, _, reply = service.request("POST", "/api/jobs", body, headers)
        assert status == 201, (status, reply)
        status, _, _ = service.request("GET", "/api/jobs/%d" % ids[0])
        assert status == 404, status  # the cancelled job was dropped for the new one
        assert service.get("/api/jobs/%d" % ids[1])["state"] == "queued"


def case_tiles_since():
    """/tiles lists one record per merged unit, in merge order; ?since=k returns the records
    from the k-th on, and `next` is the count to ask from next time. Asked of a running job (a
    finished job keeps only its newest records): its only worker is stopped (SIGSTOP)
    meanwhile, so the count does not move under the test."""
    with Service() as service:
        worker = service.worker("w1", threads=1)
        service.wait_workers(1)
        settings = dict(SETTINGS, width=320, height=240, aa=9, passes=4)
        job = service.submit(open(demo_scene()).read(), settings)
        tiles = lambda since=0: get_tiles(service, job["id"], since)  # noqa: E731
        deadline = time.time() + 30
        while tiles()["next"] < 5:
            assert time.time() < deadline, service.get("/api/jobs/%d" % job["id"])
            time.sleep(0.02)
        worker.send_signal(signal.SIGSTOP)
        time.sleep(0.5)  # results already sent are merged; no more come
        status = service.get("/api/jobs/%d" % job["id"])
        assert status["state"] == "running", status
        merges = sum(w["units"] for w in status["workers"])
        everything = tiles()
        assert everything["next"] == merges == status["tiles"] >= 5, (everything, merges)
        records = everything["records"]
        assert len(records) == merges and not everything["whole"]
        worker_id = status["workers"][0]["id"]
        for r in records:
            x0, y0, x1, y1 = r["rect"]
            assert 0 <= x0 < x1 <= settings["width"] and 0 <= y0 < y1 <= settings["height"]
            assert r["worker"] == worker_id and r["stage"] >= 0 and r["values"]
        assert records[0]["stage"] == 0  # the first merge is of the first stage
        for since in (0, 1, merges // 2, merges - 1, merges, merges + 5):
            part = tiles(since)
            assert part["next"] == merges and part["records"] == records[since:], since
        status, _, reply = service.request("GET", "/api/jobs/%d/tiles?since=abc" % job["id"])
        assert status == 400 and json.loads(reply)["error"] == "bad_request", (status, reply)
        worker.send_signal(signal.SIGCONT)
        service.request("DELETE", "/api/jobs/%d" % job["id"])


def case_image_format():
    """An existing job's image in a format other than png or exr: 400 with a JSON error."""
    with Service() as service:  # no workers: the job stays queued, its image is black
        job = service.submit("sphere\n", SMALL)
        for fmt in ("gif", "PNG", ""):
            status, _, reply = service.request(
                "GET", "/api/jobs/%d/image?format=%s" % (job["id"], fmt))
            assert status == 400, (fmt, status)
            err = json.loads(reply)
            assert err["error"] == "bad_request", (fmt, err)
            assert "png or exr" in err["detail"], err
        for fmt in ("png", "exr"):
            status, _, _ = service.request("GET", "/api/jobs/%d/image?format=%s" % (job["id"], fmt))
            assert status == 200, (fmt, status)


if __name__ == "__main__":
    service_test.run_case(globals())

#!/usr/bin/env python3
"""GET /metrics while a job runs and after it (issue 17 §4): the Prometheus text parses, the
gauges show the running job and the connected worker, and once the job is done the counters
agree with the job's own status: units, pixel passes, rays, requests by route and status, the
worker port's frames and bytes; the store's size agrees with the data directory's files.

usage: metrics_scrape_test.py --build BUILD_DIR --source SOURCE_DIR
"""
import argparse
import os
import re
import sys
import time

import service_test
from service_test import Service

SAMPLE = re.compile(r'^([a-zA-Z_:][a-zA-Z0-9_:]*)(\{(.*)\})? (\S+)$')
LABEL = re.compile(r'([a-zA-Z_][a-zA-Z0-9_]*)="((?:[^"\\]|\\.)*)"')


def scrape(service):
    """{(name, frozenset(labels)): value}, checking every line against the text format."""
    status, headers, body = service.request("GET", "/metrics")
    assert status == 200, status
    assert headers["Content-Type"].startswith("text/plain; version=0.0.4"), headers
    samples, typed = {}, {}
    for line in body.decode().splitlines():
        if line.startswith("# HELP "):
            continue
        if line.startswith("# TYPE "):
            _, _, name, kind = line.split(" ")
            assert kind in ("counter", "gauge", "histogram"), line
            assert name.startswith("tessera_"), line
            assert (kind == "counter") == name.endswith("_total"), line
            typed[name] = kind
            continue
        m = SAMPLE.match(line)
        assert m, "not a sample line: %r" % line
        name, labels, value = m.group(1), m.group(3) or "", float(m.group(4))
        family = re.sub(r"_(bucket|sum|count)$", "", name) if name not in typed else name
        assert family in typed, "sample before its TYPE: %r" % line
        samples[(name, frozenset(LABEL.findall(labels)))] = value
    return samples


def value(samples, name, **labels):
    return samples[(name, frozenset(labels.items()))]


def files_bytes(top):
    return sum(os.path.getsize(os.path.join(folder, name))
               for folder, _, names in os.walk(top) for name in names)


def check_store(service, samples):
    """tessera_store_bytes counts the bundles, images and results' payload files and the
    database's used pages: more than the bundles and images, at most every file and the whole
    database with its WAL. (The results' files, read after the scrape, may have grown since
    while a job runs: they count only towards the most.)"""
    data = os.path.join(service.tmp.name, "data")
    store = value(samples, "tessera_store_bytes")
    files = files_bytes(os.path.join(data, "bundles")) + files_bytes(os.path.join(data, "images"))
    results = files_bytes(os.path.join(data, "results"))
    database = sum(os.path.getsize(os.path.join(data, name))
                   for name in ("tessera.db", "tessera.db-wal") if os.path.exists(
                       os.path.join(data, name)))
    assert files < store <= files + results + database, (files, store, results, database)
    return store


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", required=True)
    service_test.ARGS = parser.parse_args()
    with Service("--local-workers", "1", "--local-threads", "1") as service:
        service.wait_workers(1)
        before = scrape(service)
        assert value(before, "tessera_workers") == 1 and value(before, "tessera_worker_threads") == 1
        assert value(before, "tessera_units_finished_total") == 0
        # The local worker's handshake, and nothing it did not send.
        assert value(before, "tessera_worker_port_frames_total", direction="received",
                     type="hello") == 1
        assert value(before, "tessera_worker_port_frames_total", direction="sent",
                     type="welcome") == 1
        assert ("tessera_worker_port_frames_total",
                frozenset({("direction", "received"), ("type", "result")})) not in before
        store_before = check_store(service, before)
        with open(service_test.demo_scene()) as f:
            scene = f.read()
        job = service.submit(scene, {"width": 160, "height": 120, "aa": 5, "passes": 2})
        seen_running = False
        deadline = time.time() + 60
        while time.time() < deadline:
            samples = scrape(service)
            if value(samples, "tessera_jobs", state="running") == 1:
                seen_running = True
                assert value(samples, "tessera_units_dispatched_total") >= \
                    value(samples, "tessera_units_finished_total")
            if service.get("/api/jobs/%d" % job["id"])["state"] == "done":
                break
            time.sleep(0.02)
        assert seen_running, "no scrape saw the job running"
        status = service.wait_job(job["id"])
        after = scrape(service)
        units = sum(row["units"] for row in status["levels_table"])
        traced = sum(row["traced"] for row in status["levels_table"])
        stats = status["stats"]
        rays = sum(stats[k] for k in ("camera_rays", "shadow_rays", "reflection_rays",
                                      "refraction_rays"))
        print("units %d, pixel passes %d, rays %d" % (units, traced, rays))
        assert value(after, "tessera_jobs", state="done") == 1
        assert value(after, "tessera_jobs", state="running") == 0
        assert value(after, "tessera_units_finished_total") == units
        assert value(after, "tessera_units_dispatched_total") >= units
        assert value(after, "tessera_unit_latency_seconds_count") == units
        assert value(after, "tessera_unit_render_seconds_count") == units
        assert value(after, "tessera_unit_latency_seconds_bucket", le="+Inf") == units
        assert value(after, "tessera_pixels_total") == traced
        assert value(after, "tessera_rays_total") == rays
        assert value(after, "tessera_http_requests_total", route="/api/jobs", status="201") == 1
        assert value(after, "tessera_http_requests_total", route="/api/jobs/{id}",
                     status="200") >= 2
        assert value(after, "tessera_http_requests_total", route="/metrics", status="200") >= 2
        assert value(after, "tessera_http_received_bytes_total") > 0
        # The worker port: a unit frame for every unit sent, a result frame for every unit
        # merged, each with its pixels' 12 bytes, and the scene's bundle sent once.
        frames = lambda direction, kind: value(  # noqa: E731
            after, "tessera_worker_port_frames_total", direction=direction, type=kind)
        assert frames("sent", "unit") == value(after, "tessera_units_dispatched_total")
        assert frames("received", "result") >= units
        assert frames("sent", "job") == 1
        received = value(after, "tessera_worker_port_received_bytes_total")
        sent = value(after, "tessera_worker_port_sent_bytes_total")
        assert received > 12 * traced, (received, traced)
        assert sent > len(scene) + 50 * frames("sent", "unit"), sent
        print("worker port: %d bytes received, %d sent" % (received, sent))
        # The finished job's images are in the store now, on top of what it held before.
        images = sum(len(service.request("GET", "/api/jobs/%d/image?format=%s" %
                                         (job["id"], fmt))[2]) for fmt in ("png", "exr"))
        store_after = check_store(service, scrape(service))
        assert store_after >= store_before + images, (store_before, images, store_after)
        print("store: %d bytes before the job, %d after (images %d)" %
              (store_before, store_after, images))
        status_code, _, _ = service.request("GET", "/api/jobs/999")
        assert status_code == 404
        assert value(scrape(service), "tessera_http_requests_total", route="/api/jobs/{id}",
                     status="404") == 1
    print("metrics passed")


if __name__ == "__main__":
    sys.exit(main())

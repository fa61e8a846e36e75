#!/usr/bin/env python3
"""Workers behind real round trips (issue 8, item 4), for docs/PERFORMANCE.md, side by side in
one run: the demo scene through two one-thread workers on loopback, and with the workers in
their own network namespaces 0, 20 and 50 ms (round trip) from the coordinator
(tests/multihost/netns.py; tc netem, or delay_proxy.py where the kernel has no netem), and
20 ms away with TLS on both ports (issue 17 §6: a self-signed certificate the workers verify).
Runs are interleaved; medians. Then the transfer of a mesh bundle of --mesh-mb (10) MB over a link of
--rate-mbit. Exits 77 (ctest: skipped) where network namespaces cannot be made.

Needs root (network namespaces).

usage: bench/multihost_bench.py --build BUILD_DIR [--source .] [--repeats 3]
       [--width 640] [--height 480] [--aa 5] [--rate-mbit 100] [--mesh-mb 10]
"""
import argparse
import io
import json
import math
import os
import statistics
import sys
import tarfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "service"))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "multihost"))
import netns  # noqa: E402
import service_bench  # noqa: E402  (submit_and_time)
import service_test  # noqa: E402  (Service)
import tls_test  # noqa: E402  (TlsService, make_certificate)

RTTS_MS = (0, 20, 50)
TLS_RTT_MS = 20


def sphere_obj(target_bytes):
    """A UV sphere as OBJ text of about `target_bytes`."""
    rings = int(math.sqrt(target_bytes / 100))
    lines = []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(2 * rings):
            phi = math.pi * j / rings
            lines.append("v %.6f %.6f %.6f" % (math.sin(theta) * math.cos(phi),
                                               math.sin(theta) * math.sin(phi), math.cos(theta)))
    for i in range(rings):
        for j in range(2 * rings):
            a, b = i * 2 * rings + j + 1, i * 2 * rings + (j + 1) % (2 * rings) + 1
            lines.append("f %d %d %d" % (a, b, b + 2 * rings))
            lines.append("f %d %d %d" % (a, b + 2 * rings, a + 2 * rings))
    return "\n".join(lines) + "\n"


def mesh_bundle(mesh_bytes):
    scene = ("eyePoint 0 -4 1 viewPoint 0 0 0 light 3 -3 5 1 1 1\n"
             "diffuse 0.8 0.6 0.4 mesh meshes/big.obj 1\n")
    mesh = sphere_obj(mesh_bytes).encode()
    buf = io.BytesIO()
    with tarfile.open(fileobj=buf, mode="w", format=tarfile.USTAR_FORMAT) as tar:
        for name, data in (("big.sdl", scene.encode()), ("meshes/big.obj", mesh)):
            info = tarfile.TarInfo(name)
            info.size = len(data)
            tar.addfile(info, io.BytesIO(data))
    return buf.getvalue(), len(mesh)


def first_level_of_bundle(service, bundle):
    """Seconds from submitting the tar bundle to its first level being complete."""
    start = time.perf_counter()
    status, _, body = service.request("POST", "/api/jobs?main=big.sdl&width=64&height=48",
                                      bundle, {"Content-Type": "application/x-tar"})
    assert status == 201, (status, body)
    job_id = json.loads(body)["id"]
    while True:
        job = service.get("/api/jobs/%d" % job_id)
        if job["levels_table"] and job["levels_table"][0]["complete"]:
            seconds = time.perf_counter() - start
            service.wait_job(job_id)
            return seconds
        assert job["state"] in ("queued", "running"), job
        time.sleep(0.002)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", default=".")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=480)
    parser.add_argument("--aa", type=int, default=5)
    parser.add_argument("--rate-mbit", type=float, default=100)
    parser.add_argument("--mesh-mb", type=float, default=10)
    args = parser.parse_args()
    service_test.ARGS = args
    why = netns.unavailable()
    if why:
        print("SKIPPED: multihost_bench: " + why)
        sys.exit(netns.SKIP)
    scene = open(os.path.join(args.source, "scenes", "demo.sdl")).read()
    settings = {"width": args.width, "height": args.height, "aa": args.aa}

    with netns.Network() as network, service_test.Service() as loopback:
        services = {"loopback": loopback}
        loopback.worker("w1")
        loopback.worker("w2")
        where = {"prefix": network.coordinator_prefix(), "host": network.api_host}
        for rtt in RTTS_MS:
            # Each Service is its own coordinator in the namespace, reached at its own port.
            # The API is reached from the root namespace, not loopback: open it as the
            # multihost tests do.
            service = service_test.Service("--open-submit", **where)
            services["%d ms" % rtt] = service
            network.add_worker(service, "w1", rtt_ms=rtt)
            network.add_worker(service, "w2", rtt_ms=rtt)
        # The certificate names every address a client or worker may use to reach it: the
        # API's, each worker link's coordinator end, and loopback (behind delay_proxy.py).
        cert, key = tls_test.make_certificate(
            loopback.tmp.name, "bench", "IP:127.0.0.1,IP:%s,%s" % (
                network.api_host, ",".join("IP:10.213.%d.1" % i for i in range(1, 16))))
        service = tls_test.TlsService(cert, key, "--open-submit", **where)
        services["%d ms TLS" % TLS_RTT_MS] = service
        for name in ("w1", "w2"):
            network.add_worker(service, name, rtt_ms=TLS_RTT_MS, worker_args=("--tls-ca", cert))
        try:
            for service in services.values():
                service.wait_workers(2)
            times = {name: ([], []) for name in services}
            for _ in range(args.repeats):
                for name, service in services.items():
                    first, total = service_bench.submit_and_time(service, scene, settings)
                    times[name][0].append(first)
                    times[name][1].append(total)

            print("demo.sdl %dx%d aa %d, 2 workers x 1 thread, median of %d interleaved runs; "
                  "latency by %s" % (args.width, args.height, args.aa, args.repeats,
                                     netns.latency_method()))
            print("%-10s %16s %12s %22s" % ("round trip", "first level ms", "total s",
                                            "throughput / loopback"))
            base = statistics.median(times["loopback"][1])
            for name, (first, total) in times.items():
                print("%-10s %16.1f %12.3f %22.3f" % (name, statistics.median(first) * 1e3,
                                                      statistics.median(total),
                                                      base / statistics.median(total)))
        finally:
            for name, service in services.items():
                if name != "loopback":
                    service.__exit__(None, None, None)

        bundle, mesh_bytes = mesh_bundle(int(args.mesh_mb * 1e6))
        with service_test.Service("--open-submit", prefix=network.coordinator_prefix(),
                                  host=network.api_host) as service:
            network.add_worker(service, "w", rtt_ms=20, rate_mbit=args.rate_mbit)
            service.wait_workers(1)
            sent = first_level_of_bundle(service, bundle)
            cached = first_level_of_bundle(service, bundle)
        print("%.1f MB mesh bundle, 20 ms round trip at %g Mbit/s: first level %.2f s when "
              "sent, %.2f s when cached: transfer %.2f s (%.0f Mbit/s)" %
              (mesh_bytes / 1e6, args.rate_mbit, sent, cached, sent - cached,
               len(bundle) * 8 / 1e6 / max(sent - cached, 1e-9)))


if __name__ == "__main__":
    main()

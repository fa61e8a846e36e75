#!/usr/bin/env python3
"""Seed inputs for the coordinator's fuzz targets, made from the sample scenes.

    tests/fuzz/service_seeds.py CORPUS   writes CORPUS/job_request/ and CORPUS/worker_frames/

The input layouts are those of tests/fuzz/service_fuzz_checks.h: a job request is one byte for
the content type (0 JSON, 1 multipart, 2 tar; a tar's query string and a newline come first)
and the body; a worker stream is one byte for the chunk size and then frames (docs/PROTOCOL.md).
"""
import io
import json
import struct
import sys
import tarfile
from pathlib import Path

SCENES = Path(__file__).resolve().parents[2] / "scenes"
BOUNDARY = "tesseraFuzzBoundary"
SMALL = {"width": 8, "height": 6, "passes": 2}


def job_requests():
    lighting = (SCENES / "features" / "lighting.sdl").read_text()
    yield "json_sdl", b"\x00" + json.dumps({"scene": lighting, "settings": SMALL}).encode()
    framed = (SCENES / "vrml" / "framed.wrl").read_text()
    yield "json_vrml", b"\x00" + json.dumps(
        {"format": "vrml", "files": {"w.wrl": framed}, "main": "w.wrl", "settings": SMALL}).encode()
    shadows = (SCENES / "features" / "shadows.sdl").read_text()
    form = "".join(f'--{BOUNDARY}\r\nContent-Disposition: form-data; name="{name}"\r\n\r\n{value}\r\n'
                   for name, value in [("scene", shadows), ("settings", json.dumps(SMALL))])
    yield "multipart", b"\x01" + (form + f"--{BOUNDARY}--\r\n").encode()
    # A bundle from scenes/features: a scene and the meshes it reads.
    features = SCENES / "features"
    bundle = io.BytesIO()
    with tarfile.open(fileobj=bundle, mode="w", format=tarfile.USTAR_FORMAT) as tar:
        for path in ["mesh_formats.sdl", "meshes/prism.3vn", "meshes/ball.3dv", "meshes/ring.3dm"]:
            tar.add(features / path, arcname=path)
    yield "tar", b"\x02main=mesh_formats.sdl&width=8&height=6&passes=2\n" + bundle.getvalue()


def frame(kind, header, payload=b""):
    head = json.dumps(header).encode()
    body = struct.pack(">BI", kind, len(head)) + head + payload
    return struct.pack(">I", len(body)) + body


RESULT, HEARTBEAT = 9, 6


def result(pixels=4, seconds=0.5, values=None):
    values = values if values is not None else [0.25] * (pixels * 3)
    stats = {"camera_rays": pixels, "shadow_rays": 2 * pixels, "pixels": pixels,
             "samples": pixels, "nan_samples": 0, "seconds": seconds}
    return frame(RESULT, {"job": 1, "unit": 0, "count": pixels, "stats": stats},
                 struct.pack(f"<{len(values)}f", *values))


def worker_streams():
    yield "results", b"\x07" + frame(HEARTBEAT, {}) + result() + result(seconds=1.25)
    yield "heartbeat", b"\xff" + frame(HEARTBEAT, {})


def main():
    corpus = Path(sys.argv[1])
    for target, inputs in [("job_request", job_requests()), ("worker_frames", worker_streams())]:
        (corpus / target).mkdir(parents=True, exist_ok=True)
        for name, data in inputs:
            (corpus / target / name).write_bytes(data)


if __name__ == "__main__":
    main()

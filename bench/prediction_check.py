#!/usr/bin/env python3
"""How good is the time predicted at submission (issue 5, item 3)? Renders every sample scene
through a coordinator with two one-thread workers and compares the job's predicted_seconds
with its elapsed_seconds, over two rounds: in the first the calibration starts from nothing
(the first job is predicted from the probe alone), the second shows the learnt predictions.
Target: within +-25 %.

usage: bench/prediction_check.py --build BUILD_DIR [--source .] [--width 640] [--height 480]
       [--aa 5]
"""
import argparse
import glob
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "service"))
import service_test  # noqa: E402  (Service: the real processes on loopback)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", default=".")
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=480)
    parser.add_argument("--aa", type=int, default=5)
    args = parser.parse_args()
    service_test.ARGS = args
    scenes = sorted(glob.glob(os.path.join(args.source, "scenes", "**", "*.sdl"), recursive=True))
    scenes = [s for s in scenes if "/parts/" not in s]
    settings = {"width": args.width, "height": args.height, "aa": args.aa}
    print("%dx%d aa %d, 2 workers x 1 thread" % (args.width, args.height, args.aa))
    print("%-6s %-28s %11s %9s %8s" % ("round", "scene", "predicted s", "actual s", "error"))
    worst = {1: 0.0, 2: 0.0}
    with service_test.Service("--scenes-dir", os.path.join(args.source, "scenes")) as service:
        service.worker("w1")
        service.worker("w2")
        service.wait_workers(2)
        for round_, path in [(r, p) for r in (1, 2) for p in scenes]:
            name = os.path.relpath(path, os.path.join(args.source, "scenes"))
            body = {"scene_file": name, "settings": settings}
            status, _, reply = service.request(
                "POST", "/api/jobs", service_test.json.dumps(body).encode(),
                {"Content-Type": "application/json"})
            assert status == 201, reply
            job = service.wait_job(service_test.json.loads(reply)["id"])
            assert job["state"] == "done", job
            predicted, actual = job["predicted_seconds"], job["elapsed_seconds"]
            error = (predicted - actual) / actual
            worst[round_] = max(worst[round_], abs(error))
            print("%-6d %-28s %11.3f %9.3f %+7.0f%%" % (round_, name, predicted, actual,
                                                        100 * error))
    print("largest error: round 1 %.0f %%, round 2 %.0f %%" % (100 * worst[1], 100 * worst[2]))


if __name__ == "__main__":
    main()

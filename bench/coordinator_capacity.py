#!/usr/bin/env python3
"""Coordinator capacity (issue 4 §8, issue 22 §3), for docs/SCALING.md and docs/PERFORMANCE.md.

Many workers connect to one coordinator: synthetic ones (the default) that speak the real
protocol (docs/PROTOCOL.md) but answer every unit at once with black pixels, so that the
coordinator's scheduling, merging and I/O are the only work; or, with --real N, N real
tessera-worker processes of one thread. In phases, it measures

- memory: the coordinator's resident set before and with every worker connected, per worker;
- idle: the heartbeat traffic per worker (synthetic workers count the bytes) and the
  coordinator's CPU while nothing runs;
- throughput: one job (a sphere or --scene, --size square, --aa, --passes; the coordinator
  sizes units to 20 ms of predicted work, so a costlier job has smaller units): units and
  pixel passes merged per second of wall time and per coordinator CPU-second (CPU per unit,
  per pixel pass); with --ns-per-pixel the synthetic workers' threads take that long a pixel,
  so the job's wall time shows how well its units keep the threads busy (pass barriers);
- loss: during a second job one worker crashes (its connection closes with units in flight)
  and another hangs (it stops answering, its connection stays open): the time until the
  first's units are re-queued, and until the second is dropped (--silence-ms after its last
  message) and its units re-queued.

With --jobs N the throughput job runs N times, one after the other, each reported, then the io
thread's CPU a pixel pass for the first job, the second, and the third and later (their
median): the steady state. The first job's frame buffer is memory the kernel makes as it is
first written. The second starts as soon as the first is done, while the first's buffer is
still shared with its final image's encoding: it takes new memory too, unless that encoding
ended before its first merge (a race: new memory costs it 0.1-0.2 s of the io thread, in
thousands of page faults, or tens where the kernel gives huge pages). From the third on
a job takes the buffer of the job two before it, back in the pool (mapping_pool.h).

usage: coordinator_capacity.py --build BUILD_DIR [--workers 32] [--threads 4] [--size 2048]
       [--passes 4] [--jobs 1] [--scene SDL] [--aa 1] [--settings JSON] [--real N]
       [--ns-per-pixel 0] [--heartbeat-ms 2000] [--silence-ms 10000] [--idle-seconds 6]
       [--coordinator-cpu N] [--smoke]
--smoke: seconds, tiny sizes, short heartbeats; exits 1 when a phase fails (the test command
runs it, so a protocol change that breaks this script fails CI).

--coordinator-cpu N: the coordinator (all its threads) runs on CPU N only and this script (all
the synthetic workers) on the other CPUs, as issue 22 §3 means "one coordinator core": on a
machine of two cores the script, sharing the coordinator's core unpinned, otherwise takes
turns with its io thread. Off by default.

The wall-clock rates are lower bounds: this script shares the machine with the coordinator
(and, with --real, with the workers). The coordinator's own CPU time is measured from /proc;
units per coordinator CPU-second is its capacity on a machine of its own.
"""
import argparse
import asyncio
import datetime
import hashlib
import hmac
import json
import os
import re
import resource
import secrets
import signal
import statistics
import struct
import subprocess
import sys
import tempfile
import time
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "service"))
import service_test  # noqa: E402  (start_coordinator)

SECRET = "capacity-secret"
HELLO, CHALLENGE, AUTH, WELCOME, REJECT, HEARTBEAT, JOB, UNIT, RESULT = range(1, 10)
# Read from the source, so that a new protocol version cannot leave this script behind.
with open(os.path.join(HERE, "..", "common", "protocol", "handshake.h")) as _f:
    PROTOCOL_VERSION = int(re.search(r"kProtocolVersion = (\d+);", _f.read()).group(1))
# The coordinator closes connections beyond 8 unauthenticated ones from one address
# (`WorkerPortLimits::max_unauthenticated_per_address`, docs/SECURITY.md); all of these come
# from 127.0.0.1.
HANDSHAKES_AT_ONCE = 8


def frame_head(kind, header, payload_bytes):
    """A frame's bytes before its payload: the length prefix, the type and the header."""
    head = json.dumps(header).encode()
    return struct.pack(">IBI", 5 + len(head) + payload_bytes, kind, len(head)) + head


def frame(kind, header):
    """A frame without a payload (every frame this script sends but results)."""
    return frame_head(kind, header, 0)


# Every result's black pixels, sliced from one buffer of the largest unit's (kMostUnitPixels,
# 65,536 pixels): building each result's 600 kB of zeros afresh, then copying them twice into
# its frame, took this one Python process 760 us a result (20 us now), three times the
# coordinator's io thread a unit, which then waited for data hundreds of times a job
# (docs/SCALING.md, io10).
BLACK_PIXELS = memoryview(bytes(12 * 65536))


def pixel_count(p):
    """common/progressive/unit_pixels.cpp's count, for the result's payload size: the step's
    grid in the rectangle, less the anchors of the coarser level (`exclude` in both coordinates)
    unless the pattern is "centres". Counted by rows and columns, not pixel by pixel: this one
    Python process answers every unit of every synthetic worker, and a loop over a unit's
    pixels (16,132 then) made it, not the coordinator, what set the pace."""
    x0, y0, x1, y1 = p["rect"]
    step, exclude = p["step"], p["exclude"]
    first = lambda v: (v + step - 1) // step * step
    columns, rows = range(first(x0), x1, step), range(first(y0), y1, step)
    if p["pattern"] == "centres" or exclude <= 0:
        return len(columns) * len(rows)
    anchors = lambda grid: sum(1 for v in grid if v % exclude == 0)
    return len(columns) * len(rows) - anchors(columns) * anchors(rows)


class FaultPlan:
    """Faults dealt in order ("crash", then "hang") to the first synthetic workers that get a
    unit of a job after job `after`, whichever workers the scheduler picks: both strike within
    one job, since a crashed worker's units go to another worker. (Arming two chosen workers
    was left to chance: a job of 7 units may go to others, and in CI 20 jobs in a row did.)"""

    def __init__(self):
        self.after, self.faults, self.victims = None, [], {}

    def arm(self, after, faults):
        self.after, self.faults = after, list(faults)

    def deal(self, worker, job):
        """The fault `worker` takes on a unit of `job`, or None."""
        if self.after is None or job <= self.after or not self.faults:
            return None
        fault = self.faults.pop(0)
        self.victims[fault] = worker
        return fault


class Synthetic:
    """One synthetic worker. A fault dealt by `plan` ("crash" or "hang") strikes at once;
    `fault_at` is then the time of its last message. With `ns_per_pixel` each of its `threads`
    takes that long a pixel over a unit (a sleep) before answering, so that the scheduler's
    pass barriers and pipelines, not the coordinator's CPU, set the pace."""

    def __init__(self, index, threads, plan, ns_per_pixel=0):
        self.name = "synthetic-%d" % index
        self.threads = threads
        self.plan = plan
        self.ns_per_pixel = ns_per_pixel
        self.idle_threads = None  # a semaphore of `threads`, made in the event loop
        self.received = self.sent = 0
        self.fault = self.fault_at = self.last_sent = self.writer = None
        self.error = None

    def send(self, writer, data):
        writer.write(data)
        self.sent += len(data)
        self.last_sent = time.time()

    async def read_frame(self, reader):
        (size,) = struct.unpack(">I", await reader.readexactly(4))
        body = await reader.readexactly(size)
        self.received += 4 + size
        kind, head_len = struct.unpack(">BI", body[:5])
        return kind, json.loads(body[5:5 + head_len])

    async def run(self, port, handshakes):
        try:
            async with handshakes:
                reader, writer = await asyncio.open_connection("127.0.0.1", port)
                nonce = secrets.token_hex(32)
                self.send(writer, frame(HELLO, {"version": PROTOCOL_VERSION, "name": self.name,
                                                "threads": self.threads, "nonce": nonce,
                                                "cached": []}))
                kind, challenge = await self.read_frame(reader)
                if kind != CHALLENGE:
                    raise RuntimeError("refused: %s" % challenge)
                message = "tessera-worker|%d|%s|%s" % (PROTOCOL_VERSION, challenge["nonce"],
                                                       nonce)
                proof = hmac.new(SECRET.encode(), message.encode(), hashlib.sha256).hexdigest()
                self.send(writer, frame(AUTH, {"proof": proof}))
                kind, header = await self.read_frame(reader)
                if kind != WELCOME:
                    raise RuntimeError("refused: %s" % header)
            self.writer = writer
            await self.serve(reader, writer)
        except asyncio.CancelledError:
            raise
        except Exception as e:  # a dropped synthetic worker must not go unnoticed
            self.error = repr(e)

    async def serve(self, reader, writer):
        while True:
            kind, header = await self.read_frame(reader)
            if kind == UNIT and not self.fault:
                self.fault = self.plan.deal(self, header["job"])
            if kind == UNIT and self.fault:
                self.fault_at = time.time()
                if self.fault == "crash":
                    writer.close()
                    return
                await asyncio.Event().wait()  # hang: read nothing, answer nothing
            if kind == UNIT and self.ns_per_pixel:
                asyncio.get_running_loop().create_task(self.render(writer, header))
            elif kind == UNIT:
                self.answer(writer, header, 0)
            elif kind == HEARTBEAT:
                self.send(writer, frame(HEARTBEAT, {}))

    def answer(self, writer, header, seconds):
        count = pixel_count(header["pixels"])
        # The coordinator checks the statistics against the unit (result_check.h).
        stats = {"seconds": seconds, "pixels": count, "samples": count, "camera_rays": count}
        pixels = BLACK_PIXELS[:12 * count]
        assert len(pixels) == 12 * count, "a unit of more than 65,536 pixels"
        head = frame_head(RESULT, {"job": header["job"], "unit": header["unit"], "count": count,
                                   "stats": stats}, len(pixels))
        self.send(writer, b"".join((head, pixels)))  # one write, as a real worker's

    async def render(self, writer, header):
        """--ns-per-pixel: the unit waits for one of the worker's threads, as a real worker's
        queue does, and holds it for its pixels' time."""
        if self.idle_threads is None:
            self.idle_threads = asyncio.Semaphore(self.threads)
        async with self.idle_threads:
            seconds = pixel_count(header["pixels"]) * self.ns_per_pixel * 1e-9
            await asyncio.sleep(seconds)
            if not self.fault and not writer.is_closing():
                self.answer(writer, header, seconds)


def stat_fields(stat_path):
    with open(stat_path) as f:
        return f.read().rsplit(")", 1)[1].split()


def cpu_seconds_of(stat_path):
    fields = stat_fields(stat_path)
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def page_faults(pid):
    """Minor page faults so far of a process's main thread (its io thread): each is memory the
    kernel makes (and zeroes) while the io thread waits."""
    return int(stat_fields("/proc/%d/task/%d/stat" % (pid, pid))[7])


def io_switches(pid):
    """Times so far the io thread left the processor: to wait (epoll found nothing to read) and
    preempted (another thread or process took its turn). Either lets others take its core and
    its caches, which it finds cold when it comes back (docs/SCALING.md)."""
    with open("/proc/%d/task/%d/status" % (pid, pid)) as f:
        status = f.read()
    return tuple(int(re.search(r"^%s:\s+(\d+)$" % key, status, re.M).group(1))
                 for key in ("voluntary_ctxt_switches", "nonvoluntary_ctxt_switches"))


def cpu_seconds(pid):
    """User plus system CPU time of a process so far (Linux /proc)."""
    return cpu_seconds_of("/proc/%d/stat" % pid)


# Kernels built without CONFIG_SCHED_INFO have no schedstat files.
HAVE_SCHEDSTAT = os.path.exists("/proc/self/schedstat")


def thread_cpu_seconds(pid):
    """CPU time so far of each of a process's threads, by thread id and name: the io thread is
    the main one (the process's id), the store's and the intake pool's are named. From the
    scheduler's nanoseconds (schedstat), not /proc's stat in ticks of 10 ms: a job's io thread
    takes 0.1-0.3 s, so a tick was 3-10 % of it (stat where there is no schedstat)."""
    seconds = {}
    for tid in os.listdir("/proc/%d/task" % pid):
        try:
            with open("/proc/%d/task/%s/comm" % (pid, tid)) as f:
                name = "io" if int(tid) == pid else f.read().strip().replace("tessera-", "")
            task = "/proc/%d/task/%s/" % (pid, tid)
            if HAVE_SCHEDSTAT:
                with open(task + "schedstat") as f:
                    seconds[(tid, name)] = int(f.read().split()[0]) / 1e9
            else:
                seconds[(tid, name)] = cpu_seconds_of(task + "stat")
        except FileNotFoundError:  # the thread ended
            pass
    return seconds


def rss_bytes(pid):
    with open("/proc/%d/status" % pid) as f:
        return int(re.search(r"VmRSS:\s+(\d+) kB", f.read()).group(1)) * 1024


def pinned_to(cpu):
    """A command prefix that runs a program on `cpu` only: the process is pinned before it
    execs, so every thread the program starts inherits the mask (the same pid)."""
    return (sys.executable, "-c", "import os, sys; os.sched_setaffinity(0, {%d}); "
            "os.execv(sys.argv[1], sys.argv[1:])" % cpu)


class Coordinator:
    def __init__(self, build, tmp, heartbeat_ms, silence_ms, cpu=None):
        self.log_path = os.path.join(tmp, "coordinator.log")
        with open(self.log_path, "w") as log:
            self.proc, self.http_port, self.worker_port = service_test.start_coordinator(
                build, ["--secret", SECRET, "--heartbeat-ms", str(heartbeat_ms), "--silence-ms",
                        str(silence_ms)], log, os.path.join(tmp, "ports.json"),
                prefix=() if cpu is None else pinned_to(cpu))

    def log(self):
        with open(self.log_path) as f:
            return f.read()

    def left_at(self, name):
        """The wall-clock time of the log line saying worker `name` left (its units are
        re-queued in the same step), or None. The coordinator's own clock: the script's event
        loop, busy with a thousand connections, would add its own delays to a poll."""
        line = re.search(r'^\[([0-9-]+ [0-9:.]+)\] \[info\] worker \d+ "%s" left' % name,
                         self.log(), re.M)
        return line and datetime.datetime.strptime(line.group(1), "%Y-%m-%d %H:%M:%S.%f"
                                                   ).timestamp()

    async def get(self, path, raw=False):
        def fetch():
            with urllib.request.urlopen("http://127.0.0.1:%d%s" % (self.http_port, path)) as r:
                return r.read()
        body = await asyncio.to_thread(fetch)
        return body.decode() if raw else json.loads(body)

    async def metric(self, name):
        text = await self.get("/metrics", raw=True)
        return float(re.search(r"^%s (\S+)$" % name, text, re.M).group(1))

    async def submit(self, size, passes, scene="sphere\n", aa=1, settings=None):
        body = json.dumps({"scene": scene, "settings": {
            "width": size, "height": size, "passes": passes, "aa": aa,
            **(settings or {})}}).encode()
        request = urllib.request.Request("http://127.0.0.1:%d/api/jobs" % self.http_port, body,
                                         {"Content-Type": "application/json"})
        return json.load(await asyncio.to_thread(urllib.request.urlopen, request))["id"]

    async def wait_job(self, job_id, check_workers):
        while True:
            check_workers()
            status = await self.get("/api/jobs/%d" % job_id)
            if status["state"] not in ("queued", "running"):
                return status
            await asyncio.sleep(0.02)

    async def workers(self):
        return {w["name"] for w in await self.get("/api/workers")}

    async def wait_until(self, what, condition, timeout):
        deadline = time.perf_counter() + timeout
        while not await condition():
            if time.perf_counter() > deadline:
                raise AssertionError("timed out waiting for " + what)
            await asyncio.sleep(0.005)
        return time.perf_counter()


class RealWorkers:
    """--real N: tessera-worker processes of one thread."""

    def __init__(self, build, count, port):
        self.procs = [subprocess.Popen(
            [os.path.join(build, "worker", "tessera-worker"), "--coordinator",
             "127.0.0.1:%d" % port, "--threads", "1", "--name", "real-%d" % i],
            env=dict(os.environ, TESSERA_SECRET=SECRET), stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL) for i in range(count)]
        self.names = ["real-%d" % i for i in range(count)]

    def stop(self):
        for p in self.procs:
            if p.poll() is None:
                p.send_signal(signal.SIGCONT)
                p.kill()
            p.wait()


async def keep_alive(workers, seconds):
    """Each synthetic worker sends a heartbeat after `seconds` of sending nothing, as real
    workers do (the coordinator's --heartbeat-ms, from the welcome): a worker that only received (a job's bundle, units it holds) would
    otherwise be dropped as silent."""
    while True:
        await asyncio.sleep(seconds / 4)
        now = time.time()
        for w in workers:
            if w.writer and not w.fault and w.last_sent and now - w.last_sent > seconds:
                w.send(w.writer, frame(HEARTBEAT, {}))


async def throughput(args, coordinator, check_workers, report, label):
    """One job of the throughput phase: reports its rates and the coordinator's CPU, returns
    its id and the io thread's CPU seconds."""
    pid = coordinator.proc.pid
    units0 = await coordinator.metric("tessera_units_finished_total")
    pixels0 = await coordinator.metric("tessera_pixels_total")
    # Submission probes the scene's cost on the coordinator (docs/SERVICE.md): counted from
    # its answer on, so that only the job's scheduling and merging are measured.
    job = await coordinator.submit(args.size, args.passes, args.scene_text, args.aa,
                                   args.settings)
    start = time.perf_counter()
    cpu, threads_before, faults = cpu_seconds(pid), thread_cpu_seconds(pid), page_faults(pid)
    switches = io_switches(pid)
    status = await coordinator.wait_job(job, check_workers)
    elapsed = time.perf_counter() - start
    cpu = cpu_seconds(pid) - cpu
    faults = page_faults(pid) - faults
    switches = [after - before for after, before in zip(io_switches(pid), switches)]
    by_thread = sorted(((seconds - threads_before.get(thread, 0), thread[1])
                        for thread, seconds in thread_cpu_seconds(pid).items()), reverse=True)
    if status["state"] != "done":
        raise AssertionError("the job ended %s" % status)
    units = await coordinator.metric("tessera_units_finished_total") - units0
    pixels = await coordinator.metric("tessera_pixels_total") - pixels0
    report(label, "%s %dx%d aa %d, %d passes: %d units of %.0f pixels, %.2f M pixel "
           "passes in %.2f s: %.0f units/s, %.1f M pixel passes/s (wall, machine shared)" %
           (args.scene or "sphere", args.size, args.size, args.aa, args.passes, units,
            pixels / units, pixels / 1e6, elapsed, units / elapsed, pixels / elapsed / 1e6))
    if HAVE_SCHEDSTAT:  # in ns, where /proc's stat counts 10 ms ticks (a smoke job is 0 ticks)
        cpu = sum(t for t, name in by_thread)
    cpu = max(cpu, 1e-9)
    report("coordinator CPU", "%.2f s: %.0f units and %.1f M pixel passes per CPU-second; "
           "%.0f us a unit, %.1f ns a pixel pass; its busiest threads %s; %d page faults on "
           "the io thread, which waited for data %d times and was preempted %d times" %
           (cpu, units / cpu, pixels / cpu / 1e6, cpu / units * 1e6, cpu / pixels * 1e9,
            ", ".join("%s %.3f s" % (name, t) for t, name in by_thread[:3]), faults, *switches))
    io = sum(t for t, name in by_thread if name == "io")
    return job, io / pixels


async def measure(args, coordinator, report):
    pid = coordinator.proc.pid
    rss_before = rss_bytes(pid)
    synthetic, tasks, real = [], [], None
    if args.real:
        real = RealWorkers(args.build, args.real, coordinator.worker_port)
        names, threads = real.names, 1
    else:
        handshakes = asyncio.Semaphore(HANDSHAKES_AT_ONCE)
        plan = FaultPlan()
        synthetic = [Synthetic(i, args.threads, plan, args.ns_per_pixel)
                     for i in range(args.workers)]
        tasks = [asyncio.create_task(w.run(coordinator.worker_port, handshakes))
                 for w in synthetic]
        heartbeat = min(2.0, args.heartbeat_ms / 1e3)
        tasks.append(asyncio.create_task(keep_alive(synthetic, heartbeat)))
        names, threads = [w.name for w in synthetic], args.threads
    try:
        start = time.perf_counter()

        def check_workers():
            failed = [w.error for w in synthetic if w.error and not w.fault]
            if failed:
                raise AssertionError("%d synthetic workers failed: %s" % (len(failed),
                                                                          failed[:3]))

        async def all_joined():
            check_workers()
            return len(await coordinator.workers()) == len(names)
        # A real worker process takes seconds of CPU to start (its libraries) on a busy machine.
        await coordinator.wait_until("%d workers to join" % len(names), all_joined,
                                     120 + 3 * args.real)
        joined = time.perf_counter() - start
        await asyncio.sleep(0.5)  # let the last handshakes' buffers settle
        rss_with = rss_bytes(pid)
        report("workers", "%d %s workers x %d threads joined in %.2f s" %
               (len(names), "real" if real else "synthetic", threads, joined))
        report("memory", "coordinator RSS %.1f MB idle, %.1f MB with the workers: %.1f kB "
               "per connected worker" % (rss_before / 1e6, rss_with / 1e6,
                                         (rss_with - rss_before) / len(names) / 1e3))

        # Idle: heartbeats only.
        received = sum(w.received for w in synthetic)
        sent = sum(w.sent for w in synthetic)
        cpu = cpu_seconds(pid)
        await asyncio.sleep(args.idle_seconds)
        idle_cpu = (cpu_seconds(pid) - cpu) / args.idle_seconds
        line = "coordinator CPU %.1f %% of a core" % (100 * idle_cpu)
        if synthetic:
            rate = lambda total: total / args.idle_seconds / len(names)
            line = ("heartbeats every %d ms: %.1f B/s to and %.1f B/s from each worker; %s" %
                    (args.heartbeat_ms, rate(sum(w.received for w in synthetic) - received),
                     rate(sum(w.sent for w in synthetic) - sent), line))
        report("idle", line)

        # Throughput: --jobs jobs one after the other. The first job's frame buffer is new
        # memory; later ones may take a finished job's back (common/render/mapping_pool.h).
        io_per_pixel = []
        for index in range(args.jobs):
            job, io = await throughput(args, coordinator, check_workers, report,
                                       "throughput" if args.jobs == 1 else
                                       "job %d" % (index + 1))
            io_per_pixel.append(io * 1e9)
        if args.jobs > 1:
            line = "first job %.1f ns a pixel pass; job 2 %.1f ns" % tuple(io_per_pixel[:2])
            steady = io_per_pixel[2:]
            if steady:
                line += "; jobs 3-%d %.1f-%.1f ns (median %.2f)" % (
                    args.jobs, min(steady), max(steady), statistics.median(steady))
            report("io thread", line)

        # Loss: one worker crashes and one hangs while a job runs.
        requeued0 = await coordinator.metric("tessera_units_requeued_total")
        if synthetic:
            # Armed before the job exists: its first units may reach a worker while the
            # submission's answer is still on its way here.
            plan.arm(job, ("crash", "hang"))
            job = await coordinator.submit(args.size, args.passes)
            async def struck():
                return len(plan.victims) == 2 and all(w.fault_at for w in plan.victims.values())
            await coordinator.wait_until("the faults", struck, 60)
            crash, hang = plan.victims["crash"].name, plan.victims["hang"].name
            crash_at, hang_at = plan.victims["crash"].fault_at, plan.victims["hang"].last_sent
        else:
            crash, hang = names[0], names[1]
            # Real workers take time: a job long enough that both victims hold units.
            with open(os.path.join(HERE, "..", "scenes", "demo.sdl")) as f:
                job = await coordinator.submit(256, 16, f.read(), aa=9)
            await coordinator.wait_until("the job to start",
                                         lambda: _progressed(coordinator, job), 60)
            crash_at = time.time()
            real.procs[0].kill()
            hang_at = time.time()
            real.procs[1].send_signal(signal.SIGSTOP)

        async def left(name):
            return coordinator.left_at(name) is not None
        await coordinator.wait_until("the crashed worker to be dropped",
                                     lambda: left(crash), 30)
        await coordinator.wait_until("the hung worker to be dropped", lambda: left(hang),
                                     args.silence_ms / 1000 + 30)
        crash_seen, hang_seen = coordinator.left_at(crash), coordinator.left_at(hang)
        requeued = await coordinator.metric("tessera_units_requeued_total") - requeued0
        report("loss", "(the coordinator's log, to the ms) a crashed worker dropped, its units "
               "re-queued, %.0f ms after its connection closed; a hung one %.2f s after %s "
               "(--silence-ms %d); %d units re-queued (a unit another worker holds too is not "
               "counted)" %
               (max(0, crash_seen - crash_at) * 1e3, hang_seen - hang_at,
                "it was stopped" if real else "its last message", args.silence_ms, requeued))
    finally:
        for t in tasks:
            t.cancel()
        if real:
            real.stop()


async def _progressed(coordinator, job):
    return (await coordinator.get("/api/jobs/%d" % job))["progress"] > 0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--workers", type=int, default=32)
    parser.add_argument("--threads", type=int, default=4)
    parser.add_argument("--size", type=int, default=2048)
    parser.add_argument("--passes", type=int, default=4)
    parser.add_argument("--scene", help="an SDL file for the throughput job (default: one "
                        "sphere); a costlier scene or --aa 9 gives smaller units")
    parser.add_argument("--jobs", type=int, default=1,
                        help="throughput jobs, one after the other (the first job's frame "
                        "buffer is new memory, later ones' may be a finished job's)")
    parser.add_argument("--aa", type=int, default=1)
    parser.add_argument("--settings", type=json.loads, default={},
                        help="more settings of the throughput job, a JSON object, e.g. "
                        "'{\"shadows\": \"soft\", \"cone_samples\": 64}' for costlier pixels, "
                        "so that the coordinator cuts smaller units")
    parser.add_argument("--ns-per-pixel", type=float, default=0,
                        help="synthetic workers' threads take this long a pixel over a unit "
                        "(the job's wall time then shows how well units keep them busy)")
    parser.add_argument("--real", type=int, default=0)
    parser.add_argument("--heartbeat-ms", type=int, default=2000)
    parser.add_argument("--silence-ms", type=int, default=10000)
    parser.add_argument("--idle-seconds", type=float, default=6)
    parser.add_argument("--coordinator-cpu", type=int,
                        help="run the coordinator on this CPU only and this script on the others")
    parser.add_argument("--smoke", action="store_true")
    args = parser.parse_args()
    args.scene_text = open(args.scene).read() if args.scene else "sphere\n"
    if args.smoke:
        args.workers, args.size, args.passes = min(args.workers, 8), 64, 2
        args.jobs = 2  # the loop runs in CI too
        args.real = min(args.real, 3)
        # Real workers adopt --heartbeat-ms and --silence-ms from the welcome; 3 s leaves their
        # slow start on a loaded machine some room, and 2 s the synthetic workers' event loop
        # (at 0.5 s a busy CI machine had the coordinator drop one that was merely late).
        args.heartbeat_ms, args.idle_seconds = 100, 0.5
        args.silence_ms = 3000 if args.real else 2000
    if max(args.workers if not args.real else 0, args.real) < 2:
        parser.error("needs at least 2 workers (one crashes, one hangs)")
    # Each connection is a descriptor on both sides; the coordinator inherits this limit.
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    resource.setrlimit(resource.RLIMIT_NOFILE, (hard, hard))
    if hard < 2 * (args.workers + args.real) + 100:
        parser.error("the descriptor limit %d is too low for %d workers" % (hard, args.workers))
    report = lambda what, line: print("%-16s %s" % (what + ":", line), flush=True)
    if args.coordinator_cpu is not None:
        cpus = os.sched_getaffinity(0)
        if args.coordinator_cpu not in cpus or len(cpus) < 2:
            parser.error("--coordinator-cpu %d: this script may run on CPUs %s; it needs that "
                         "one and another" % (args.coordinator_cpu, sorted(cpus)))
        # Before any thread starts (asyncio.to_thread's), so that all of them inherit it.
        os.sched_setaffinity(0, cpus - {args.coordinator_cpu})
        report("pinned", "the coordinator to CPU %d, this script (the synthetic workers) to "
               "CPUs %s" % (args.coordinator_cpu,
                            ",".join(map(str, sorted(cpus - {args.coordinator_cpu})))))
    with tempfile.TemporaryDirectory() as tmp:
        coordinator = Coordinator(args.build, tmp, args.heartbeat_ms, args.silence_ms,
                                  args.coordinator_cpu)
        try:
            asyncio.run(measure(args, coordinator, report))
        except AssertionError as e:
            print("coordinator_capacity: FAILED: %s\n--- the coordinator's log ends:\n%s" %
                  (e, coordinator.log()[-3000:]))
            return 1
        finally:
            coordinator.proc.kill()
            coordinator.proc.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())

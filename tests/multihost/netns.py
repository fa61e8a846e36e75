"""Hosts on one machine: network namespaces joined by veth pairs (Debian's iproute2), with
latency and bandwidth added by tc netem where the kernel has it, else by delay_proxy.py, a
relay in the worker's namespace that holds every byte back half the round trip each way.
Needs root (or CAP_NET_ADMIN).

Topology: a coordinator namespace linked to the test's own namespace (no delay, for the HTTP
API) and to one namespace per worker, each worker on its own link and subnet, so that a
worker's link can be cut alone:

    test 10.213.0.1 ── 10.213.0.2 coordinator 10.213.N.1 ── 10.213.N.2 worker N
"""
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SKIP = 77  # ctest's SKIP_RETURN_CODE for these tests


def run(*argv):
    subprocess.run(argv, check=True, capture_output=True, text=True)


def unavailable():
    """Why network namespaces cannot be used here, or None when they can."""
    if os.geteuid() != 0:
        return "needs root for ip netns"
    probe = "tessera-probe-%d" % os.getpid()
    try:
        run("ip", "netns", "add", probe)
    except (OSError, subprocess.CalledProcessError) as e:
        return "ip netns add failed: %s" % getattr(e, "stderr", e).strip()
    subprocess.run(["ip", "netns", "del", probe], capture_output=True)
    return None


def latency_method():
    return "tc netem" if netem_available() else "delay_proxy.py (this kernel has no tc netem)"


def netem_available():
    probe = "tessera-probe-%d" % os.getpid()
    run("ip", "netns", "add", probe)
    try:
        run("ip", "-n", probe, "link", "set", "lo", "up")
        run("ip", "netns", "exec", probe, "tc", "qdisc", "add", "dev", "lo", "root", "netem",
            "delay", "1ms")
        return True
    except (OSError, subprocess.CalledProcessError):
        return False
    finally:
        subprocess.run(["ip", "netns", "del", probe], capture_output=True)


class Network:
    """The namespaces of one test; deleted (with their links) on exit."""

    def __init__(self):
        self.netem = netem_available()
        self.tag = "t%d" % (os.getpid() % 100000)
        self.coordinator_ns = self.tag + "-coord"
        self.namespaces = []
        self.links = 0
        self._add_namespace(self.coordinator_ns)
        # The test's side stays in the root namespace: the API answers without delay.
        self._link(None, "10.213.0.1", self.coordinator_ns, "10.213.0.2", rtt_ms=0, rate=None)
        self.api_host = "10.213.0.2"

    def _add_namespace(self, name):
        run("ip", "netns", "add", name)
        self.namespaces.append(name)
        run("ip", "-n", name, "link", "set", "lo", "up")

    def _link(self, a_ns, a_addr, b_ns, b_addr, rtt_ms, rate):
        """A veth pair between two namespaces (None: the test's own), each end delaying half
        the round trip and limited to `rate` (tc syntax, e.g. "100mbit")."""
        self.links += 1
        a_dev, b_dev = "%s-a%d" % (self.tag, self.links), "%s-b%d" % (self.tag, self.links)
        run("ip", "link", "add", a_dev, "type", "veth", "peer", "name", b_dev)
        for dev, ns, addr in ((a_dev, a_ns, a_addr), (b_dev, b_ns, b_addr)):
            on = ["-n", ns] if ns else []
            if ns:
                run("ip", "link", "set", dev, "netns", ns)
            run("ip", *on, "addr", "add", addr + "/24", "dev", dev)
            run("ip", *on, "link", "set", dev, "up")
            netem = (["delay", "%gms" % (rtt_ms / 2)] if rtt_ms else []) + \
                (["rate", rate] if rate else [])
            if netem and self.netem:
                inside = ["ip", "netns", "exec", ns] if ns else []
                run(*inside, "tc", "qdisc", "add", "dev", dev, "root", "netem", *netem,
                    "limit", "100000")
        return b_dev if b_ns == self.coordinator_ns else a_dev

    def add_worker(self, service, name, rtt_ms=0, rate_mbit=0, threads=1, worker_args=()):
        """Starts a worker of `service` (with `worker_args`, e.g. its --tls-ca) in a new
        namespace `rtt_ms` away from the coordinator; returns the name of its link for cut()."""
        index = len(self.namespaces)
        ns = "%s-w%d" % (self.tag, index)
        self._add_namespace(ns)
        coordinator = "10.213.%d.1" % index
        rate = "%gmbit" % rate_mbit if rate_mbit else None
        coord_dev = self._link(self.coordinator_ns, coordinator, ns, "10.213.%d.2" % index,
                               rtt_ms, rate)
        prefix = ["ip", "netns", "exec", ns]
        address, port = coordinator, service.worker_port
        if not self.netem and (rtt_ms or rate_mbit):
            port_file = os.path.join(service.tmp.name, name + "-proxy.json")
            service.spawn([*prefix, sys.executable, os.path.join(HERE, "delay_proxy.py"),
                           "--connect", "%s:%d" % (coordinator, port), "--delay-ms",
                           str(rtt_ms / 2), "--rate-mbit", str(rate_mbit), "--port-file",
                           port_file], name + "-proxy")
            deadline = time.time() + 10
            while not os.path.exists(port_file):
                assert time.time() < deadline, "delay_proxy.py did not start"
                time.sleep(0.02)
            with open(port_file) as f:
                address, port = "127.0.0.1", json.load(f)["port"]
        service.worker(name, threads=threads, prefix=prefix, address=address, port=port,
                       extra=worker_args)
        return coord_dev

    def coordinator_prefix(self):
        return ["ip", "netns", "exec", self.coordinator_ns]

    def cut(self, coord_dev):
        """Takes the coordinator's end of a worker's link down: packets stop both ways."""
        run("ip", "-n", self.coordinator_ns, "link", "set", coord_dev, "down")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        for ns in reversed(self.namespaces):  # deleting a namespace deletes its veth ends
            subprocess.run(["ip", "netns", "del", ns], capture_output=True)
        subprocess.run(["ip", "link", "del", "%s-a1" % self.tag], capture_output=True)

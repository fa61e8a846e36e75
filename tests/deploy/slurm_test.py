#!/usr/bin/env python3
"""deploy/slurm/tessera-workers.sbatch on a real one-node Slurm cluster (issue 22 §2).

Starts munged, slurmctld and slurmd directly (no systemd) from Debian's munge and slurm-wlm,
with a generated slurm.conf, key and state in a temporary folder and ports the system picks;
submits the batch script with two tasks against a coordinator on loopback; renders a job
through those two workers and checks its EXR bit-identical to tessera-render's; cancels the
allocation and checks that both workers leave the coordinator. Everything it started is
stopped, and the folder removed.

usage: slurm_test.py --build BUILD_DIR --source SOURCE_DIR
Exits 77 (ctest: skipped), saying why, when not root or without the Slurm and munge programs.
"""
import argparse
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time

SKIP = 77
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "service"))
import service_test  # noqa: E402  (Service, render_and_compare)

PROGRAMS = ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "scancel")
# The service tests' small job: several levels and two passes, a few hundred units.
SETTINGS = service_test.SETTINGS


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for(what, condition, timeout, log_files=()):
    deadline = time.time() + timeout
    while not condition():
        if time.time() > deadline:
            for path in log_files:
                if os.path.exists(path):
                    print("--- %s\n%s" % (path, open(path).read()[-3000:]))
            raise AssertionError("timed out waiting for " + what)
        time.sleep(0.1)


class Cluster:
    """munged, slurmctld and slurmd of one node, all in `folder`; stopped on exit."""

    def __init__(self, folder):
        self.folder = folder
        self.procs = []
        self.env = dict(os.environ, SLURM_CONF=os.path.join(folder, "slurm.conf"))

    def path(self, name):
        return os.path.join(self.folder, name)

    def __enter__(self):
        node = socket.gethostname().split(".")[0]
        for sub in ("state", "spool", "munge"):
            os.makedirs(self.path(sub), mode=0o700)
        key = self.path("munge/munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o400)
        socket_path = self.path("munge/munge.socket")
        self.start(["munged", "--foreground", "--force", "--key-file", key, "--socket",
                    socket_path, "--pid-file", self.path("munge/munged.pid"), "--log-file",
                    self.path("munged.log"), "--seed-file", self.path("munge/seed")], "munged")
        wait_for("munged's socket", lambda: os.path.exists(socket_path), 10,
                 [self.path("munged.log")])
        with open(self.path("slurm.conf"), "w") as f:
            f.write("\n".join([
                "ClusterName=tessera-test",
                "SlurmctldHost=%s(127.0.0.1)" % node,
                "SlurmctldPort=%d" % free_port(),
                "SlurmdPort=%d" % free_port(),
                "SlurmUser=root",
                "AuthType=auth/munge",
                "CredType=cred/munge",
                "AuthInfo=socket=%s" % socket_path,
                "StateSaveLocation=%s" % self.path("state"),
                "SlurmdSpoolDir=%s" % self.path("spool"),
                "SlurmctldPidFile=%s" % self.path("slurmctld.pid"),
                "SlurmdPidFile=%s" % self.path("slurmd.pid"),
                "SlurmctldLogFile=%s" % self.path("slurmctld.log"),
                "SlurmdLogFile=%s" % self.path("slurmd.log"),
                # No cgroups, no accounting: nothing outside this folder is touched.
                "ProctrackType=proctrack/linuxproc",
                "TaskPlugin=task/none",
                "JobAcctGatherType=jobacct_gather/none",
                "AccountingStorageType=accounting_storage/none",
                "JobCompType=jobcomp/none",
                "MpiDefault=none",
                "SwitchType=switch/none",
                "SelectType=select/cons_tres",
                "SelectTypeParameters=CR_CPU",
                "ReturnToService=2",
                "SlurmdTimeout=30",
                "NodeName=%s NodeAddr=127.0.0.1 CPUs=%d State=UNKNOWN"
                % (node, os.cpu_count()),
                "PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP",
                ""]))
        self.start(["slurmctld", "-D", "-i"], "slurmctld")
        self.start(["slurmd", "-D", "-N", node], "slurmd")
        logs = [self.path("slurmctld.log"), self.path("slurmd.log")]
        wait_for("the node to be idle", lambda: "idle" in self.run(
            ["sinfo", "-h", "-o", "%T"], check=False), 30, logs)
        return self

    def start(self, argv, name):
        log = open(self.path(name + ".out"), "w")
        self.procs.append(subprocess.Popen(argv, env=self.env, stdout=log,
                                           stderr=subprocess.STDOUT))

    def run(self, argv, check=True, env=None):
        result = subprocess.run(argv, env=dict(self.env, **(env or {})), capture_output=True,
                                text=True)
        if check and result.returncode != 0:
            raise AssertionError("%s: %s" % (argv, result.stdout + result.stderr))
        return result.stdout

    def jobs(self):
        return self.run(["squeue", "-h", "-o", "%i %T"], check=False).split()

    def __exit__(self, *exc):
        self.run(["scancel", "--full", "--user", "root"], check=False)
        try:
            wait_for("the cluster to drain", lambda: not self.jobs(), 15)
        except AssertionError:
            pass
        for proc in reversed(self.procs):
            proc.terminate()
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", required=True)
    args = parser.parse_args()
    service_test.ARGS = args
    missing = [p for p in PROGRAMS + ("sinfo",) if not shutil.which(p)]
    if os.geteuid() != 0:
        print("SKIPPED: slurm: needs root to run slurmd and munged")
        return SKIP
    if missing:
        print("SKIPPED: slurm: %s not found (Debian's slurm-wlm and munge; "
              "scripts/install-deps.sh installs them)" % ", ".join(missing))
        return SKIP
    script = os.path.join(args.source, "deploy", "slurm", "tessera-workers.sbatch")
    tmp = tempfile.mkdtemp(prefix="tessera-slurm-")
    try:
        with service_test.Service() as service, Cluster(tmp) as cluster:
            out = os.path.join(tmp, "workers-%j.out")
            submitted = cluster.run(
                ["sbatch", "--parsable", "--ntasks", "2", "--ntasks-per-node", "2",
                 "--output", out, script],
                env={"TESSERA_COORDINATOR": "127.0.0.1:%d" % service.worker_port,
                     "TESSERA_SECRET": service_test.SECRET,
                     "TESSERA_WORKER": service_test.binary("worker", "tessera-worker")})
            job = submitted.strip().split(";")[0]
            service.wait_workers(2, timeout=30)
            names = sorted(w["name"] for w in service.get("/api/workers"))
            assert [n.split("/")[-1] for n in names] == ["slurm-%s.0" % job,
                                                         "slurm-%s.1" % job], names

            status = service_test.render_and_compare(service, SETTINGS, tmp, "slurm")
            # Rendered by the allocation's workers (which of the two takes how many of the
            # job's few units is the scheduler's business).
            shares = {w["name"]: w["units"] for w in status["workers"]}
            assert set(shares) <= set(names) and sum(shares.values()) > 0, shares

            # The allocation ends: Slurm signals the workers, they exit and leave.
            cluster.run(["scancel", job])
            wait_for("the workers to leave", lambda: not service.get("/api/workers"), 30)
            wait_for("the allocation to end", lambda: job not in cluster.jobs(), 30)
        print("slurm: 2 workers of allocation %s rendered a job (units %s), bit-identical; "
              "both left when it was cancelled" % (job, sorted(shares.values())))
        return 0
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())

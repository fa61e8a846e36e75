#!/usr/bin/env python3
"""The compose setup with TLS (issue 17 §5; docs/SECURITY.md "TLS in containers") is
consistent, checked without a container runtime: docker/compose.yaml with
docker/compose.tls.yaml on top, the certificate docker/make-tls-cert.sh makes, and what
docker/entrypoint.sh and docker/healthcheck.sh do with them.

- the script's certificate names the host the workers dial (TESSERA_COORDINATOR) and the
  host's own ways in; its key is readable by its owner only;
- every TLS file the services' environment names lies in a volume of that service whose
  source is the script's output; workers get the certificate and never the key;
- the entry point turns that environment into --tls-cert/--tls-key and --tls-ca (the
  coordinator's arguments through a stand-in program; a real worker through the real entry
  point joins a real coordinator serving the pair, over TLS, verifying it);
- the flags are the programs' own (their --help), and the health check answers 200 over HTTPS
  when TLS is on (and the image installs the openssl command it uses).

usage: compose_tls_test.py --build BUILD_DIR --source SOURCE_DIR
"""
import argparse
import os
import re
import ssl
import stat
import subprocess
import sys
import tempfile
import time
import urllib.request

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "service"))
import service_test  # noqa: E402  (start_coordinator)

from checks import FAILURES, check  # noqa: E402


def interpolate(value, variables):
    """Compose's ${VAR}, ${VAR:-default} and ${VAR:?message} in `value`, from `variables`."""
    def one(m):
        name, kind, rest = m.group(1), m.group(2), m.group(3)
        if name in variables:
            return variables[name]
        assert kind == "-", "%s is required: %s" % (name, rest)
        return rest
    return re.sub(r"\$\{(\w+)(?::([-?])([^}]*))?\}", one, str(value))


def merged_services(source, variables):
    """compose.yaml's services with compose.tls.yaml's on top (environment maps merged,
    volume lists joined, as compose merges them), their variables taken from `variables`."""
    docker = os.path.join(source, "docker")
    base = yaml.safe_load(open(os.path.join(docker, "compose.yaml")))["services"]
    tls = yaml.safe_load(open(os.path.join(docker, "compose.tls.yaml")))["services"]
    for name, extra in tls.items():
        service = base[name]
        service["environment"] = {**service.get("environment", {}), **extra.get("environment", {})}
        service["volumes"] = service.get("volumes", []) + extra.get("volumes", [])
    for service in base.values():
        service["environment"] = {k: interpolate(v, variables)
                                  for k, v in service.get("environment", {}).items()}
        service["volumes"] = [interpolate(v, variables) for v in service.get("volumes", [])]
    return base


def host_file(service, path):
    """The host file behind `path` in the service's container, through its bind mounts."""
    for volume in service["volumes"]:
        parts = volume.split(":")
        host, target = parts[0], parts[1]
        if not host.startswith("/"):
            continue  # a named volume
        if path == target:
            return host
        if path.startswith(target.rstrip("/") + "/"):
            return os.path.join(host, os.path.relpath(path, target))
    return None


def entrypoint_argv(source, role, env, stub_dir):
    """The command line docker/entrypoint.sh ROLE runs, through stand-in programs that print
    their arguments one a line."""
    for program in ("tessera-coordinator", "tessera-worker"):
        path = os.path.join(stub_dir, program)
        with open(path, "w") as f:
            f.write('#!/bin/sh\nprintf "%s\\n" "$@"\n')
        os.chmod(path, 0o755)
    run_env = {**env, "PATH": stub_dir + ":/usr/bin:/bin"}
    out = subprocess.run([os.path.join(source, "docker", "entrypoint.sh"), role], env=run_env,
                         capture_output=True, text=True, check=True).stdout
    return out.splitlines()


def flag_value(argv, flag):
    return argv[argv.index(flag) + 1] if flag in argv else None


def certificate_names(cert, host):
    """Whether the certificate is valid for `host` (a DNS name or an IP address)."""
    option = "-checkip" if host.replace(".", "").isdigit() else "-checkhost"
    out = subprocess.run(["openssl", "x509", "-in", cert, "-noout", option, host],
                         capture_output=True, text=True).stdout
    return "does match" in out


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", required=True)
    args = parser.parse_args()
    service_test.ARGS = args
    source = os.path.abspath(args.source)
    with tempfile.TemporaryDirectory() as tmp:
        tls_dir = os.path.join(tmp, "tls")
        subprocess.run([os.path.join(source, "docker", "make-tls-cert.sh"), tls_dir],
                       check=True, capture_output=True)
        cert, key = os.path.join(tls_dir, "tls.crt"), os.path.join(tls_dir, "tls.key")
        check(stat.S_IMODE(os.stat(key).st_mode) == 0o600, "the key is readable by others")
        check(stat.S_IMODE(os.stat(tls_dir).st_mode) == 0o755,
              "the certificate's folder is not searchable by the containers' user")
        if os.getuid() == 0:
            check(os.stat(key).st_uid == 7701, "the key does not belong to uid 7701 (tessera)")
        for host in ("coordinator", "localhost", "127.0.0.1"):
            check(certificate_names(cert, host), "the certificate does not name " + host)

        services = merged_services(source, {"TESSERA_TLS_DIR": tls_dir,
                                            "TESSERA_SECRET": service_test.SECRET,
                                            "TESSERA_API_TOKEN": "token"})
        coordinator, worker = services["coordinator"], services["worker"]
        c_env, w_env = coordinator["environment"], worker["environment"]
        check(host_file(coordinator, c_env.get("TESSERA_TLS_CERT", "")) == cert,
              "TESSERA_TLS_CERT is not the script's certificate in a coordinator volume")
        check(host_file(coordinator, c_env.get("TESSERA_TLS_KEY", "")) == key,
              "TESSERA_TLS_KEY is not the script's key in a coordinator volume")
        check(host_file(worker, w_env.get("TESSERA_TLS_CA", "")) == cert,
              "TESSERA_TLS_CA is not the script's certificate in a worker volume")
        check(all(":ro" in v for v in coordinator["volumes"] + worker["volumes"]
                  if v.startswith(tls_dir)), "a TLS volume is writable")
        check(not any(v.startswith(tls_dir) and not v.startswith(cert)
                      for v in worker["volumes"]), "workers get more than the certificate")
        dialled, port = w_env["TESSERA_COORDINATOR"].rsplit(":", 1)
        check(certificate_names(cert, dialled),
              "the workers dial %s, which the certificate does not name" % dialled)
        check(port + ":" + port in " ".join(coordinator["ports"]), "the worker port differs")

        # The environment as arguments, and the arguments as the programs take them.
        c_argv = entrypoint_argv(source, "coordinator", {
            **c_env, "TESSERA_HTTP_PORT": "8080", "TESSERA_WORKER_PORT": "7701"}, tmp)
        check(flag_value(c_argv, "--tls-cert") == c_env["TESSERA_TLS_CERT"] and
              flag_value(c_argv, "--tls-key") == c_env["TESSERA_TLS_KEY"],
              "the coordinator's entry point runs %s" % c_argv)
        w_argv = entrypoint_argv(source, "worker", w_env, tmp)
        check(flag_value(w_argv, "--tls-ca") == w_env["TESSERA_TLS_CA"],
              "the worker's entry point runs %s" % w_argv)
        plain = entrypoint_argv(source, "coordinator", {"TESSERA_HTTP_PORT": "8080",
                                                        "TESSERA_WORKER_PORT": "7701"}, tmp)
        check("--tls-cert" not in plain, "TLS without its environment")
        helps = {name: subprocess.run([service_test.binary(folder, name), "--help"],
                                      capture_output=True, text=True).stdout
                 for folder, name in (("coordinator", "tessera-coordinator"),
                                      ("worker", "tessera-worker"))}
        for flag in ("--tls-cert", "--tls-key"):
            check(flag in helps["tessera-coordinator"], "tessera-coordinator has no " + flag)
        check("--tls-ca" in helps["tessera-worker"], "tessera-worker has no --tls-ca")
        dockerfile = open(os.path.join(source, "docker", "Dockerfile")).read()
        coordinator_stage = dockerfile.split("AS coordinator")[1].split("FROM ")[0]
        check(" openssl" in coordinator_stage, "the coordinator image has no openssl command")

        # The pair in use: a coordinator serving it, a worker through the real entry point
        # (the real tessera-worker first on PATH), the health check over HTTPS.
        log = open(os.path.join(tmp, "coordinator.log"), "w")
        proc, http_port, worker_port = service_test.start_coordinator(
            args.build, ["--secret", service_test.SECRET, "--tls-cert", cert, "--tls-key", key],
            log, os.path.join(tmp, "ports.json"))
        worker_proc = None
        try:
            worker_proc = subprocess.Popen(
                [os.path.join(source, "docker", "entrypoint.sh"), "worker"],
                env={**w_env, "TESSERA_COORDINATOR": "localhost:%d" % worker_port,
                     "TESSERA_TLS_CA": cert, "TESSERA_SECRET": service_test.SECRET,
                     "PATH": os.path.dirname(service_test.binary("worker", "tessera-worker")) +
                     ":/usr/bin:/bin"},
                stdout=log, stderr=subprocess.STDOUT)
            context = ssl.create_default_context(cafile=cert)
            deadline, workers = time.time() + 20, "[]"
            while time.time() < deadline and workers == "[]":
                url = "https://localhost:%d/api/workers" % http_port
                with urllib.request.urlopen(url, context=context, timeout=10) as r:
                    workers = r.read().decode()
                time.sleep(0.1)
            check(workers != "[]", "the worker given TESSERA_TLS_CA did not join")
            health = os.path.join(source, "docker", "healthcheck.sh")
            env = {"TESSERA_HTTP_PORT": str(http_port), "PATH": "/usr/bin:/bin"}
            check(subprocess.run([health, "coordinator"], env={**env, **c_env}).returncode == 0,
                  "the health check fails over HTTPS")
            check(subprocess.run([health, "coordinator"], env=env).returncode != 0,
                  "the plain health check passes against a TLS port")
        finally:
            for p in (worker_proc, proc):
                if p:
                    p.kill()
                    p.wait()
            log.close()
        if FAILURES:
            print(open(os.path.join(tmp, "coordinator.log")).read()[-3000:])
    for failure in FAILURES:
        print("FAIL: " + failure)
    print("%d checks failed" % len(FAILURES) if FAILURES else "compose with TLS: consistent")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())

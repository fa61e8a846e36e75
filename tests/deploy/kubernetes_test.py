#!/usr/bin/env python3
"""The Kubernetes manifests (issue 22 §1) hold what docs/KUBERNETES.md promises and what the
programs and images accept.

Renders deploy/kubernetes (the example overlay) and deploy/kubernetes/base with
`kubectl kustomize`, turns the YAML into JSON offline (`kubectl patch --local`), and checks:
the objects against the page's table, every Secret reference against its Secrets table, the
images against docker/compose.yaml's and the page's, every flag against the program's own
usage text, every file a flag names against a mounted Secret key, probes against a running
coordinator (the path answers 200) and docker/healthcheck.sh, the autoscaler's metric against
the adapter rule and /metrics, resources and non-root security contexts on every container.

usage: kubernetes_test.py --build BUILD_DIR --source SOURCE_DIR
Exits 77 (ctest: skipped) without kubectl (Debian's kubernetes-client).
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import urllib.error
import urllib.request

SKIP = 77
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "service"))
import service_test  # noqa: E402  (start_coordinator)

from checks import FAILURES, check  # noqa: E402


def render(kubectl, folder):
    """The objects `kubectl kustomize FOLDER` makes, as dicts."""
    yaml = subprocess.run([kubectl, "kustomize", folder], check=True, capture_output=True,
                          text=True).stdout
    # An empty merge patch applied locally prints each object as JSON: no YAML parser needed.
    text = subprocess.run([kubectl, "patch", "--local", "--type", "merge", "-p", "{}", "-f",
                           "-", "-o", "json"], input=yaml, check=True, capture_output=True,
                          text=True).stdout
    decoder, objects, i = json.JSONDecoder(), [], 0
    while True:
        while i < len(text) and text[i].isspace():
            i += 1
        if i == len(text):
            return objects
        obj, i = decoder.raw_decode(text, i)
        objects.extend(obj["items"] if obj.get("kind") == "List" else [obj])


def doc_table(doc, heading):
    """Rows of the first Markdown table after `heading`, as lists of cells without backquotes."""
    lines = doc[doc.index(heading):].splitlines()[1:]
    rows = []
    for line in lines:
        if not line.startswith("|"):
            if rows:
                break
            continue
        cells = [c.strip().strip("`") for c in line.strip().strip("|").split("|")]
        if not set(cells[0]) <= set("- "):
            rows.append(cells)
    return rows[1:]  # without the header row


def usage_flags(argv):
    """Every --flag a program's --help (or usage error) prints."""
    out = subprocess.run(argv + ["--help"], capture_output=True, text=True)
    return set(re.findall(r"--[a-z][a-z0-9-]*", out.stdout + out.stderr))


def pod_spec(obj):
    return obj["spec"]["template"]["spec"]


def check_containers(obj, flags, secrets, uid):
    spec = pod_spec(obj)
    where = "%s %s" % (obj["kind"], obj["metadata"]["name"])
    context = spec.get("securityContext", {})
    check(context.get("runAsNonRoot") is True, where + ": runAsNonRoot")
    check(context.get("runAsUser") == uid, where + ": runAsUser %s, the image's user is %d"
          % (context.get("runAsUser"), uid))
    volumes = {v["name"]: v for v in spec.get("volumes", [])}
    for claim in obj["spec"].get("volumeClaimTemplates", []):
        volumes[claim["metadata"]["name"]] = claim
    for c in spec["containers"]:
        name = "%s container %s" % (where, c["name"])
        for kind in ("requests", "limits"):
            for resource in ("cpu", "memory"):
                check(resource in c.get("resources", {}).get(kind, {}),
                      "%s: no %s.%s" % (name, kind, resource))
        sc = c.get("securityContext", {})
        check(sc.get("allowPrivilegeEscalation") is False, name + ": allowPrivilegeEscalation")
        check(sc.get("readOnlyRootFilesystem") is True, name + ": readOnlyRootFilesystem")
        check(sc.get("capabilities", {}).get("drop") == ["ALL"], name + ": capabilities")
        args = c.get("args", [])
        for arg in args:
            if arg.startswith("--"):
                check(arg.split("=")[0] in flags, "%s: %s is not a flag of the program" %
                      (name, arg))
        # A file a flag names must be a key of a mounted Secret.
        mounted = {}
        for m in c.get("volumeMounts", []):
            volume = volumes.get(m["name"])
            check(volume is not None, "%s: mounts undeclared volume %s" % (name, m["name"]))
            if volume and "secret" in volume:
                secret = volume["secret"]
                items = secret.get("items") or [{"key": k, "path": k}
                                                 for k in secrets.get(secret["secretName"], [])]
                for item in items:
                    mounted[m["mountPath"] + "/" + item["path"]] = (secret["secretName"],
                                                                     item["key"])
        for flag, path in zip(args, args[1:]):
            if flag in ("--tls-cert", "--tls-key", "--tls-ca"):
                check(path in mounted, "%s: %s %s is no mounted Secret key" % (name, flag, path))
        for env in c.get("env", []):
            ref = env.get("valueFrom", {}).get("secretKeyRef")
            if ref:
                check(ref["key"] in secrets.get(ref["name"], []),
                      "%s: %s from %s/%s, which docs/KUBERNETES.md does not list" %
                      (name, env["name"], ref["name"], ref["key"]))
        for volume in volumes.values():
            if "secret" in volume:
                check(volume["secret"]["secretName"] in secrets,
                      "%s: volume from Secret %s, not in docs/KUBERNETES.md" %
                      (where, volume["secret"]["secretName"]))
    return mounted


def env_of(container):
    return {e["name"]: e.get("value") for e in container.get("env", [])}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", required=True)
    args = parser.parse_args()
    kubectl = shutil.which("kubectl")
    if not kubectl:
        print("SKIPPED: kubernetes: kubectl not found (Debian's kubernetes-client; "
              "scripts/install-deps.sh installs it)")
        return SKIP
    src = lambda *p: os.path.join(args.source, *p)
    doc = open(src("docs", "KUBERNETES.md")).read()
    example = render(kubectl, src("deploy", "kubernetes"))
    base = render(kubectl, src("deploy", "kubernetes", "base"))

    # The objects, as the page lists them ("overlay" rows only in the example).
    objects = doc_table(doc, "## What the manifests hold")
    by_key = {(o["kind"], o["metadata"]["name"]): o for o in example}
    check(set(by_key) == {(row[0], row[1]) for row in objects},
          "rendered objects %s, docs/KUBERNETES.md lists %s" %
          (sorted(by_key), sorted((r[0], r[1]) for r in objects)))
    check({(o["kind"], o["metadata"]["name"]) for o in base} ==
          {(r[0], r[1]) for r in objects if r[2] == "base"},
          "the base's objects differ from the rows marked base")
    secrets = {row[0]: [k.strip().strip("`") for k in row[1].split(",")]
               for row in doc_table(doc, "## Secrets")}

    # The image's user (docker/Dockerfile) and the data directory (docker/entrypoint.sh).
    dockerfile = open(src("docker", "Dockerfile")).read()
    uid = int(re.search(r"--uid (\d+)", dockerfile).group(1))
    worker_uid = int(re.search(r"collect-root\.sh /worker-root (\d+)", dockerfile).group(1))
    check(worker_uid == uid, "the worker image's user is %d, the coordinator's %d" %
          (worker_uid, uid))
    data_dir = re.search(r"TESSERA_DATA_DIR:-([^}]+)}",
                         open(src("docker", "entrypoint.sh")).read()).group(1)

    coordinator = by_key.get(("StatefulSet", "tessera-coordinator"))
    worker = by_key.get(("Deployment", "tessera-worker"))
    if not coordinator or not worker:
        print("\n".join(FAILURES))
        return 1
    coordinator_flags = usage_flags([os.path.join(args.build, "coordinator",
                                                  "tessera-coordinator")])
    worker_flags = usage_flags([os.path.join(args.build, "worker", "tessera-worker")])
    check("--tls-cert" in coordinator_flags and "--tls-ca" in worker_flags,
          "could not read the programs' flags")
    coord_mounts = check_containers(coordinator, coordinator_flags, secrets, uid)
    worker_mounts = check_containers(worker, worker_flags, secrets, uid)
    check(not any(key == "tls.key" for _, key in worker_mounts.values()),
          "workers must get the certificate only, never the key: %s" % worker_mounts)
    check(("tessera-tls", "tls.key") in coord_mounts.values(), "the coordinator has no key")

    # Images: the base uses those scripts/build-images.sh makes (as the compose file does), the
    # overlay what the page says.
    built = set(re.findall(r"image: (\S+)", open(src("docker", "compose.yaml")).read()))
    base_images = {c["image"] for o in base if o["kind"] in ("StatefulSet", "Deployment")
                   for c in pod_spec(o)["containers"]}
    check(base_images == built, "base images %s, docker/compose.yaml runs %s" %
          (base_images, built))
    for o in (coordinator, worker):
        for c in pod_spec(o)["containers"]:
            check("`%s`" % c["image"] in doc, "image %s is not in docs/KUBERNETES.md" %
                  c["image"])

    # The job store on a persistent volume at the image's data directory.
    (container,) = pod_spec(coordinator)["containers"]
    claims = [t["metadata"]["name"] for t in coordinator["spec"].get("volumeClaimTemplates", [])]
    check(any(m["name"] in claims and m["mountPath"] == data_dir
              for m in container["volumeMounts"]),
          "no volume claim mounted at the data directory %s" % data_dir)
    check(coordinator["spec"]["replicas"] == 1, "one coordinator owns the jobs")

    # Services reach the coordinator's named ports; workers connect to the worker Service.
    ports = {p["name"]: p["containerPort"] for p in container["ports"]}
    labels = coordinator["spec"]["template"]["metadata"]["labels"]
    services = {o["metadata"]["name"]: o for o in example if o["kind"] == "Service"}
    for name, service in services.items():
        check(all(labels.get(k) == v for k, v in service["spec"]["selector"].items()),
              "Service %s does not select the coordinator" % name)
        for p in service["spec"]["ports"]:
            check(p["targetPort"] in ports, "Service %s: no port %s" % (name, p["targetPort"]))
    (worker_container,) = pod_spec(worker)["containers"]
    host, port = env_of(worker_container)["TESSERA_COORDINATOR"].split(":")
    check(host in services and int(port) in [p["port"] for p in services[host]["spec"]["ports"]]
          and ports["workers"] == 7701, "workers connect to %s:%s" % (host, port))
    check("DNS:%s" % host in doc, "the page's certificate must name %s" % host)

    # Probes: the coordinator's path answers 200 on a real coordinator; the worker's command is
    # the image's health check.
    probe_paths = set()
    for kind in ("readinessProbe", "livenessProbe"):
        probe = container.get(kind)
        check(probe is not None and probe["httpGet"]["port"] in ports,
              "coordinator %s: %s" % (kind, probe))
        if probe:
            check(probe["httpGet"].get("scheme") == "HTTPS", "probes speak HTTPS (TLS is on)")
            probe_paths.add(probe["httpGet"]["path"])
    probe = worker_container.get("livenessProbe", {}).get("exec", {}).get("command", [])
    check(probe == ["healthcheck.sh", "worker"] and
          "  worker)" in open(src("docker", "healthcheck.sh")).read(),
          "worker liveness probe %s" % probe)

    # The autoscaler scales the workers on the adapter's metric, made from one on /metrics.
    (hpa,) = [o for o in example if o["kind"] == "HorizontalPodAutoscaler"]
    check(hpa["spec"]["scaleTargetRef"]["name"] == "tessera-worker" and
          hpa["spec"]["scaleTargetRef"]["kind"] == "Deployment", "the HPA's target")
    metric = hpa["spec"]["metrics"][0]["external"]["metric"]["name"]
    rules = open(src("deploy", "kubernetes", "prometheus-adapter-rules.yaml")).read()
    check(re.search(r"as: %s\b" % metric, rules), "no adapter rule makes %s" % metric)
    sources = set(re.findall(r"\b(tessera_[a-z_]+)\{", rules))

    with tempfile.TemporaryDirectory() as tmp:
        proc, http_port, _ = service_test.start_coordinator(
            args.build, ["--insecure"], subprocess.DEVNULL, os.path.join(tmp, "ports.json"))
        try:
            for path in sorted(probe_paths):
                try:
                    status = urllib.request.urlopen("http://127.0.0.1:%d%s" %
                                                    (http_port, path)).status
                except urllib.error.HTTPError as e:
                    status = e.code
                check(status == 200, "probe %s answered %d" % (path, status))
            with urllib.request.urlopen("http://127.0.0.1:%d/metrics" % http_port) as r:
                exposed = r.read().decode()
            for name in sources:
                check(re.search(r"^%s\{" % name, exposed, re.M),
                      "the adapter rule reads %s, which /metrics does not export" % name)
        finally:
            proc.kill()
            proc.wait()
    check(sources, "the adapter rule reads no tessera_ metric")

    for failure in FAILURES:
        print("FAIL:", failure)
    print("kubernetes: %d objects checked, %d failures" % (len(example), len(FAILURES)))
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""TLS on both ports (issue 17 §3): the coordinator with --tls-cert/--tls-key serves HTTPS and
TLS on the worker port; workers verify it with --tls-ca. Each case makes its own self-signed
certificate with the openssl command line.

usage: tls_test.py --build BUILD_DIR --source SOURCE_DIR CASE
CASE: render | refused | relay
"""
import http.client
import os
import socket
import ssl
import subprocess
import tempfile
import threading
import time
import urllib.error
import urllib.request

import service_test
from service_test import SETTINGS, Service, render_and_compare


def make_certificate(folder, name, names="DNS:localhost,IP:127.0.0.1"):
    """A self-signed certificate for `names` (subjectAltName); returns (cert, key) paths."""
    cert, key = os.path.join(folder, name + ".pem"), os.path.join(folder, name + ".key")
    subprocess.run(["openssl", "req", "-x509", "-newkey", "ec", "-pkeyopt",
                    "ec_paramgen_curve:P-256", "-nodes", "-days", "1", "-subj", "/CN=localhost",
                    "-addext", "subjectAltName=" + names, "-keyout", key,
                    "-out", cert], check=True, capture_output=True)
    return cert, key


class TlsService(Service):
    """A coordinator serving its certificate on both ports; the API is reached over HTTPS,
    trusting that certificate, on one kept-alive connection as a browser would (a handshake
    per poll would cost the client and the coordinator more CPU than the service's TLS)."""

    def __init__(self, cert, key, *extra, **where):
        super().__init__("--tls-cert", cert, "--tls-key", key, *extra, **where)
        self.cert = cert
        self.context = ssl.create_default_context(cafile=cert)
        self.connection = None

    def request(self, method, path, body=None, headers=None):
        for attempt in (1, 2):  # once more on a fresh connection if the server closed it
            if self.connection is None:
                self.connection = http.client.HTTPSConnection(self.host, self.http_port,
                                                              timeout=30, context=self.context)
            try:
                self.connection.request(method, path, body=body, headers=headers or {})
                r = self.connection.getresponse()
                return r.status, dict(r.headers), r.read()
            except (http.client.HTTPException, ConnectionError):
                self.connection.close()
                self.connection = None
                if attempt == 2:
                    raise

    def tls_worker(self, name, *tls_args, address="127.0.0.1", port=None):
        return self.worker(name, address=address, port=port, extra=tls_args)

    def log(self, name):
        with open(os.path.join(self.tmp.name, name + ".log")) as f:
            return f.read()


def wait_for(predicate, what, timeout=10):
    deadline = time.time() + timeout
    while not predicate():
        if time.time() > deadline:
            raise AssertionError("timed out waiting for " + what)
        time.sleep(0.05)


def case_render():
    """Jobs over TLS render bit-identical to tessera-render: with local workers (started by the
    coordinator), with a remote worker that verifies the certificate by name, and submitted by
    tessera-submit over HTTPS."""
    with tempfile.TemporaryDirectory() as tmp:
        cert, key = make_certificate(tmp, "coordinator")
        with TlsService(cert, key, "--local-workers", "2", "--local-threads", "1") as service:
            service.wait_workers(2)
            render_and_compare(service, SETTINGS, tmp, "local")
            assert "with TLS" in service.log("coordinator"), service.log("coordinator")
        with TlsService(cert, key) as service:
            # By name (the DNS entry) and by address (the IP entry), each checked.
            service.tls_worker("by-name", "--tls-ca", cert, address="localhost")
            service.tls_worker("by-address", "--tls-ca", cert)
            service.wait_workers(2)
            render_and_compare(service, SETTINGS, tmp, "remote")
            # The API answers over HTTPS only to a client that trusts the certificate.
            names = sorted(w["name"] for w in service.get("/api/workers"))
            assert names == ["by-address", "by-name"], names
            try:
                urllib.request.urlopen("https://127.0.0.1:%d/api/workers" % service.http_port,
                                       timeout=10)
                raise AssertionError("a client without the CA was served")
            except urllib.error.URLError as e:
                assert isinstance(e.reason, ssl.SSLCertVerificationError), e
            submit_over_https(service, cert, tmp)


def submit_over_https(service, cert, tmp):
    """tessera-submit reaches an HTTPS coordinator that its --tls-ca trusts (the image bit-
    identical to tessera-render's), and refuses one whose certificate it cannot verify."""
    scene, out = service_test.demo_scene(), os.path.join(tmp, "submitted.exr")
    argv = [service_test.binary("client", "tessera-submit"), scene, "--coordinator",
            "https://localhost:%d" % service.http_port, "--width", str(SETTINGS["width"]),
            "--height", str(SETTINGS["height"]), "--quiet"]
    result = subprocess.run(argv + ["--tls-ca", cert, "-o", out], capture_output=True, text=True,
                            timeout=100)
    assert result.returncode == 0, result.stdout + result.stderr
    settings = {"width": SETTINGS["width"], "height": SETTINGS["height"]}
    service_test.render_cli(scene, settings, os.path.join(tmp, "submitted-cli.exr"))
    service_test.assert_identical(out, os.path.join(tmp, "submitted-cli.exr"))
    result = subprocess.run(argv, capture_output=True, text=True, timeout=100)
    assert result.returncode == 1 and "certificate verify failed" in result.stderr, \
        result.stdout + result.stderr


def plaintext_exchange(port, data):
    """Sends data over plain TCP and returns what comes back before the peer closes."""
    with socket.create_connection(("127.0.0.1", port), timeout=10) as s:
        s.sendall(data)
        received = b""
        try:
            while True:
                chunk = s.recv(4096)
                if not chunk:
                    break
                received += chunk
        except (ConnectionResetError, socket.timeout):
            pass
        return received


def case_refused():
    """A worker that trusts another CA, a plaintext worker and plaintext clients are refused on
    both ports; none of them ever renders. A certificate for another host name is refused
    too, though the worker trusts it."""
    with tempfile.TemporaryDirectory() as tmp:
        cert, key = make_certificate(tmp, "coordinator")
        other, _ = make_certificate(tmp, "other")
        with TlsService(cert, key) as service:
            service.tls_worker("wrong-ca", "--tls-ca", other)
            service.worker("plaintext")  # no TLS flag: speaks plain frames to a TLS port
            wait_for(lambda: "certificate verify failed" in service.log("wrong-ca"),
                     "the wrong-CA worker's log line")
            wait_for(lambda: "TLS handshake failed" in service.log("coordinator"),
                     "the coordinator's log line")
            # A plain HTTP request on the HTTPS port gets no HTTP answer.
            reply = plaintext_exchange(service.http_port,
                                       b"GET /api/workers HTTP/1.1\r\nHost: x\r\n\r\n")
            assert not reply.startswith(b"HTTP/"), reply[:100]
            reply = plaintext_exchange(service.worker_port, b"\0\0\0\x10" + b"{}" * 8)
            assert reply == b"" or reply[0] == 0x15, reply[:100]  # nothing, or a TLS alert
            assert service.get("/api/workers") == [], service.get("/api/workers")
            # Given a job, still nobody renders it.
            job = service.submit(open(service_test.demo_scene()).read(), SETTINGS)
            time.sleep(1.5)
            assert service.get("/api/jobs/%d" % job["id"])["progress"] == 0.0
            assert service.get("/api/workers") == []
        elsewhere, elsewhere_key = make_certificate(tmp, "elsewhere", "DNS:elsewhere.example")
        with TlsService(elsewhere, elsewhere_key) as service:
            service.context.check_hostname = False  # the test's own client, not the worker
            service.tls_worker("wrong-name", "--tls-ca", elsewhere)
            wait_for(lambda: "certificate verify failed" in service.log("wrong-name"),
                     "the wrong-name worker's log line")
            assert service.get("/api/workers") == []


class FlippingRelay:
    """A TCP forwarder between a worker and the coordinator that flips one bit of the first
    connection's worker-to-coordinator stream once `after` bytes have passed; later
    connections are relayed unaltered."""

    def __init__(self, target_port, after):
        self.target_port, self.after = target_port, after
        self.listener = socket.create_server(("127.0.0.1", 0))
        self.port = self.listener.getsockname()[1]
        self.connections = 0
        self.flipped = False
        threading.Thread(target=self.accept, daemon=True).start()

    def accept(self):
        while True:
            client, _ = self.listener.accept()
            upstream = socket.create_connection(("127.0.0.1", self.target_port))
            self.connections += 1
            tamper = self.connections == 1
            threading.Thread(target=self.pump, args=(client, upstream, tamper),
                             daemon=True).start()
            threading.Thread(target=self.pump, args=(upstream, client, False),
                             daemon=True).start()

    def pump(self, source, sink, tamper):
        passed = 0
        try:
            while True:
                data = source.recv(65536)
                if not data:
                    break
                if tamper and not self.flipped and passed + len(data) > self.after:
                    i = max(0, self.after - passed)
                    data = data[:i] + bytes([data[i] ^ 0x01]) + data[i + 1:]
                    self.flipped = True
                passed += len(data)
                sink.sendall(data)
        except OSError:
            pass
        for s in (source, sink):
            try:
                s.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass


def case_relay():
    """A relay that flips a bit of a worker's results breaks the TLS connection; the results
    are never altered: the worker reconnects and the image is still bit-identical."""
    with tempfile.TemporaryDirectory() as tmp:
        cert, key = make_certificate(tmp, "coordinator")
        with TlsService(cert, key) as service:
            relay = FlippingRelay(service.worker_port, after=6000)
            service.tls_worker("relayed", "--tls-ca", cert, port=relay.port)
            service.wait_workers(1)
            render_and_compare(service, SETTINGS, tmp, "relayed")
            assert relay.flipped, "the relay never flipped a bit"
            assert relay.connections >= 2, "the altered connection was not broken"
            log = service.log("coordinator")
            assert "worker 1: " in log, log


if __name__ == "__main__":
    service_test.run_case(globals())

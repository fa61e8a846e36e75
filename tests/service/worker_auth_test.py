#!/usr/bin/env python3
"""The worker's side of authentication against a fake coordinator (issue 23, §4): a worker
given a secret refuses a coordinator whose challenge offers auth "none" or whose welcome proof
is wrong or missing, with a clear error, exit status 1 and no second connection; it joins one
that proves the secret. The proofs are computed here with Python's hmac, independently of
common/protocol/handshake.cpp, so the wire strings of docs/PROTOCOL.md are pinned too.

usage: worker_auth_test.py --build BUILD_DIR --source SOURCE_DIR
"""
import argparse
import hashlib
import hmac
import json
import os
import socket
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import service_test  # noqa: E402  (binary(), the shared SECRET)

SECRET = service_test.SECRET
VERSION = 2
HELLO, CHALLENGE, AUTH, WELCOME = 1, 2, 3, 4


def proof(kind, first_nonce, second_nonce, secret=SECRET):
    message = "tessera-%s|%d|%s|%s" % (kind, VERSION, first_nonce, second_nonce)
    return hmac.new(secret.encode(), message.encode(), hashlib.sha256).hexdigest()


def send_frame(sock, kind, header):
    head = json.dumps(header).encode()
    body = struct.pack(">BI", kind, len(head)) + head
    sock.sendall(struct.pack(">I", len(body)) + body)


def read_exactly(sock, n):
    data = b""
    while len(data) < n:
        chunk = sock.recv(n - len(data))
        if not chunk:
            raise EOFError("the worker closed the connection")
        data += chunk
    return data


def read_frame(sock):
    (size,) = struct.unpack(">I", read_exactly(sock, 4))
    body = read_exactly(sock, size)
    kind, head_size = struct.unpack(">BI", body[:5])
    return kind, json.loads(body[5:5 + head_size])


class FakeCoordinator:
    """One listening socket on a port the system picks; a tessera-worker pointed at it."""

    def __init__(self, secret):
        self.listener = socket.create_server(("127.0.0.1", 0))
        self.listener.settimeout(10)
        self.tmp = tempfile.TemporaryDirectory()
        self.log_path = os.path.join(self.tmp.name, "worker.log")
        argv = [service_test.binary("worker", "tessera-worker"), "--coordinator",
                "127.0.0.1:%d" % self.listener.getsockname()[1], "--threads", "1",
                "--name", "auth-test"]
        if secret:
            argv += ["--secret", secret]
        env = dict(os.environ)
        env.pop("TESSERA_SECRET", None)
        with open(self.log_path, "w") as log:
            self.worker = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, env=env)

    def accept(self):
        conn, _ = self.listener.accept()
        conn.settimeout(10)
        kind, hello = read_frame(conn)
        assert kind == HELLO and hello["version"] == VERSION, (kind, hello)
        return conn, hello["nonce"]

    def log(self):
        return open(self.log_path).read()

    def expect_refusal(self, conn, words):
        """The worker exits 1 naming the reason, and never connects again."""
        assert self.worker.wait(timeout=10) == 1, self.worker.returncode
        assert words in self.log(), self.log()
        conn.settimeout(2)
        try:  # nothing but the close may follow: the worker sends no auth, no other frame
            assert conn.recv(1) == b""
        except ConnectionResetError:
            pass
        self.listener.settimeout(1.5)  # past the first retry delay (250 ms)
        try:
            self.listener.accept()
            raise AssertionError("the refused worker connected again")
        except socket.timeout:
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.worker.poll() is None:
            self.worker.kill()
        self.worker.wait()
        if exc[0] is not None:
            print("----- worker log\n" + self.log()[-3000:])
        self.listener.close()
        self.tmp.cleanup()


def case_offers_none():
    """A coordinator that offers no authentication gets no obedience from a worker with a
    secret."""
    with FakeCoordinator(SECRET) as fake:
        conn, _ = fake.accept()
        with conn:
            send_frame(conn, CHALLENGE, {"version": VERSION, "nonce": "ab" * 32, "auth": "none"})
            fake.expect_refusal(conn, 'offers authentication "none"')


def case_wrong_proof():
    """A coordinator that does not know the secret, or sends no proof, is refused after the
    worker's own (correct) proof."""
    for welcome in ({"worker": 1, "proof": None}, {"worker": 1}):
        with FakeCoordinator(SECRET) as fake:
            conn, worker_nonce = fake.accept()
            with conn:
                nonce = "cd" * 32
                send_frame(conn, CHALLENGE,
                           {"version": VERSION, "nonce": nonce, "auth": "hmac-sha256"})
                kind, auth = read_frame(conn)
                assert kind == AUTH and auth["proof"] == proof("worker", nonce, worker_nonce)
                if "proof" in welcome:
                    welcome["proof"] = proof("coordinator", worker_nonce, nonce, "guessed")
                send_frame(conn, WELCOME, welcome)
                fake.expect_refusal(conn, "does not know our secret")


def case_right_proof():
    """The real coordinator's answer: the worker joins and stays; without a secret, it joins a
    coordinator that offers auth "none"."""
    for secret in (SECRET, ""):
        with FakeCoordinator(secret) as fake:
            conn, worker_nonce = fake.accept()
            with conn:
                nonce = "ef" * 32
                send_frame(conn, CHALLENGE, {"version": VERSION, "nonce": nonce,
                                             "auth": "hmac-sha256" if secret else "none"})
                kind, auth = read_frame(conn)
                expected = proof("worker", nonce, worker_nonce) if secret else ""
                assert kind == AUTH and auth["proof"] == expected, auth
                send_frame(conn, WELCOME, {"worker": 7, "proof": proof(
                    "coordinator", worker_nonce, nonce) if secret else ""})
                deadline = time.time() + 10
                while "as worker 7" not in fake.log():
                    assert fake.worker.poll() is None and time.time() < deadline, fake.log()
                    time.sleep(0.02)
                time.sleep(0.3)
                assert fake.worker.poll() is None, fake.log()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", required=True)
    service_test.ARGS = parser.parse_args()
    for case in (case_offers_none, case_wrong_proof, case_right_proof):
        start = time.time()
        case()
        print("%s passed in %.1f s" % (case.__name__[5:], time.time() - start))


if __name__ == "__main__":
    sys.exit(main())

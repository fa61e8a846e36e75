#!/usr/bin/env bash
# A self-signed certificate and key for the compose setup with TLS (docker/compose.tls.yaml;
# docs/SECURITY.md "TLS in containers"), made with the openssl command line:
#   docker/make-tls-cert.sh [DIR] [NAMES]    # DIR/tls.crt and DIR/tls.key; DIR: docker/tls
# The certificate names DNS:coordinator (the host the worker containers dial on the compose
# network), DNS:localhost and IP:127.0.0.1 (the page and the API from the host), and NAMES in
# subjectAltName form for other ways in (e.g. DNS:render.example,IP:192.0.2.7).
set -euo pipefail
dir=${1:-$(dirname "$0")/tls}
names="DNS:coordinator,DNS:localhost,IP:127.0.0.1${2:+,$2}"
# The folder is mounted into the containers, which run as uid 7701: it must be searchable.
mkdir -p -m 0755 "$dir"
umask 077
openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:P-256 -nodes -days 365 \
  -subj /CN=coordinator -addext "subjectAltName=$names" \
  -keyout "$dir/tls.key" -out "$dir/tls.crt" 2>/dev/null
chmod 0644 "$dir/tls.crt"
# Only the coordinator's user (tessera, uid 7701 in docker/Dockerfile) may read the key.
if [ "$(id -u)" -eq 0 ]; then
  chown 7701 "$dir/tls.key"
else
  echo "make-tls-cert.sh: give the key to the containers' user: sudo chown 7701 $dir/tls.key" \
    "(rootful), or podman unshare chown 7701 $dir/tls.key (rootless podman)" >&2
fi
echo "$dir/tls.crt: $names"

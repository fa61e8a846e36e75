#!/bin/bash
# Container health: the coordinator answers GET /api/workers with 200 (over HTTPS when
# TESSERA_TLS_CERT is set: openssl s_client, which does not check the certificate on
# loopback); a worker holds an established TCP connection (state 01 in /proc/net/tcp*) to its
# coordinator.
set -euo pipefail
request='GET /api/workers HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n'
case "$1" in
  coordinator)
    port=${TESSERA_HTTP_PORT:-8080}
    if [ -n "${TESSERA_TLS_CERT:-}" ]; then
      printf "$request" | openssl s_client -quiet -connect "127.0.0.1:$port" 2>/dev/null |
        head -n 1 | grep -q ' 200 '
      exit
    fi
    exec 3<>"/dev/tcp/127.0.0.1/$port"
    printf "$request" >&3
    head -n 1 <&3 | grep -q ' 200 ' ;;
  worker)
    port=$(printf '%04X' "${TESSERA_COORDINATOR##*:}")
    cat /proc/net/tcp /proc/net/tcp6 2>/dev/null | awk -v p=":$port" '$3 ~ p"$" && $4 == "01" {found=1} END {exit !found}' ;;
esac

#!/bin/bash
# Maps the containers' environment to the programs' flags; flags given to `podman run` after
# the image name are appended and win.
#   coordinator: TESSERA_HTTP_PORT, TESSERA_WORKER_PORT, TESSERA_DATA_DIR (the job store, a
#                volume: /var/lib/tessera), TESSERA_SECRET and TESSERA_API_TOKEN
#                (read by the program), TESSERA_OPEN_SUBMIT=1 (--open-submit). Requests from the
#                host through a published port do not come from loopback inside the container:
#                to submit, give them TESSERA_API_TOKEN (Authorization: Bearer TOKEN; the page
#                asks for it) or, on a trusted network, TESSERA_OPEN_SUBMIT=1.
#                TESSERA_TLS_CERT and TESSERA_TLS_KEY (--tls-cert, --tls-key: TLS on both ports).
#   worker:      TESSERA_COORDINATOR (host:port, required), TESSERA_THREADS, TESSERA_NAME,
#                TESSERA_SECRET, TESSERA_TLS_CA (--tls-ca: TLS, verifying that certificate)
set -euo pipefail
role=$1
shift
case "$role" in
  coordinator)
    [ "${TESSERA_OPEN_SUBMIT:-}" = 1 ] && set -- --open-submit "$@"
    if [ -n "${TESSERA_TLS_CERT:-}" ]; then
      set -- --tls-cert "$TESSERA_TLS_CERT" \
        --tls-key "${TESSERA_TLS_KEY:?set TESSERA_TLS_KEY with TESSERA_TLS_CERT}" "$@"
    fi
    exec tessera-coordinator --http-port "$TESSERA_HTTP_PORT" --worker-port "$TESSERA_WORKER_PORT" \
      --web-dir /usr/share/tessera/web --scenes-dir /usr/share/tessera/scenes \
      --data-dir "${TESSERA_DATA_DIR:-/var/lib/tessera}" "$@" ;;
  worker)
    args=(--coordinator "${TESSERA_COORDINATOR:?set TESSERA_COORDINATOR to HOST:PORT of the coordinator}")
    [ -n "${TESSERA_THREADS:-}" ] && args+=(--threads "$TESSERA_THREADS")
    [ -n "${TESSERA_NAME:-}" ] && args+=(--name "$TESSERA_NAME")
    [ -n "${TESSERA_TLS_CA:-}" ] && args+=(--tls-ca "$TESSERA_TLS_CA")
    exec tessera-worker "${args[@]}" "$@" ;;
  *)
    echo "entrypoint.sh: unknown role '$role'" >&2
    exit 2 ;;
esac

#!/usr/bin/env bash
# Builds the coordinator and worker container images with podman, from a Debian 12 base made
# here by debootstrap (no registry is needed). docs/MULTIHOST.md explains each step.
#   scripts/build-images.sh        # images tessera-coordinator and tessera-worker
set -euo pipefail
cd "$(dirname "$0")/.."
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
missing=()
for p in podman runc debootstrap podman-compose golang-github-containernetworking-plugin-dnsname; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# runc rather than crun, and explicit limits no higher than the host's: in VMs without
# CAP_SYS_RESOURCE (and with hybrid cgroups) podman's defaults, or even the host's own
# hard limits, cannot be applied.
podman_run_opts=(--runtime runc)
limits=(--ulimit nofile=1024:8192 --ulimit nproc=4096:8192)

base=localhost/tessera-debian:bookworm
if ! $sudo podman image exists "$base"; then
  rootfs=$(mktemp -d)
  trap '$sudo rm -rf "$rootfs"' EXIT
  echo "== debootstrap: a minimal Debian 12 as the base image"
  $sudo debootstrap --variant=minbase bookworm "$rootfs" http://deb.debian.org/debian >/dev/null
  $sudo tar -C "$rootfs" -c . | $sudo podman import - "$base" >/dev/null
fi
for target in coordinator worker; do
  echo "== image tessera-$target"
  $sudo podman "${podman_run_opts[@]}" build --format docker --network host "${limits[@]}" \
    --target "$target" -t "tessera-$target" -f docker/Dockerfile .
done
$sudo podman images --filter reference='tessera-*'

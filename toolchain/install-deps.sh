#!/usr/bin/env bash
# Installs, idempotently, everything kestrel needs on Debian 12 (bookworm), as root:
# host compiler and tools, the two ARM cross compilers, qemu-user, and Eigen, libccd,
# GoogleTest and Google Benchmark for the host and (multiarch) for armhf and armel.
# A transient "Mirror sync in progress" on one index must not fail the install, so the
# result of `apt-get update` is not trusted; the installed packages are checked instead.
set -euo pipefail

host_pkgs=(build-essential cmake ninja-build pkg-config git
           g++-arm-linux-gnueabihf g++-arm-linux-gnueabi qemu-user
           libeigen3-dev libccd-dev libgtest-dev libgmock-dev libbenchmark-dev libpng-dev zlib1g-dev
           binutils-arm-linux-gnueabihf)
arm_pkgs=()
for arch in armhf armel; do
  arm_pkgs+=("libccd-dev:$arch" "libgtest-dev:$arch" "libgmock-dev:$arch" "libbenchmark-dev:$arch"
             "libc6:$arch" "libstdc++6:$arch" "zlib1g:$arch"
)
done

missing() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}\n' "$p" 2>/dev/null | grep -q '^install ok installed$' || echo "$p"
  done
}

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: run as root (apt-get needs it)" >&2
  exit 1
fi

for arch in armhf armel; do
  dpkg --print-foreign-architectures | grep -qx "$arch" || dpkg --add-architecture "$arch"
done

todo=$(missing "${host_pkgs[@]}" "${arm_pkgs[@]}")
if [ -n "$todo" ]; then
  export DEBIAN_FRONTEND=noninteractive
  # A foreign architecture's index can lag the host's during a mirror sync; Multi-Arch: same
  # packages then disagree in version, so retry the update a few times before installing.
  for attempt in 1 2 3; do
    if apt-get update; then break; fi
    echo "install-deps: apt-get update failed (attempt $attempt); retrying" >&2
    sleep $((attempt * 5))
  done
  # shellcheck disable=SC2086
  apt-get install -y --no-install-recommends $todo
fi

still=$(missing "${host_pkgs[@]}" "${arm_pkgs[@]}")
if [ -n "$still" ]; then
  echo "install-deps: these packages could not be installed: $still" >&2
  exit 1
fi
echo "install-deps: all packages present"

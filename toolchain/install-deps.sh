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

# The versions of a package (name:arch) that the indexes offer, one a line, sorted for comm.
offered() { apt-cache madison "$1" 2> /dev/null | awk -F'|' '{gsub(/ /, "", $2); print $2}' | LC_ALL=C sort -u; }

# A Multi-Arch: same package must have one version on every architecture. The foreign ones
# do not always offer the host's: bookworm-security (Debian 12 LTS) carries no armel, so
# zlib1g:armhf takes a security update that zlib1g:armel cannot, and apt refuses both. So
# each such package is asked for, on every architecture, at a version all of them offer: the
# host's installed one if it is among them, else the newest they share. Prints name:arch=version
# requests.
pin_multiarch_same() {
  local name host_arch installed common arch v c
  host_arch=$(dpkg --print-architecture)
  for name in "$@"; do
    [[ $(apt-cache show "$name:armhf" 2> /dev/null) == *$'\nMulti-Arch: same'* ]] || continue
    common=$(offered "$name:$host_arch")
    for arch in armhf armel; do
      common=$(LC_ALL=C comm -12 <(echo "$common") <(offered "$name:$arch"))
    done
    if [ -z "$common" ]; then
      echo "install-deps: no version of $name is offered for $host_arch, armhf and armel alike" >&2
      return 1
    fi
    installed=$(dpkg-query -W -f='${Version}' "$name:$host_arch" 2> /dev/null || true)
    if [ -n "$installed" ] && grep -qxF "$installed" <<< "$common"; then
      v=$installed
    else
      v=$(head -n 1 <<< "$common")
      for c in $common; do if dpkg --compare-versions "$c" gt "$v"; then v=$c; fi; done
      if [ -n "$installed" ] || printf '%s\n' "${host_pkgs[@]}" | grep -qxF "$name"; then
        echo "$name:$host_arch=$v"
      fi
    fi
    for arch in armhf armel; do echo "$name:$arch=$v"; done
  done
}

todo=$(missing "${host_pkgs[@]}" "${arm_pkgs[@]}")
if [ -n "$todo" ]; then
  export DEBIAN_FRONTEND=noninteractive
  # A transient "Mirror sync in progress" can fail one index's update: retry a few times, then
  # go on with what the indexes hold and judge by what got installed.
  for attempt in 1 2 3; do
    if apt-get update; then break; fi
    echo "install-deps: apt-get update failed (attempt $attempt); retrying" >&2
    sleep $((attempt * 5))
  done
  # shellcheck disable=SC2046
  pins=$(pin_multiarch_same $(printf '%s\n' "${arm_pkgs[@]}" | sed 's/:.*//' | sort -u))
  # A pinned request replaces the unversioned one (name or name:arch).
  for p in $pins; do
    todo=$(printf '%s\n' $todo | grep -vxF -e "${p%%=*}" -e "${p%%:*}" || true)
  done
  # shellcheck disable=SC2086
  apt-get install -y --no-install-recommends --allow-downgrades $todo $pins
fi

still=$(missing "${host_pkgs[@]}" "${arm_pkgs[@]}")
if [ -n "$still" ]; then
  echo "install-deps: these packages could not be installed: $still" >&2
  exit 1
fi
echo "install-deps: all packages present"

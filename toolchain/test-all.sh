#!/usr/bin/env bash
# The README's test command: installs what is missing, then configures, builds and runs the
# tests of all five presets (host, host-asan, host-tsan: the threaded tests only, and the two
# ARM targets under qemu-arm).
# Usage (as root on Debian 12): bash toolchain/test-all.sh [preset ...]
set -euo pipefail
cd "$(dirname "$0")/.."

bash toolchain/install-deps.sh

presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=(host host-asan host-tsan overo verdex)
jobs=$(nproc)

declare -A result
failed=0
for p in "${presets[@]}"; do
  echo "=== preset $p: configure and build"
  start=$(date +%s)
  cmake --preset "$p" > "build-$p.configure.log" 2>&1 || { cat "build-$p.configure.log"; exit 1; }
  rm -f "build-$p.configure.log"
  cmake --build --preset "$p" -j "$jobs"
  echo "=== preset $p: test"
  launcher=()
  # ThreadSanitizer's runtime (gcc 12) maps its shadow memory at fixed addresses, which a kernel
  # with more address-space randomisation (vm.mmap_rnd_bits 32) can already have used; without
  # randomisation (inherited by every test the run starts) it works on any kernel.
  [ "$p" = host-tsan ] && setarch "$(uname -m)" -R true 2> /dev/null && launcher=(setarch "$(uname -m)" -R)
  if "${launcher[@]}" ctest --preset "$p" -j "$jobs"; then
    result[$p]=passed
  else
    result[$p]=FAILED
    failed=$((failed + 1))
  fi
  echo "=== preset $p: ${result[$p]} in $(( $(date +%s) - start )) s"
done

echo
echo "=== summary"
passed=0
for p in "${presets[@]}"; do
  echo "  $p: ${result[$p]}"
  [ "${result[$p]}" = passed ] && passed=$((passed + 1))
done
echo "presets: $passed passed, $failed failed"
[ "$failed" -eq 0 ]

#!/usr/bin/env bash
# The README's main command: installs what is missing, builds the host preset and flies the
# default mission in the simulator, writing its outputs (render.png, map, trajectories,
# metrics.json) to out/ (or the directory given as the first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out}

bash toolchain/install-deps.sh
cmake --preset host > /dev/null
cmake --build --preset host -j "$(nproc)"
mkdir -p "$out"
./build/host/host_sim/tools/kestrel-sim --world iarc-arena --laser utm30lx --mission explore \
  --duration 600 --seed 1 --out "$out"
echo "outputs in $out/: $(ls "$out" | tr '\n' ' ')"

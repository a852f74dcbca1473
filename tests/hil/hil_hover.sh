#!/usr/bin/env bash
# Hardware in the loop, end to end: kestrel-sim serves its devices over TCP, kestrel-fw flies
# a short hover through its HIL drivers, and the simulator's metrics must show a take-off to
# about 1 m, a landing, and no collision. Real time: about 15 s.
# An optional fourth argument names the laser (default utm30lx); with urg04lx the firmware
# flies with the compact SLAM on its level-3 thread, and must say it processed scans.
set -euo pipefail
sim=$1 fw=$2 out=$3 laser=${4:-utm30lx}
port=$((20000 + RANDOM % 20000))
rm -rf "$out" && mkdir -p "$out"
"$sim" --world iarc-arena --laser "$laser" --mission hil --mission-arg port=$port --mission-arg wait_s=20 \
  --duration 40 --out "$out" > "$out/sim.stderr" 2>&1 &
sim_pid=$!
for _ in $(seq 50); do grep -q "waiting for kestrel-fw" "$out/sim.stderr" 2>/dev/null && break; sleep 0.1; done
fw_rc=0
"$fw" --hil 127.0.0.1:$port --laser "$laser" --mission hover --hover-s 5 --max-s 30 > "$out/fw.stderr" 2>&1 || fw_rc=$?
sim_rc=0
wait $sim_pid || sim_rc=$?
cat "$out/fw.stderr"
[ $fw_rc -eq 0 ] || { echo "kestrel-fw failed ($fw_rc)"; exit 1; }
[ $sim_rc -eq 0 ] || { echo "kestrel-sim failed ($sim_rc)"; cat "$out/sim.stderr"; exit 1; }
grep -q "mission finished, phase landed;" "$out/fw.stderr" || { echo "the firmware did not land"; exit 1; }
# The firmware's own view of the link: frames arrived, none bad, no byte outside a frame.
grep -Eq "link frames [1-9][0-9]*, bad CRC or length 0, skipped bytes 0, malformed 0" "$out/fw.stderr" ||
  { echo "the firmware's link report is missing or shows damage"; exit 1; }
# Its filter's counts: it predicted and took poses, and refused none of the devices' input.
filter_ok="filter imu_samples [1-9][0-9]* imu_not_finite 0 imu_out_of_range 0 imu_time_backwards 0 .*pose_updates [1-9]"
grep -Eq "$filter_ok" "$out/fw.stderr" ||
  { echo "the firmware's filter report is missing or shows refused input"; exit 1; }
grep -Eq "filter .* meas_not_finite 0 meas_out_of_range 0 .*meas_future 0 " "$out/fw.stderr" ||
  { echo "the firmware's filter refused measurements"; exit 1; }
if [ "$laser" = urg04lx ]; then
  grep -Eq "slam on, scans [1-9][0-9]* corrections" "$out/fw.stderr" ||
    { echo "the firmware's SLAM did not run"; exit 1; }
else
  grep -q "slam off, scans 0 corrections 0" "$out/fw.stderr" || { echo "the UTM-30LX firmware ran the SLAM"; exit 1; }
fi
python3 - "$out/metrics.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
assert m["collisions"] == 0, "collision"
assert 0.8 < m["max_altitude_m"] < 1.3, f"max altitude {m['max_altitude_m']}"
assert m["final_truth"]["z_m"] < 0.2, f"did not land: z = {m['final_truth']['z_m']}"
assert m["hil_bad_frames"] == 0, "corrupt frames on the link"
assert m["hil_skipped_bytes"] == 0, "bytes outside any frame on the link"
print("hil hover: ok, max altitude %.2f m, frames out %d in %d"
      % (m["max_altitude_m"], m["hil_frames_out"], m["hil_frames_in"]))
PY

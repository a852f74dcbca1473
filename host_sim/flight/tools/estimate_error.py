#!/usr/bin/env python3
"""The estimate's horizontal error along a kestrel-sim flight, from the run's TUM files.

Reads OUT/trajectory_est.tum and OUT/trajectory_truth.tum of a `kestrel-sim` run, pairs each
estimate with the truth sample nearest in time (the truth is written at 10 Hz), and prints
the horizontal error (m):
  mean      over every estimate
  worst     over the estimates taken while airborne (true height above --airborne-m)
  far_end   where the true position is farthest along --axis (x or y) from the start: the
            README's hallway drift figure (iarc-arena's hallway runs along x)
  final     at the last estimate

Example:
  build/host/host_sim/tools/kestrel-sim --world iarc-arena --mission waypoints \\
      --waypoints host_sim/flight/examples/iarc_arena_hallway.waypoints \\
      --mission-arg controller=CTRL --duration 90 --seed 1 --out out/hall-1
  host_sim/flight/tools/estimate_error.py out/hall-1

Exit status 2 when a file is missing, malformed or empty.
"""
import argparse
import bisect
import math
import sys


def load_tum(path):
    rows = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            fields = line.split()
            if len(fields) != 8:
                raise ValueError(f"{path}:{n}: expected 8 fields, got {len(fields)}")
            values = [float(v) for v in fields]
            if not all(math.isfinite(v) for v in values):
                raise ValueError(f"{path}:{n}: not a finite number")
            rows.append(values)
    if not rows:
        raise ValueError(f"{path}: no poses")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", help="a kestrel-sim --out directory")
    ap.add_argument("--axis", choices=["x", "y"], default="x", help="far_end's axis (default x)")
    ap.add_argument("--airborne-m", type=float, default=0.5, help="worst counts above this true height")
    args = ap.parse_args()
    try:
        est = load_tum(f"{args.run}/trajectory_est.tum")
        truth = load_tum(f"{args.run}/trajectory_truth.tum")
    except (OSError, ValueError) as e:
        print(f"estimate_error: {e}", file=sys.stderr)
        return 2
    times = [t[0] for t in truth]
    axis = 1 if args.axis == "x" else 2
    start = truth[0][axis]
    errors, worst, far, far_error = [], 0.0, -1.0, float("nan")
    for e in est:
        i = bisect.bisect_left(times, e[0])
        if i > 0 and (i == len(times) or e[0] - times[i - 1] <= times[i] - e[0]):
            i -= 1
        g = truth[i]
        err = math.hypot(e[1] - g[1], e[2] - g[2])
        errors.append(err)
        if g[3] > args.airborne_m:
            worst = max(worst, err)
        if abs(g[axis] - start) > far:
            far, far_error = abs(g[axis] - start), err
    print(f"mean {sum(errors) / len(errors):.3f} worst {worst:.3f} far_end {far_error:.3f} "
          f"(at {far:.2f} m along {args.axis}) final {errors[-1]:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

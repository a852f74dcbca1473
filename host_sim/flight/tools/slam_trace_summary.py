#!/usr/bin/env python3
"""Summary of kestrel-sim --trace-scans SLAM traces (slam_trace.csv): could the map set it right?

For each trace given (or each slam_trace.csv under a directory given), one table row with:

  scans        rows in the trace (every scan the compact SLAM processed)
  corrected    handed back to the filter; refused: no_fit, no_gain, too_far
  move p50/p99/max   how far the search's best fit lay from the filter's pose (m)
  off          scans searched while the filter's pose was more than --off-m from the truth
  fit nearer   of those, the share whose (supported) best fit lay at least --gain-m nearer
               the truth
  off the map  of those not drawn (the trace judges only those), the share whose best fit
               lies on ground the map has not drawn (level at least --unknown-level; 128 is a
               cell never drawn): the estimate has run off what the map holds
  map holds truth    of the rest, the share whose scan fits the map at the true pose at least
               --level-gain levels better than at the best fit (true_level)

"fit nearer" low and "map holds truth" low: the map was drawn where the drifted filter put
the walls and has followed it (no search, however wide, would set the filter right from it);
"map holds truth" high and "fit nearer" low: the map holds the true place, out of the search's
reach. The comparison leans towards the fit: the scans drawn in the last 0.3 m were drawn at
the filter's pose. Then a line over all the traces.

Standard library only. Example:
  host_sim/flight/tools/slam_trace_summary.py out/explore/slam_trace.csv
"""
import argparse
import math
import sys

from trace_files import find_traces, load_rows


def percentile(sorted_values, q):
    if not sorted_values:
        return float("nan")
    return sorted_values[min(len(sorted_values) - 1, int(q * len(sorted_values)))]


def summarise(rows, args):
    s = {"scans": len(rows), "corrected": 0, "no_fit": 0, "no_gain": 0, "too_far": 0, "off": 0, "nearer": 0,
         "judged": 0, "off_map": 0, "holds": 0}
    moves = []
    for r in rows:
        for k in ("corrected", "no_fit", "no_gain", "too_far"):
            s[k] += int(r[k])
        if not r["matched"]:
            continue
        moves.append(r["fit_move_m"])
        if math.isnan(r["prior_err_m"]) or r["prior_err_m"] <= args.off_m:
            continue
        s["off"] += 1
        if r["fit_err_m"] <= r["prior_err_m"] - args.gain_m:
            s["nearer"] += 1
        if math.isnan(r["true_level"]):
            continue
        s["judged"] += 1
        if r["level"] >= args.unknown_level:
            s["off_map"] += 1
        elif r["true_level"] <= r["level"] - args.level_gain:
            s["holds"] += 1
    moves.sort()
    s["moves"] = moves
    return s


def share(part, whole):
    return "%.1f %%" % (100.0 * part / whole) if whole else "-"


def row(name, s):
    m = s["moves"]
    return "| %s | %d | %d | %d / %d / %d | %.3f / %.3f / %.3f | %d | %s | %s | %s |" % (
        name, s["scans"], s["corrected"], s["no_fit"], s["no_gain"], s["too_far"], percentile(m, 0.5),
        percentile(m, 0.99), m[-1] if m else float("nan"), s["off"], share(s["nearer"], s["off"]),
        share(s["off_map"], s["judged"]), share(s["holds"], s["judged"] - s["off_map"]))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("traces", nargs="+", help="slam_trace.csv files, or directories searched for them")
    p.add_argument("--off-m", type=float, default=1.0, help="the filter counts as off beyond this, m (1.0)")
    p.add_argument("--gain-m", type=float, default=0.05, help="'fit nearer' by at least this, m (0.05)")
    p.add_argument("--unknown-level", type=float, default=120.0,
                   help="a best fit this high lies off what the map has drawn (120; 128 is never drawn)")
    p.add_argument("--level-gain", type=float, default=6.0,
                   help="'map holds truth' by at least this many levels (6, the SLAM's min_gain_level)")
    args = p.parse_args()
    paths = find_traces(args.traces, "slam_trace.csv")
    if not paths:
        print("slam_trace_summary: no slam_trace.csv found", file=sys.stderr)
        return 2
    print("| trace | scans | corrected | refused: no fit / no gain / too far | move p50 / p99 / max (m) | "
          "off > %.1f m | fit nearer | off the map | map holds truth |" % args.off_m)
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    total = None
    for path in sorted(paths):
        try:
            s = summarise(load_rows(path), args)
        except (OSError, KeyError, ValueError) as e:
            print("slam_trace_summary: %s: %s" % (path, e), file=sys.stderr)
            return 2
        print(row(path, s))
        if total is None:
            total = s
        else:
            for k, v in s.items():
                total[k] = total[k] + v
    total["moves"].sort()
    print(row("all %d" % len(paths), total))
    return 0


if __name__ == "__main__":
    sys.exit(main())

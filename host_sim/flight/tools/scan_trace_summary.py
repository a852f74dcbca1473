#!/usr/bin/env python3
"""Summary of kestrel-sim --trace-scans files (scan_trace.csv): where an estimate's error grew.

For each trace given (or each scan_trace.csv under a directory given), every scan is put in
one class, the first that applies:

  rejected     no pose (too few points in range, bad geometry, no map)
  lost         best score too low: the pose is the prediction
  few          fewer than --few-points scored points
  degenerate   the matcher's degenerate flag (axis ratio above its threshold)
  weak         axis ratio above --weak-ratio, not flagged degenerate
  good         the rest

and the table gives, per class: its share of the scans, the filter's error growth during
those scans (the sum of the increases of nav_err_m from the previous scan), and, over scans
taken while the vehicle moved faster than --moving-mps, how far the match and the filter
moved along the true direction of travel per metre the vehicle really moved (1.000: no
lag; below 1: the estimate falls behind, the controller then flies faster than it thinks).

With --episodes the windows of at most --window seconds in which nav_err_m grew by more than
--growth metres are listed with where the vehicle was and the classes of their scans
(R rejected, L lost, F few, D degenerate, W weak, G good), key scans, map restarts and the
largest velocity error.

Standard library only. Example:
  host_sim/flight/tools/scan_trace_summary.py --episodes out/explore/scan_trace.csv
"""
import argparse
import math
import sys

from trace_files import find_traces, load_rows

CLASSES = ["rejected", "lost", "few", "degenerate", "weak", "good"]
LETTER = {"rejected": "R", "lost": "L", "few": "F", "degenerate": "D", "weak": "W", "good": "G"}


def classify(r, few_points, weak_ratio):
    if r["rejected"]:
        return "rejected"
    if r["lost"]:
        return "lost"
    if r["points"] < few_points:
        return "few"
    if r["degenerate"]:
        return "degenerate"
    if r["axis_ratio"] > weak_ratio:
        return "weak"
    return "good"


def finite(x):
    return not math.isnan(x) and not math.isinf(x)


def summarise(rows, args, acc):
    prev = None
    for i, r in enumerate(rows):
        c = classify(r, args.few_points, args.weak_ratio)
        a = acc[c]
        a["scans"] += 1
        if prev is not None and finite(r["nav_err_m"]) and finite(prev["nav_err_m"]):
            a["growth"] += max(0.0, r["nav_err_m"] - prev["nav_err_m"])
        if prev is not None and not r["rejected"] and not prev["rejected"] and r["t_s"] - prev["t_s"] < 0.5:
            v = math.hypot(r["true_vx"], r["true_vy"])
            if v > args.moving_mps:
                ux, uy = r["true_vx"] / v, r["true_vy"] / v
                along = lambda kx, ky: (r[kx] - prev[kx]) * ux + (r[ky] - prev[ky]) * uy
                a["true_m"] += along("true_x", "true_y")
                a["match_m"] += along("x", "y")
                a["nav_m"] += along("nav_x", "nav_y")
        prev = r


def episodes(rows, args):
    out = []
    i, n = 0, len(rows)
    while i < n:
        best, bj, j = 0.0, i, i
        while j < n and rows[j]["t_s"] - rows[i]["t_s"] <= args.window:
            d = rows[j]["nav_err_m"] - rows[i]["nav_err_m"]
            if finite(d) and d > best:
                best, bj = d, j
            j += 1
        if best <= args.growth:
            i += 1
            continue
        seg = rows[i:bj + 1]
        counts = {}
        for r in seg:
            c = classify(r, args.few_points, args.weak_ratio)
            counts[c] = counts.get(c, 0) + 1
        verr = max(math.hypot(r["nav_vx"] - r["true_vx"], r["nav_vy"] - r["true_vy"]) for r in seg)
        a, b = rows[i], rows[bj]
        out.append(
            "  %7.1f-%7.1f s  error %.2f -> %.2f m  truth (%.1f, %.1f) -> (%.1f, %.1f)  scans %s  key %d  restarts %d"
            "  max velocity error %.2f m/s"
            % (a["t_s"], b["t_s"], a["nav_err_m"], b["nav_err_m"], a["true_x"], a["true_y"], b["true_x"], b["true_y"],
               "".join("%s%d" % (LETTER[c], counts[c]) for c in CLASSES if c in counts),
               sum(r["key_scan"] for r in seg), sum(r["map_restarted"] for r in seg), verr))
        i = bj + 1
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("traces", nargs="+", help="scan_trace.csv files, or directories searched for them")
    p.add_argument("--few-points", type=float, default=60, help="'few' below this many scored points (60)")
    p.add_argument("--weak-ratio", type=float, default=10, help="'weak' above this axis ratio (10)")
    p.add_argument("--moving-mps", type=float, default=0.3, help="lag measured above this true speed (0.3)")
    p.add_argument("--episodes", action="store_true", help="list the windows where the error grew")
    p.add_argument("--window", type=float, default=15, help="episode window, s (15)")
    p.add_argument("--growth", type=float, default=0.4, help="episode error growth, m (0.4)")
    args = p.parse_args()
    paths = find_traces(args.traces, "scan_trace.csv")
    if not paths:
        print("scan_trace_summary: no scan_trace.csv found", file=sys.stderr)
        return 2
    acc = {c: {"scans": 0, "growth": 0.0, "true_m": 0.0, "match_m": 0.0, "nav_m": 0.0} for c in CLASSES}
    eps = []
    for path in sorted(paths):
        try:
            rows = load_rows(path)
        except (OSError, KeyError, ValueError) as e:
            print("scan_trace_summary: %s: %s" % (path, e), file=sys.stderr)
            return 2
        summarise(rows, args, acc)
        if args.episodes:
            eps.append((path, episodes(rows, args)))
    total = sum(a["scans"] for a in acc.values())
    print("%d trace(s), %d scans" % (len(paths), total))
    print("| class | scans | share | error growth (m) | match / true along travel | filter / true | "
          "true distance (m) |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for c in CLASSES:
        a = acc[c]
        lag = lambda k: "%.3f" % (a[k] / a["true_m"]) if a["true_m"] > 1 else "-"
        print("| %s | %d | %.2f | %.2f | %s | %s | %.0f |" % (c, a["scans"], a["scans"] / max(1, total), a["growth"],
                                                          lag("match_m"), lag("nav_m"), a["true_m"]))
    for path, lines in eps:
        print("%s: %d episode(s)" % (path, len(lines)))
        for line in lines:
            print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())

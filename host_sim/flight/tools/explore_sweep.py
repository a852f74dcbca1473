#!/usr/bin/env python3
"""Sweep of kestrel-sim's explore mission (issue 6, paper 002 / paper 004 comparison).

Runs `kestrel-sim --mission explore` for every world x laser x explorer x seed (at most
--jobs at a time, under nice), keeps each run's outputs in OUT/<world>-<laser>-<explorer>-s<seed>,
and prints four markdown tables: one row per run (with the first contact's place and time);
one row per (world, laser, explorer) with the aggregates the README reports (runs with every
room entered, collisions, median t_all_rooms_s, mean coverage and coverage at fixed times from
coverage_vs_time); per (world, laser, explorer) how many runs never entered each room; and
per (world, laser, explorer) the contacts, split by how far off the estimate was at each
(metrics.json's contacts[].estimate_err_m: within 0.5 m, or more).

Standard library only. Runs already present in OUT (metrics.json exists) are not re-run, so
an interrupted sweep can be resumed and a table re-printed with --seeds and no runs.

With --plot PNG it also draws coverage against time, one panel per world and laser and one
curve per explorer, each the mean over the seeds of the runs' coverage_vs_time.csv (a run that
ended early, by a collision or a finished mission, keeps its last coverage), by calling
kestrel-coverage-plot (--plot-tool, default: beside --sim).

Example:
  host_sim/flight/tools/explore_sweep.py --sim build/host/host_sim/tools/kestrel-sim \\
      --out /tmp/sweep --worlds gt-building iarc-arena --lasers urg04lx utm30lx \\
      --explorers blend wallfollow srt --seeds 1-10 --duration 600 --jobs 2
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor


def parse_seeds(text):
    """1-3,7 -> [1, 2, 3, 7]; ValueError, with the culprit, for anything that names no seed."""
    seeds = []
    for part in text.split(","):
        if not part:
            continue
        a, dash, b = part.partition("-")
        if not a.isdecimal() or (dash and not b.isdecimal()):
            raise ValueError(f"'{part}' is not a seed or a range of seeds like 1-10")
        if dash and int(b) < int(a):
            raise ValueError(f"'{part}' ends before it starts")
        seeds.extend(range(int(a), int(b if dash else a) + 1))
    if not seeds:
        raise ValueError(f"'{text}' names no seed")
    return seeds


def run_dir(out, world, laser, explorer, seed):
    return os.path.join(out, f"{world}-{laser}-{explorer}-s{seed}")


def run_one(args, world, laser, explorer, seed):
    d = run_dir(args.out, world, laser, explorer, seed)
    metrics = os.path.join(d, "metrics.json")
    if not os.path.exists(metrics):
        os.makedirs(d, exist_ok=True)
        cmd = ["nice", "-n", "10", args.sim, "--world", world, "--laser", laser, "--mission", "explore",
               "--explorer", explorer, "--duration", str(args.duration), "--seed", str(seed), "--out", d]
        for kv in args.mission_arg or []:
            cmd += ["--mission-arg", kv]
        if args.config:
            cmd += ["--config", args.config]
        with open(os.path.join(d, "stderr.txt"), "w") as err:
            try:
                subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=err, timeout=args.timeout, check=False)
            except subprocess.TimeoutExpired:
                err.write(f"explore_sweep.py: stopped after --timeout {args.timeout} s\n")
                return None
    try:
        with open(metrics) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def fmt(v, digits=0, pct=False):
    if v is None:
        return "-"
    if pct:
        return f"{100 * v:.{digits}f} %"
    return f"{v:.{digits}f}"


def collisions(m):
    """The count, and where and when the first contact was: 1 at (5.0, 9.0) 1828 s."""
    n = m.get("collisions")
    contacts = m.get("contacts") or []
    if not n or not contacts:
        return f"{n}"
    c = contacts[0]
    return f"{n} at ({c['x_m']:.1f}, {c['y_m']:.1f}) {c['t_s']:.0f} s"


def rooms_missed(ms):
    """How many runs never entered each room (metrics.json room_entry_s), most missed first."""
    missed = {}
    for m in ms:
        for room, t in (m.get("room_entry_s") or {}).items():
            missed[room] = missed.get(room, 0) + (t is None)
    return ", ".join(f"{r} {k}" for r, k in sorted(missed.items(), key=lambda rk: -rk[1]) if k) or "none"


def mmss(s):
    if s is None:
        return "-"
    whole = int(round(s))  # minutes and seconds of the same rounding: 59.6 s is 1:00
    return f"{whole // 60}:{whole % 60:02d}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sim", default="build/host/host_sim/tools/kestrel-sim")
    ap.add_argument("--out", required=True)
    ap.add_argument("--worlds", nargs="+", default=["gt-building", "iarc-arena"])
    ap.add_argument("--lasers", nargs="+", default=["urg04lx", "utm30lx"])
    ap.add_argument("--explorers", nargs="+", default=["blend", "wallfollow", "srt"])
    ap.add_argument("--seeds", default="1-10")
    ap.add_argument("--duration", type=int, default=600)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=int, default=3600, help="wall-clock seconds per run")
    ap.add_argument("--mission-arg", action="append", metavar="KEY=VALUE",
                    help="passed to every run, e.g. keepout=2,8.9,5,9.1 (repeatable)")
    ap.add_argument("--config",
                    help="kestrel-sim --config FILE for every run, e.g. host_sim/sim/configs/perfect_imu.cfg")
    ap.add_argument("--plot", help="coverage-versus-time picture (PNG) of the sweep")
    ap.add_argument("--plot-tool", help="kestrel-coverage-plot (default: beside --sim)")
    args = ap.parse_args()
    try:
        seeds = parse_seeds(args.seeds)
    except ValueError as e:
        ap.error(f"--seeds: {e}")
    combos = [(w, l, e, s) for w in args.worlds for l in args.lasers for e in args.explorers for s in seeds]
    # Without this a missing simulator only shows as "no metrics" rows (nice fails in each run's
    # stderr.txt) and exit status 0. A sweep with every run already done needs no simulator.
    todo = [c for c in combos if not os.path.exists(os.path.join(run_dir(args.out, *c), "metrics.json"))]
    if todo and shutil.which(args.sim) is None:
        ap.error(f"--sim: '{args.sim}' is not an executable (build kestrel-sim, or pass its path)")
    with ThreadPoolExecutor(max_workers=max(1, min(args.jobs, 2))) as pool:
        results = list(pool.map(lambda c: (c, run_one(args, *c)), combos))

    print("| world | laser | explorer | seed | end | coverage | t90 | rooms | all rooms at | collisions | distance m |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for (w, l, e, s), m in results:
        if m is None:
            print(f"| {w} | {l} | {e} | {s} | no metrics | | | | | | |")
            continue
        end = "finished" if m.get("mission_finished") else m.get("end_reason", "?")
        print(f"| {w} | {l} | {e} | {s} | {end} | {fmt(m.get('coverage'), 1, True)} | "
              f"{fmt(m.get('coverage_t90_s'))} | {m.get('rooms_entered')}/{m.get('rooms_total')} | "
              f"{mmss(m.get('t_all_rooms_s'))} | {collisions(m)} | {fmt(m.get('distance_m'), 1)} |")

    print()
    # "All rooms and collision-free" and its best time are paper 002's criterion for one flight
    # (every room, inner one included, without touching anything), counted over the seeds.
    print("| world | laser | explorer | runs | all rooms entered | collision-free | "
          "all rooms and collision-free | finished | median all rooms at | "
          "best all rooms at, collision-free | mean coverage | median t90 s | landed at home | "
          "landed within 0.5 m of take-off | mean position error m | mean velocity error m/s | "
          "estimate runaways per flight hour |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    groups = {}
    for (w, l, e, s), m in results:
        groups.setdefault((w, l, e), []).append(m)
    for (w, l, e), ms in groups.items():
        ms = [m for m in ms if m is not None]
        n = len(ms)
        if n == 0:
            print(f"| {w} | {l} | {e} | 0 | | | | | | | | | | | | | |")
            continue
        all_rooms = [m for m in ms if m.get("rooms_entered") == m.get("rooms_total")]
        t_all = [m["t_all_rooms_s"] for m in ms if m.get("t_all_rooms_s") is not None]
        t90 = [m["coverage_t90_s"] for m in ms if m.get("coverage_t90_s") is not None]
        free = sum(1 for m in ms if m.get("collisions", 1) == 0)
        clean = [m for m in all_rooms if m.get("collisions", 1) == 0]
        t_clean = [m["t_all_rooms_s"] for m in clean if m.get("t_all_rooms_s") is not None]
        fin = sum(1 for m in ms if m.get("mission_finished"))
        cov = statistics.mean(m.get("coverage", 0.0) for m in ms)
        home = sum(1 for m in ms if m.get("returned_home"))
        # By the truth (returned_home is by the estimate): landed, and within 0.5 m of where it
        # took off. '-' when a kept run predates final_from_start_m.
        near = (str(sum(1 for m in ms if m.get("mission_finished") and m["final_from_start_m"] <= 0.5)) + f"/{n}"
                if all(m.get("final_from_start_m") is not None for m in ms) else "-")
        pos = [m["pos_err_mean_m"] for m in ms if m.get("pos_err_mean_m") is not None]
        vel = [m["vel_err_mean_mps"] for m in ms if m.get("vel_err_mean_mps") is not None]
        # Runaways (1 m of error within 10 s, metrics.json) per hour simulated: steadier than
        # the count of flights ending in a contact.
        ran = [(m["estimate_runaways"], m["sim_time_s"]) for m in ms
               if m.get("estimate_runaways") is not None and m.get("sim_time_s")]
        hours = sum(t for _, t in ran) / 3600.0
        if len(ran) < n:
            print(f"{w} {l} {e}: {n - len(ran)} of {n} runs have no estimate_runaways (kept from an older "
                  "kestrel-sim?): the runaway rate is over the others", file=sys.stderr)
        print(f"| {w} | {l} | {e} | {n} | {len(all_rooms)}/{n} | {free}/{n} | {len(clean)}/{n} | {fin}/{n} | "
              f"{mmss(statistics.median(t_all)) if t_all else '-'} | {mmss(min(t_clean)) if t_clean else '-'} | "
              f"{fmt(cov, 1, True)} | "
              f"{fmt(statistics.median(t90)) if t90 else '-'} | {home}/{n} | {near} | "
              f"{fmt(statistics.mean(pos), 2) if pos else '-'} | {fmt(statistics.mean(vel), 3) if vel else '-'} | "
              f"{fmt(sum(r for r, _ in ran) / hours, 2) if hours > 0 else '-'} |")
    print()
    print("| world | laser | explorer | runs that never entered each room |")
    print("|---|---|---|---|")
    for (w, l, e), ms in groups.items():
        ms = [m for m in ms if m is not None]
        print(f"| {w} | {l} | {e} | {rooms_missed(ms)} |")
    print()
    # Whose contacts: with the estimate metres off the vehicle flew where it thought it was
    # clear (the estimator's); with the estimate on the truth, not the estimator's (the
    # guidance's, or a surface the simulated laser does not show, such as a jamb seen edge-on).
    print("| world | laser | explorer | contacts | estimate within 0.5 m | estimate 0.5 m or more off | "
          "estimate's error at each, m |")
    print("|---|---|---|---|---|---|---|")
    for (w, l, e), ms in groups.items():
        contacts = [c for m in ms if m is not None for c in (m.get("contacts") or [])]
        errs = [c.get("estimate_err_m") for c in contacts]
        known = sorted(x for x in errs if x is not None)
        on = sum(1 for x in known if x < 0.5)
        parts = [", ".join(f"{x:.2f}" for x in known)] if known else []
        if len(known) < len(errs):
            parts.append(f"({len(errs) - len(known)} unknown)")
        listed = " ".join(parts) or "-"
        print(f"| {w} | {l} | {e} | {len(contacts)} | {on} | {len(known) - on} | {listed} |")
    missing = sum(1 for _, m in results if m is None)
    if missing:
        print(f"{missing} run(s) left no metrics.json: see stderr.txt in their directories", file=sys.stderr)
    status = plot(args, results) if args.plot else 0
    return 1 if missing else status


def plot_command(args, results):
    """kestrel-coverage-plot's arguments: a panel per (world, laser), a curve per explorer."""
    tool = args.plot_tool or os.path.join(os.path.dirname(args.sim), "kestrel-coverage-plot")
    cmd = [tool, "--out", args.plot, "--end", str(args.duration)]
    panels = {}
    for (w, l, e, s), m in results:
        csv = os.path.join(run_dir(args.out, w, l, e, s), "coverage_vs_time.csv")
        if m is None or not os.path.exists(csv):
            continue
        panels.setdefault((w, l), {}).setdefault(e, []).append((csv, m))
    for (w, l), explorers in panels.items():
        cmd += ["--panel", f"{w}, {l}, seeds {args.seeds}"]
        for e, runs in explorers.items():
            hit = sum(1 for _, m in runs if m.get("collisions", 0) > 0)
            label = f"{e} ({hit}/{len(runs)} collided)"
            cmd += ["--series", label + "=" + ",".join(csv for csv, _ in runs)]
    return cmd


def plot(args, results):
    cmd = plot_command(args, results)
    if "--series" not in cmd:
        print("no coverage_vs_time.csv in the runs: nothing to plot", file=sys.stderr)
        return 1
    done = subprocess.run(cmd, check=False)
    if done.returncode == 0:
        print(f"\ncoverage against time: {args.plot}")
    return done.returncode


if __name__ == "__main__":
    sys.exit(main())

"""What kestrel-sim's trace summaries share: finding the trace files and reading their rows.

Standard library only; imported by scan_trace_summary.py and slam_trace_summary.py, which sit
beside it.
"""
import csv
import os


def find_traces(arguments, name):
    """The files named, and every file called `name` under the directories named."""
    paths = []
    for t in arguments:
        if os.path.isdir(t):
            for root, _, files in os.walk(t):
                if name in files:
                    paths.append(os.path.join(root, name))
        else:
            paths.append(t)
    return paths


def load_rows(path):
    """Every row of a trace as a dict of floats (nan stays nan); ValueError on a bad number."""
    with open(path, newline="") as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]

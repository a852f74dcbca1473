#!/usr/bin/env python3
"""How noisy are a CARMEN log's reference poses, per scan? An independent check for the
kestrel-replay RPE figures (README, scan matcher results).

For every STEP-th pair of consecutive scans, a scan-to-scan point-to-line ICP (robust
weights, shrinking association gate) is started from the matcher's relative pose and its
result compared with the matcher's and with the log's reference. Where the ICP agrees with the
matcher far better than either agrees with the reference, the reference's own error bounds
what the RPE against it can show.

  python3 reference_noise_check.py LOG.gz out/DIR/trajectory_est.tum [STEP]

Needs numpy (Debian: apt-get install python3-numpy). Host-side analysis only.
"""
import gzip
import math
import sys

import numpy as np


def read_log(path):
    scans, refs = [], []
    with gzip.open(path, "rt") as f:
        for line in f:
            if not line.startswith("FLASER "):
                continue
            t = line.split()
            n = int(t[1])
            r = np.array([float(x) for x in t[2:2 + n]])
            v = t[2 + n:2 + n + 7]
            step = math.pi / 180 if n in (180, 181) else math.pi / 360 if n in (360, 361) else math.pi / (n - 1)
            a = -math.pi / 2 + np.arange(n) * step
            ok = (r > 0.05) & (r < 40)
            scans.append(np.c_[r[ok] * np.cos(a[ok]), r[ok] * np.sin(a[ok])])
            refs.append((float(v[6]), float(v[0]), float(v[1]), float(v[2])))
    return scans, refs


def read_tum(path, refs):
    index = {round(r[0], 6): i for i, r in enumerate(refs)}
    est = {}
    for line in open(path):
        if line.startswith("#"):
            continue
        e = [float(x) for x in line.split()]
        est[index[round(e[0], 6)]] = (e[1], e[2], 2 * math.atan2(e[6], e[7]))
    return est


def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return np.array((c * dx + s * dy, -s * dx + c * dy, math.atan2(math.sin(b[2] - a[2]), math.cos(b[2] - a[2]))))


def normals(p):
    nrm = np.zeros_like(p)
    good = np.zeros(len(p), bool)
    for i in range(1, len(p) - 1):
        d = p[i + 1] - p[i - 1]
        length = math.hypot(*d)
        if length < 0.3 and math.hypot(*(p[i] - p[i - 1])) < 0.15 and math.hypot(*(p[i + 1] - p[i])) < 0.15:
            nrm[i] = (-d[1] / length, d[0] / length)
            good[i] = True
    return nrm, good


def icp(a, b, x0, iterations=30):
    """Pose of scan b in scan a's frame, point-to-line, started at x0."""
    na, ga = normals(a)
    a2, na = a[ga], na[ga]
    x = np.array(x0, float)
    used = 0
    for k in range(iterations):
        c, s = math.cos(x[2]), math.sin(x[2])
        q = b @ np.array([[c, s], [-s, c]]) + x[:2]
        d2 = ((q[:, None, :] - a2[None, :, :]) ** 2).sum(-1)
        j = d2.argmin(1)
        dist = np.sqrt(d2[np.arange(len(q)), j])
        m = dist < max(0.05, 0.3 * 0.7 ** k)
        n, qm, pm = na[j[m]], q[m], a2[j[m]]
        r = ((qm - pm) * n).sum(1)
        dq = np.c_[-(qm[:, 1] - x[1]), qm[:, 0] - x[0]]
        jac = np.c_[n[:, 0], n[:, 1], (dq * n).sum(1)]
        w = 1 / np.maximum(np.abs(r), 0.01)
        dx = np.linalg.lstsq(jac * w[:, None], -r * w, rcond=None)[0]
        x = x + dx
        used = int(m.sum())
        if np.abs(dx).max() < 1e-6:
            break
    return x, used


def err(a, b):
    e = between(a, b)
    return math.hypot(e[0], e[1]), abs(math.degrees(e[2]))


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 1
    scans, refs = read_log(sys.argv[1])
    est = read_tum(sys.argv[2], refs)
    step = int(sys.argv[3]) if len(sys.argv) > 3 else 10
    rows = []
    for i in range(1, len(refs), step):
        if i - 1 not in est or i not in est:
            continue
        ref = between(refs[i - 1][1:], refs[i][1:])
        mine = between(est[i - 1], est[i])
        x, used = icp(scans[i - 1], scans[i], mine)
        if used < 0.5 * len(scans[i]):
            continue  # the ICP found too little overlap to judge
        rows.append(err(ref, mine) + err(ref, x) + err(x, mine))
    o = np.array(rows)
    print("pairs %d (every %d-th)" % (len(o), step))
    print("matcher vs reference  %.4f m %.3f deg" % (o[:, 0].mean(), o[:, 1].mean()))
    print("ICP vs reference      %.4f m %.3f deg" % (o[:, 2].mean(), o[:, 3].mean()))
    print("matcher vs ICP        %.4f m %.3f deg (median %.4f m %.3f deg)"
          % (o[:, 4].mean(), o[:, 5].mean(), np.median(o[:, 4]), np.median(o[:, 5])))
    return 0


if __name__ == "__main__":
    sys.exit(main())

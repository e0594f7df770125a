#!/usr/bin/python3
"""Compare two runs' series.csv statistics over a time window: mean, standard deviation and the
standard error of the mean (from block averages, since samples are correlated) of each column.
Used to check that a change to a kernel leaves the physics of a scene unchanged within sampling
noise, e.g. 20,000 steps of the settled drum before and after.

    /usr/bin/python3 tools/compare_series.py runs/before/series.csv runs/after/series.csv --from 0.1
"""
import argparse
import sys

import numpy as np


def load(path):
    data = np.genfromtxt(path, delimiter=",", names=True)
    if data.size < 2:
        sys.exit(f"{path}: fewer than two rows; run longer or sample more often")
    return data


def block_sem(x, blocks=5):
    """Standard error of the mean from the spread of `blocks` consecutive block means."""
    if len(x) < 2 * blocks:
        return float("nan")
    means = [b.mean() for b in np.array_split(x, blocks)]
    return float(np.std(means, ddof=1) / np.sqrt(blocks))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--from", dest="t0", type=float, default=0.0, help="start of the window (s)")
    ap.add_argument("--columns", default="ke_translational,ke_rotational,contacts,wall_contacts,max_overlap_ratio")
    args = ap.parse_args()
    a, b = load(args.a), load(args.b)
    na, nb = int(np.sum(a["time"] >= args.t0)), int(np.sum(b["time"] >= args.t0))
    if min(na, nb) < 2:
        sys.exit(f"window t >= {args.t0} s holds {na} and {nb} samples; lower --from or run longer")
    print(f"window t >= {args.t0} s: {na} and {nb} samples")
    print(f"{'column':20s} {'mean A':>12s} {'mean B':>12s} {'B/A - 1':>9s} {'|dA-B|/sem':>10s}")
    worst = 0.0
    for col in args.columns.split(","):
        xa = a[col][a["time"] >= args.t0]
        xb = b[col][b["time"] >= args.t0]
        ma, mb = xa.mean(), xb.mean()
        sem = np.hypot(block_sem(xa), block_sem(xb))
        z = abs(ma - mb) / sem if sem > 0 else float("nan")
        worst = max(worst, z) if np.isfinite(z) else worst
        rel = mb / ma - 1 if ma != 0 else float("nan")
        print(f"{col:20s} {ma:12.5g} {mb:12.5g} {rel:9.2%} {z:10.2f}")
    print(f"largest difference: {worst:.2f} standard errors")


if __name__ == "__main__":
    main()

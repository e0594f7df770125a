#!/usr/bin/python3
"""Petals inside the bed: how many arms of small grains, separated by streaks of large grains, cross
rings about the drum axis, where the pattern classifier's rim band counts only the lobes that reach
the wall.

    /usr/bin/python3 studies/seed000/petal_arms.py studies/seed000/results/study/half_w0.25/final_state.csv [--out DIR]

A petal pattern whose small-grain arms stop short of the wall reads as few lobes at the rim, while
inside the bed the arms alternate with radial streaks of large grains (the seed's Figs. 5-6 show the
petals this way). Method, on the state's cross-section (drum axis z through the origin, radius R =
0.075 m): rings at r/R = 0.4 ... 0.9, each 6 mm (two large diameters) wide, cut into arcs of 4.5 mm
(1.5 large diameters) at the ring's mid radius; per arc the large grains' share of the solid volume
(a grain counts in the arc holding its centre). Arcs holding less than a quarter of the ring's median
solid volume (above the free surface) are left out, and the ring is read along its longest stretch
of filled arcs. An arm is a run of arcs with a large-grain share below 0.15 that has an arc above
0.5 on both sides before the next such run; runs at the stretch's ends (at the free surface) are not
counted. In a mixed bed an arc of this size holds about five large grains' volume, so an arc without
any is rare: the shared settled and flowing seed-000 states read 0 or 1 arm per ring. Prints a table
per ring and writes DIR/petal_arms.json and DIR/petal_arms.png (the share along each ring).
"""
import argparse
import json
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
from grainflow.outputs import read_csv  # noqa: E402

R = 0.075          # m, the seed's drum radius
WIDTH = 0.006      # m, ring width: two large diameters
ARC = 0.0045       # m, arc length of a bin at the ring's mid radius
POOR = 0.15        # large-grain share of the solid volume below which an arc is part of a small-grain arm
RICH = 0.5         # and above which it is part of a large-grain streak
RINGS = (0.4, 0.5, 0.6, 0.7, 0.8, 0.9)


def ring_profile(d, frac):
    """(angles of the arcs, large share per arc, filled mask) along the ring at r/R = frac."""
    r = np.hypot(d["x"], d["y"])
    rm = frac * R
    inside = np.abs(r - rm) <= WIDTH / 2
    bins = max(8, int(2 * math.pi * rm / ARC))
    theta = np.mod(np.arctan2(d["y"][inside], d["x"][inside]), 2 * math.pi)
    k = np.minimum((theta / (2 * math.pi) * bins).astype(int), bins - 1)
    vol = d["diameter"][inside] ** 3
    large = d["diameter"][inside] > 0.5 * (d["diameter"].min() + d["diameter"].max())
    total = np.bincount(k, weights=vol, minlength=bins)
    big = np.bincount(k, weights=vol * large, minlength=bins)
    filled = total > 0.25 * np.median(total[total > 0]) if np.any(total > 0) else total > 0
    share = np.divide(big, total, out=np.zeros(bins), where=total > 0)
    return (np.arange(bins) + 0.5) / bins * 2 * math.pi, share, filled


def longest_stretch(filled):
    """Indices of the longest circular run of filled arcs, in order along the ring."""
    n = len(filled)
    if filled.all():
        return list(range(n))
    start = int(np.flatnonzero(~filled)[0])
    best, run = [], []
    for s in range(1, n + 1):
        i = (start + s) % n
        if filled[i]:
            run.append(i)
        else:
            if len(run) > len(best):
                best = run
            run = []
    return best if len(best) >= len(run) else run


def count_arms(share_along):
    """Small-grain arms crossing the ring: runs of arcs with a large-grain share below POOR, with
    an arc above RICH on both sides of the run before the next such run (arcs in between, neither
    poor nor rich, neither end nor start one). Runs at the stretch's ends are not counted."""
    marks = [("P" if v < POOR else "R" if v > RICH else "") for v in share_along]
    seq = [m for m in marks if m]
    collapsed = [m for i, m in enumerate(seq) if i == 0 or m != seq[i - 1]]
    return sum(1 for i in range(1, len(collapsed) - 1)
               if collapsed[i] == "P" and collapsed[i - 1] == "R" and collapsed[i + 1] == "R")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("state", type=Path)
    ap.add_argument("--out", type=Path, default=None, help="default: the state's folder")
    a = ap.parse_args()
    out = a.out or a.state.parent
    out.mkdir(parents=True, exist_ok=True)
    d = read_csv(a.state)
    rows = []
    fig, axes = plt.subplots(len(RINGS), 1, figsize=(7, 1.3 * len(RINGS)), sharex=True)
    for ax, frac in zip(axes, RINGS):
        angle, share, filled = ring_profile(d, frac)
        idx = longest_stretch(filled)
        along = share[idx]
        n = count_arms(along)
        rows.append({"r_over_R": frac, "arcs": len(idx), "arc_deg": round(360.0 / len(share), 2),
                     "large_share_mean": round(float(along.mean()), 3) if len(idx) else None, "arms": n})
        ax.plot(np.arange(len(idx)) * 360.0 / len(share), along, lw=0.9, drawstyle="steps-mid")
        ax.axhline(POOR, color="grey", lw=0.6, ls=":")
        ax.axhline(RICH, color="grey", lw=0.6, ls=":")
        ax.set_ylim(0, 1)
        ax.set_ylabel(f"{frac:.1f} R", fontsize=8)
        ax.set_title(f"r = {frac:.1f} R: {n} arms", fontsize=8, loc="right")
    axes[-1].set_xlabel("degrees along the ring, from the free surface on one side to the other")
    fig.suptitle(f"large grains' share of the solid volume along rings: {a.state}", fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "petal_arms.png", dpi=110)
    doc = {"state": str(a.state), "ring_width_m": WIDTH, "arc_m": ARC, "poor_below": POOR, "rich_above": RICH, "rings": rows}
    (out / "petal_arms.json").write_text(json.dumps(doc, indent=1) + "\n")
    print("| r / R | arcs in the bed | arc (deg) | mean large share | arms |")
    print("|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['r_over_R']:.1f} | {r['arcs']} | {r['arc_deg']} | {r['large_share_mean']} | {r['arms']} |")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Does the flow's pulsation set the number of petals? For each of the six cases, the dominant period
of the free-surface angle (series.csv, pulsation.py's spectrum) over windows of the rotation, as an
angle of rotation T_rad, and the number of petals it would lay down if each petal took two pulses of
the surface, one turn holding 2 pi / T_rad pulses: n = pi / T_rad. Beside it the most small-grain arms
crossing one ring inside the bed at 30 rad (petal_arms.json, petal_arms.py).

Why two pulses a petal is a reading, not measured here: in a thin half-filled drum each avalanche of
small grains lays down a petal and, when it reaches the wall, a wave of large grains runs back up the
surface before the next avalanche (Zuriguel, Gray, Peixinho and Mullin, Phys. Rev. E 73, 061302,
2006), two events a petal. The script tests only the count.

    PYTHONPATH=python /usr/bin/python3 studies/seed000/petal_period.py [--out studies/seed000/results/petal_period.json]
"""
import argparse
import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "studies" / "seed000"))
from pulsation import dominant_period  # noqa: E402

from grainflow.resumable import load_series  # noqa: E402

CASES = ("half_w0.25", "half_w0.50", "half_w1.00", "half_w2.00", "quarter_w0.25", "quarter_w0.50")
RUNS = ROOT / "studies" / "seed000" / "results" / "study"
ARMS = ROOT / "studies" / "seed000" / "results" / "petal_arms"
WINDOWS = ((20.0, 30.0), (5.0, 10.0), (10.0, 15.0), (15.0, 20.0), (20.0, 25.0), (25.0, 30.0))  # rad


def window(s, lo, hi):
    """The surface angle's dominant period over lo..hi rad of rotation, in s and in rad, its prominence, and
    pi / period_rad."""
    w = s[(s["angle"] >= lo) & (s["angle"] <= hi)]
    if len(w) < 16:
        return None
    omega = float((w["angle"][-1] - w["angle"][0]) / (w["time"][-1] - w["time"][0]))
    period, prominence, _, _ = dominant_period(w["time"], w["surface_angle"])
    if period is None:
        return None
    return {"from_rad": lo, "to_rad": hi, "period_s": period, "period_rad": period * omega,
            "prominence": prominence, "petals_two_pulses_each": math.pi / (period * omega)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=ROOT / "studies" / "seed000" / "results" / "petal_period.json")
    a = ap.parse_args()
    out = {"command": "studies/seed000/petal_period.py", "signal": "surface_angle", "cases": {}}
    for case in CASES:
        s = load_series(RUNS / case)
        if s is None:
            sys.exit(f"petal_period: no series.csv in {RUNS / case}")
        rings = json.loads((ARMS / case / "petal_arms.json").read_text())["rings"]
        arms = max(r["arms"] for r in rings)
        out["cases"][case] = {"arms_inside_the_bed": arms,
                              "arms_at_r_over_R": [r["r_over_R"] for r in rings if r["arms"] == arms],
                              "windows": [x for x in (window(s, lo, hi) for lo, hi in WINDOWS) if x]}
        first = out["cases"][case]["windows"][0]
        print(f"{case:14s} period {first['period_s']:.3f} s = {first['period_rad']:.3f} rad (prominence "
              f"{first['prominence']:.0f}): pi/T {first['petals_two_pulses_each']:.2f}; arms {arms}")
    a.out.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Turns a mixer state (final_state.csv of a run that ended at time t) back by omega t about the
mixer's axis (x, through the origin), so that it fits the mixer at angle 0: the state the mesh-wall
benchmark loads (scenes/data/mixer_design1_steady.csv).

Usage: state_at_angle_zero.py final_state.csv summary.json out.csv
"""
import csv
import json
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import mixer_scene  # noqa: E402


def main():
    state, summary, out = sys.argv[1:4]
    t = json.loads(pathlib.Path(summary).read_text())["simulated_time"]
    a = -mixer_scene.OMEGA * t
    c, s = math.cos(a), math.sin(a)
    with open(state) as f, open(out, "w", newline="") as g:
        rows = csv.reader(f)
        w = csv.writer(g, lineterminator="\n")
        header = next(rows)
        w.writerow(header)
        col = {k: i for i, k in enumerate(header)}
        for r in rows:
            for y, z in (("y", "z"), ("vy", "vz"), ("wy", "wz")):
                if y in col:
                    yy, zz = float(r[col[y]]), float(r[col[z]])
                    r[col[y]], r[col[z]] = repr(c * yy - s * zz), repr(s * yy + c * zz)
            w.writerow(r)
    print(f"wrote {out}: turned back by {-a:.6g} rad (t = {t:.6g} s)")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""studies/seed002/left_in_hopper.py on a synthetic frame: fixed and removed bodies are not counted,
grains over the 8 m orifice are those with |x| and |z| under 4 m, the lowest of them and the
fastest grain are found."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies" / "seed002"))
from left_in_hopper import left_in_hopper  # noqa: E402

COLUMNS = "id,shape,group,layer,motion,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz".split(",")


def body(i, motion, x, y, z, v=(0.0, 0.0, 0.0)):
    values = [i, "grain", 0, -1, motion, x, y, z, 1, 0, 0, 0, *v, 0, 0, 0]
    return {k: str(val) for k, val in zip(COLUMNS, values)}


rows = [
    body(0, "fixed", 0.0, -0.25, 0.0),          # the bottom: not a grain
    body(1, "removed", 0.0, -5.0, 0.0),         # fell through: not left
    body(2, "moving", 3.9, 0.7, -3.9),          # over the orifice, near its corner
    body(3, "moving", 3.5, 0.5, 0.0, (0.0, 0.3, 0.4)),  # over it, the lowest, speed 0.5
    body(4, "moving", 4.1, 0.2, 0.0),           # just beside it
    body(5, "moving", -6.0, 0.6, 9.0, (0.1, 0.0, 0.0)),
]
got = left_in_hopper(rows, 8.0)
want = {"grains_left": 4, "over_orifice": 2, "lowest_over_orifice_y": 0.5, "max_speed": 0.5,
        "median_speed": 0.1, "faster_than_0.1_m_s": 1, "orifice": 8.0}
failures = [f"{k}: {got[k]}, expected {v}" for k, v in want.items() if abs((got[k] or 0) - v) > 1e-12]
empty = left_in_hopper(rows[:2], 8.0)
if empty["grains_left"] != 0 or empty["over_orifice"] != 0 or empty["max_speed"] is not None:
    failures.append(f"an emptied hopper: {empty}")
if failures:
    print("\n".join(failures))
    sys.exit(1)
print("left_in_hopper: all checks pass")

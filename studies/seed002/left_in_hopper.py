#!/usr/bin/python3
"""What a hopper discharge leaves behind, from one body frame (frames/frame_NNNNNN.csv): how many
grains stay, how many of them have their centres over the orifice and how low the lowest of those
sits, how fast the fastest still moves and how many move faster than 0.1 m/s. A hopper that has stopped with grains over an open
orifice is held by an arch; one whose grains lie only beside it has drained to its crater.

    /usr/bin/python3 studies/seed002/left_in_hopper.py FRAME.csv [--orifice 8.0] [--out FILE.json]

The orifice is a square of side --orifice (m) centred on x = z = 0 in the plane y = 0, as in
scenes/hopper_seed002_shapes.toml. Grains are the frame's moving bodies (fixed and removed bodies
are left out).
"""
import argparse
import json
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))


def _outputs():
    """grainflow.outputs, imported where run files are read: it needs numpy, the tables do not."""
    import grainflow.outputs
    return grainflow.outputs



def left_in_hopper(rows, orifice):
    """The measures of the module docstring from the frame's rows (dicts of its columns)."""
    grains = [r for r in rows if r["motion"] == "moving"]
    half = orifice / 2
    over = [r for r in grains if abs(float(r["x"])) < half and abs(float(r["z"])) < half]
    speed = [math.sqrt(sum(float(r[k]) ** 2 for k in ("vx", "vy", "vz"))) for r in grains]
    return {
        "grains_left": len(grains),
        "over_orifice": len(over),
        "lowest_over_orifice_y": min((float(r["y"]) for r in over), default=None),
        "max_speed": max(speed, default=None),
        "median_speed": sorted(speed)[len(speed) // 2] if speed else None,
        "faster_than_0.1_m_s": sum(1 for v in speed if v > 0.1),
        "orifice": orifice,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("frame", type=Path)
    ap.add_argument("--orifice", type=float, default=8.0, help="side of the square orifice (m)")
    ap.add_argument("--out", type=Path, default=None)
    a = ap.parse_args()
    result = {"frame": str(a.frame)} | left_in_hopper(_outputs().rows_of(_outputs().read_csv(a.frame)), a.orifice)
    text = json.dumps(result, indent=1)
    if a.out:
        a.out.write_text(text + "\n")
    print(text)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""The four composite grains of seed 002's second hopper, as OBJ files of convex parts (one `o`
group per part, the core's vertices; grainflow dilates each core by the scene's radius).

    /usr/bin/python3 scenes/generators/armour_shapes.py [--radius 0.04] [--out scenes/data/shapes]

The seed builds four composites of equal outer size (L = W = H = 1 m) and names two of them: the
hollow block (kong xin ti), which discharged fastest and left the smallest angle of repose, and the
twisted king block (niu wang zi), slowest with the largest. Both are concrete armour units of
breakwaters (the authors' group works on ocean engineering), so the other two are taken from the
same family, between those two in complexity: the tetrapod and the twisted I block (a dolos-like
unit). Dimensions chosen here (the seed gives none): every shape fills a 1 m cube (its outer,
dilated bounding box), bars 0.2 m thick, the hollow block's walls 0.25 m:
  hollow_block   a square tube 1 x 1 x 1 m with a 0.5 x 0.5 m hole along z (4 parts);
  tetrapod       four square frusta from the centre toward alternate corners of the cube, 0.36 m
                 wide at the centre and 0.2 m at the tips (4 parts);
  twisted_i      a 1 m shaft along x with a 1 m fluke at each end, along y at one end and along z at
                 the other (3 parts);
  twisted_king   a 1 m stem along y with three 1 m bars across it, the top one along x, the bottom
                 one along z and the middle one at 45 degrees between them (4 parts).
Each part's core is its outer solid moved in by r on every face, so the dilated part is the outer
solid with rounded edges.
"""
import argparse
import math
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
BAR = 0.2  # m
WALL = 0.25  # m


def box(lo, hi, r, rotation=None):
    """The 8 core vertices of the outer box [lo, hi] moved in by r, optionally turned about the origin."""
    lo, hi = np.array(lo, float) + r, np.array(hi, float) - r
    v = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
    return v if rotation is None else v @ rotation.T


def about_y(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def frustum(axis, base_half, tip_half, length, r):
    """A square frustum from the origin along the unit `axis`: a square of half width base_half at
    the origin and tip_half at `length`, moved in by r (approximately, on its slanted faces)."""
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    u = np.cross(axis, [0.0, 0.0, 1.0] if abs(axis[2]) < 0.9 else [1.0, 0.0, 0.0])
    u /= np.linalg.norm(u)
    w = np.cross(axis, u)
    pts = []
    for d, h in ((r, base_half - r), (length - r, tip_half - r)):
        for a in (-1, 1):
            for b in (-1, 1):
                pts.append(d * axis + h * (a * u + b * w))
    return np.array(pts)


def hollow_block(r):
    h, t = 0.5, WALL
    return [box([-h, -h, -h], [-h + t, h, h], r), box([h - t, -h, -h], [h, h, h], r),
            box([-h + t, -h, -h], [h - t, -h + t, h], r), box([-h + t, h - t, -h], [h - t, h, h], r)]


def tetrapod(r):
    corners = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]
    return [frustum(c, 0.18, 0.10, 0.62, r) for c in corners]


def twisted_i(r):
    h, b = 0.5, BAR / 2
    return [box([-h, -b, -b], [h, b, b], r), box([-h, -h, -b], [-h + BAR, h, b], r),
            box([h - BAR, -b, -h], [h, b, h], r)]


def twisted_king(r):
    h, b = 0.5, BAR / 2
    return [box([-b, -h, -b], [b, h, b], r), box([-h, h - BAR, -b], [h, h, b], r),
            box([-h, -b, -b], [h, b, b], r, about_y(math.pi / 4)), box([-b, -h, -h], [b, -h + BAR, h], r)]


SHAPES = {"hollow_block": hollow_block, "tetrapod": tetrapod, "twisted_i": twisted_i, "twisted_king": twisted_king}


def fit_unit_cube(parts, r):
    """Scales and centres the cores so that the dilated shape's bounding box is the 1 m cube."""
    allv = np.vstack(parts)
    lo, hi = allv.min(axis=0) - r, allv.max(axis=0) + r
    centre = 0.5 * (lo + hi)
    # The dilation stays r: scale the cores about the centre so each axis spans 1 - 2 r.
    scale = (1.0 - 2 * r) / (hi - lo - 2 * r)
    return [(p - centre) * scale for p in parts]


def write_obj(path, name, parts):
    lines = [f"# {name}: {len(parts)} convex cores of seed 002's four-shape hopper "
             "(scenes/generators/armour_shapes.py); dilated by the scene's radius"]
    for k, p in enumerate(parts):
        lines.append(f"o part{k}")
        lines += [f"v {x:.9f} {y:.9f} {z:.9f}" for x, y, z in p]
    path.write_text("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--radius", type=float, default=0.04, help="m, the dilation the scene gives (cores inset by it)")
    ap.add_argument("--out", type=Path, default=REPO / "scenes" / "data" / "shapes")
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    for name, build in SHAPES.items():
        parts = fit_unit_cube(build(a.radius), a.radius)
        write_obj(a.out / f"{name}.obj", name, parts)
        print(f"{name}: {len(parts)} parts -> {a.out / (name + '.obj')}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Writes the fixed packed bed of scenes/liquid/packed_bed.toml: 2 mm spheres on a body-centred cubic
lattice of cell a = 2.4 mm (solid fraction 2 (pi/6) d^3 / a^3 = 0.606, liquid fraction 0.394) filling a
column of 12 x 12 mm cross-section (y, z) and 12 mm periodic length (x). The lattice runs on through the
column's walls: every site whose grain reaches the liquid nodes within the smoothing radius h is kept, so
the liquid fraction at every liquid node is the unbounded lattice's, walls or not.

    /usr/bin/python3 scenes/generators/bcc_bed.py scenes/data/packed_bed_bcc.csv
"""
import sys

D = 2.0e-3      # m, grain diameter
A = 2.4e-3      # m, lattice cell
LX = 12.0e-3    # m, periodic length (5 cells, 16 l0)
L = 12.0e-3     # m, column side (16 l0)
L0 = 0.75e-3    # m, the liquid's node spacing
H = 3.0e-3      # m, smoothing radius (1.5 d, 4 l0)


def reaches_liquid(y, z):
    """Whether a grain at (y, z) has a liquid node (at l0/2 .. L - l0/2) within h."""
    lo, hi = 0.5 * L0, L - 0.5 * L0
    dy = max(lo - y, 0.0, y - hi)
    dz = max(lo - z, 0.0, z - hi)
    return dy * dy + dz * dz < H * H


def sites():
    cells = round(LX / A)
    out = []
    for shift in (0.0, 0.5):  # corners, then body centres
        for i in range(cells):
            x = (i + 0.25 + shift) * A
            for j in range(-2, round(L / A) + 3):
                for k in range(-2, round(L / A) + 3):
                    y, z = (j + shift) * A, (k + shift) * A
                    if reaches_liquid(y, z):
                        out.append((x, y, z))
    return out


def main():
    rows = sites()
    with open(sys.argv[1], "w") as f:
        f.write("id,type,diameter,x,y,z\n")
        for n, (x, y, z) in enumerate(rows):
            f.write(f"{n},1,{D!r},{x!r},{y!r},{z!r}\n")
    print(f"{len(rows)} grains")


if __name__ == "__main__":
    main()

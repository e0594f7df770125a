#!/usr/bin/env python3
"""How hollow each letter grain is: its face area against the area of its convex hull.

Seed 002 explains its packing order by the letters' hollows: O packs densest, A and C loosest
"because their hollow parts are larger" and interlock with more neighbours. This measures that
property of the letters as grainflow builds them (the in-plane layout of letter_layout in
systems/bodies/body_shapes.cpp: strokes as rectangles and slanted quadrilaterals of width s across,
A's crossbar at a quarter of the height), for given stroke widths, and sets it beside measured
packing fractions:

  area      the union of the strokes (the face; times the depth W it is the core's volume before
            the edges are rounded), cm^2
  hull      the area of the face's convex hull, cm^2
  hollow    hull - area: the notches and holes another grain could reach into, cm^2
  convexity area / hull (1 for a convex plate)

Areas are counted on a grid of 0.2 mm cells (about 0.3 % of the smallest face), hulls exactly.

  /usr/bin/python3 studies/seed002/letter_convexity.py --strokes 0.015 0.03 0.04 \\
      --packing 0.03=studies/seed002/results/packing/packing.json 0.04=studies/seed002/results/packing/stroke40_dt5/packing.json \\
      --out studies/seed002/results/packing/letter_convexity.json
  /usr/bin/python3 studies/seed002/letter_convexity.py --table studies/seed002/results/packing/letter_convexity.json
"""
import argparse
import json
import math
import sys
from pathlib import Path

LETTERS = "OTZKAC"
CELL = 2e-4  # m


def rect(x0, x1, y0, y1):
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


def slanted(x_left, y_left, x_right, y_right, s):
    """A stroke of width s across, with horizontal ends (body_shapes.cpp: slanted)."""
    X, dy = x_right - x_left, abs(y_right - y_left)
    w = (s * dy * math.sqrt(X * X + dy * dy - s * s) - s * s * X) / (dy * dy - s * s)
    a, b, c, d = (x_left, y_left), (x_left + w, y_left), (x_right, y_right), (x_right - w, y_right)
    return [a, b, c, d] if y_left < y_right else [d, c, b, a]


def layout(letter, L, H, s):
    """The letter's strokes as counter-clockwise quadrilaterals, centred on the origin."""
    if letter == "O":
        return [rect(-L / 2, -L / 2 + s, -H / 2, H / 2), rect(L / 2 - s, L / 2, -H / 2, H / 2),
                rect(-L / 2, L / 2, H / 2 - s, H / 2), rect(-L / 2, L / 2, -H / 2, -H / 2 + s)]
    if letter == "T":
        return [rect(-L / 2, L / 2, H / 2 - s, H / 2), rect(-s / 2, s / 2, -H / 2, H / 2)]
    if letter == "Z":
        return [rect(-L / 2, L / 2, H / 2 - s, H / 2), rect(-L / 2, L / 2, -H / 2, -H / 2 + s),
                slanted(-L / 2, -H / 2, L / 2, H / 2, s)]
    if letter == "K":
        return [rect(-L / 2, -L / 2 + s, -H / 2, H / 2), slanted(-L / 2, 0.0, L / 2, H / 2, s),
                slanted(-L / 2, 0.0, L / 2, -H / 2, s)]
    if letter == "A":
        left, right = slanted(-L / 2, -H / 2, s / 2, H / 2, s), slanted(-s / 2, H / 2, L / 2, -H / 2, s)
        w, y = left[1][0] - left[0][0], -H / 4
        bx, by, tx = -L / 2 + w / 2, -H / 2, s / 2 - w / 2
        c = -(bx + (tx - bx) * (y - by) / H)
        return [left, right, rect(-c, c, y - s / 2, y + s / 2)]
    if letter == "C":
        return [rect(-L / 2, -L / 2 + s, -H / 2, H / 2), rect(-L / 2, L / 2, H / 2 - s, H / 2),
                rect(-L / 2, L / 2, -H / 2, -H / 2 + s)]
    raise ValueError(f"no letter {letter!r}: the letters are {LETTERS}")


def hull(points):
    """Convex hull, counter-clockwise (monotone chain)."""
    pts = sorted(set(points))

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def polygon_area(poly):
    return 0.5 * abs(sum(poly[k][0] * poly[(k + 1) % len(poly)][1] - poly[(k + 1) % len(poly)][0] * poly[k][1]
                         for k in range(len(poly))))


def inside(poly, X, Y):
    """Points of the grid inside a convex counter-clockwise polygon."""
    import numpy as np  # here, so that printing a table needs no NumPy
    m = np.ones_like(X, dtype=bool)
    for k in range(len(poly)):
        (x0, y0), (x1, y1) = poly[k], poly[(k + 1) % len(poly)]
        m &= (x1 - x0) * (Y - y0) - (y1 - y0) * (X - x0) >= 0
    return m


def measure(letter, L, H, s):
    import numpy as np
    quads = layout(letter, L, H, s)
    xs = np.arange(-L / 2, L / 2, CELL) + CELL / 2
    ys = np.arange(-H / 2, H / 2, CELL) + CELL / 2
    X, Y = np.meshgrid(xs, ys)
    covered = np.zeros_like(X, dtype=bool)
    for q in quads:
        covered |= inside(q, X, Y)
    area = float(covered.sum()) * CELL * CELL
    h = polygon_area(hull([p for q in quads for p in q]))
    return {"letter": letter, "stroke_m": s, "area_cm2": round(area * 1e4, 2), "hull_cm2": round(h * 1e4, 2),
            "hollow_cm2": round((h - area) * 1e4, 2), "convexity": round(area / h, 4)}


def ranks(values):
    order = sorted(values, key=lambda k: -values[k])
    return {k: order.index(k) + 1 for k in values}


def spearman(a, b):
    ra, rb = ranks(a), ranks(b)
    n = len(a)
    return 1.0 - 6.0 * sum((ra[k] - rb[k]) ** 2 for k in a) / (n * (n * n - 1))


def run(args):
    packing = {}
    for item in args.packing:
        stroke, _, path = item.partition("=")
        doc = json.loads(Path(path).read_text())
        packing[float(stroke)] = {"file": path, "fractions": {r["letter"]: r["packing_fraction"] for r in doc["shapes"]
                                                              if r.get("packing_fraction") is not None}}
    rows, fits = [], []
    for s in args.strokes:
        measured = packing.get(s, {}).get("fractions", {})
        for letter in LETTERS:
            r = measure(letter, args.width, args.height, s)
            r["packing_fraction"] = measured.get(letter)
            rows.append(r)
        if len(measured) == len(LETTERS):
            conv = {r["letter"]: r["convexity"] for r in rows if r["stroke_m"] == s}
            fits.append({"stroke_m": s, "packing_file": packing[s]["file"],
                         "spearman_convexity_packing": round(spearman(conv, measured), 3)})
    doc = {"width_m": args.width, "height_m": args.height, "cell_m": CELL, "rows": rows, "rank_correlation": fits}
    text = json.dumps(doc, indent=1)
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(text + "\n")
    else:
        print(text)


def table(path):
    doc = json.loads(Path(path).read_text())
    strokes = sorted({r["stroke_m"] for r in doc["rows"]})
    head = "| letter | " + " | ".join(f"{1e3 * s:.0f} mm strokes: area / hull (cm²), convexity, hollow (cm²), packing"
                                      for s in strokes) + " |"
    lines = [head, "|---" * (len(strokes) + 1) + "|"]
    for letter in LETTERS:
        cells = []
        for s in strokes:
            r = next(r for r in doc["rows"] if r["letter"] == letter and r["stroke_m"] == s)
            pf = "—" if r["packing_fraction"] is None else f"{r['packing_fraction']:.3f}"
            cells.append(f"{r['area_cm2']:.1f} / {r['hull_cm2']:.1f}, **{r['convexity']:.3f}**, {r['hollow_cm2']:.1f}, {pf}")
        lines.append(f"| {letter} | " + " | ".join(cells) + " |")
    fits = "; ".join(f"{1e3 * f['stroke_m']:.0f} mm: {f['spearman_convexity_packing']:+.3f}" for f in doc["rank_correlation"])
    lines.append("")
    lines.append(f"Rank correlation (Spearman) of convexity with the packing fraction: {fits}.")
    print("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--strokes", type=float, nargs="*", default=[0.03, 0.04], help="stroke widths, m")
    ap.add_argument("--width", type=float, default=0.100, help="letter width L, m")
    ap.add_argument("--height", type=float, default=0.180, help="letter height H, m")
    ap.add_argument("--packing", nargs="*", default=[], help="STROKE=packing.json of packing.py collect")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--table", help="print the README table of a result file")
    args = ap.parse_args()
    if args.table:
        table(args.table)
        return 0
    try:
        run(args)
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"letter_convexity: {e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

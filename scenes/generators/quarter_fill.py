#!/usr/bin/python3
"""Quarter-fill state for seed 000 from the shared half-fill settled state: the N grains lowest
along gravity (-y), which keeps the random mixture of the settled bed (the seed's quarter fill has
half the grains, 23,554, in the same 1:1 volume ratio; the cut keeps it within sampling noise, and
the tool prints the ratio it got). The cut surface is flat; the scene settles it briefly.

    /usr/bin/python3 scenes/generators/quarter_fill.py scenes/data/drum_settled_47108.csv \
        scenes/data/drum_quarter_23554.csv --count 23554
"""
import argparse
import csv
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("state", help="settled state CSV: id,type,diameter,x,y,z")
    ap.add_argument("out", help="CSV to write (same columns)")
    ap.add_argument("--count", type=int, default=23554, help="grains to keep (default 23554)")
    a = ap.parse_args()
    with open(a.state, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or set(rows[0]) != {"id", "type", "diameter", "x", "y", "z"}:
        sys.exit(f"quarter_fill: {a.state}: expected columns id,type,diameter,x,y,z")
    if not 0 < a.count <= len(rows):
        sys.exit(f"quarter_fill: --count must be in 1..{len(rows)}, got {a.count}")
    # The bottom of each grain, so a large grain counts as low as a small one at the same floor.
    rows.sort(key=lambda r: float(r["y"]) - 0.5 * float(r["diameter"]))
    kept = sorted(rows[: a.count], key=lambda r: int(r["id"]))
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["id", "type", "diameter", "x", "y", "z"], lineterminator="\n")
        w.writeheader()
        w.writerows(kept)
    vol = {}
    for r in kept:
        vol[r["type"]] = vol.get(r["type"], 0.0) + float(r["diameter"]) ** 3
    counts = {t: sum(1 for r in kept if r["type"] == t) for t in sorted(vol)}
    ratio = " : ".join(f"{vol[t] / min(vol.values()):.3f}" for t in sorted(vol))
    print(f"{a.out}: {len(kept)} grains, counts by type {counts}, volume ratio {ratio}")


if __name__ == "__main__":
    main()

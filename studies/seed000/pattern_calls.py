#!/usr/bin/python3
"""How the drum's pattern classifier called a run's series rows, in bins of rotation: the rows
called moon, petals and undecided (the `pattern` column: 0, 1, -1), the mean petal count of the rows
called petals and the median contrast, from series.csv.

    /usr/bin/python3 studies/seed000/pattern_calls.py studies/seed000/results/study/half_w0.25 [--from 16] [--bin 0.25] [--out FILE.csv]

A single series row is one state, and the classifier's verdict near a threshold flickers from row
to row; the bins show when a verdict has settled. Prints the table and writes it as CSV to FILE.
"""
import argparse
import csv
import math
import sys
from pathlib import Path

import numpy as np

from grainflow.resumable import load_series  # noqa: E402

COLUMNS = ("from_rad", "to_rad", "rows", "moon", "petals", "undecided", "mean_petal_count", "median_contrast")


def calls(series, start, width):
    """One dict per bin of `width` rad from `start` that holds rows (as many bins as rows at most)."""
    angle = series["angle"]
    pattern = series["pattern"].astype(int)
    rows = np.flatnonzero(np.isfinite(angle) & (angle >= start))
    index = np.floor((angle[rows] - start) / width)
    order = np.argsort(index, kind="stable")
    bins, counts = np.unique(index, return_counts=True)
    out = []
    for k, members in zip(bins, np.split(rows[order], np.cumsum(counts)[:-1])):
        p = pattern[members]
        petal_counts = series["petals"][members][p == 1]
        out.append({
            "from_rad": round(start + k * width, 6), "to_rad": round(start + (k + 1) * width, 6), "rows": len(members),
            "moon": int((p == 0).sum()), "petals": int((p == 1).sum()), "undecided": int((p == -1).sum()),
            "mean_petal_count": float(petal_counts.mean()) if len(petal_counts) else math.nan,
            "median_contrast": float(np.median(series["pattern_contrast"][members])),
        })
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", type=Path, help="a run folder with series.csv")
    ap.add_argument("--from", dest="start", type=float, default=0.0, help="first bin's start (rad)")
    ap.add_argument("--bin", type=float, default=0.25, help="bin width (rad)")
    ap.add_argument("--out", type=Path, help="CSV to write")
    a = ap.parse_args()
    if not (math.isfinite(a.bin) and a.bin > 0 and math.isfinite(a.start)):
        sys.exit("pattern_calls.py: --bin must be a positive number of rad and --from a finite angle, e.g. --from 16 --bin 0.25")
    series = load_series(a.run)
    if series is None:
        sys.exit(f"pattern_calls.py: {a.run}/series.csv is missing or empty: give a drum run's folder")
    missing = [c for c in ("angle", "pattern", "petals", "pattern_contrast") if c not in series.dtype.names]
    if missing:
        sys.exit(f"pattern_calls.py: {a.run}/series.csv has no column {', '.join(missing)}: "
                 "only drum runs with two species are classified")
    rows = calls(series, a.start, a.bin)
    print(",".join(COLUMNS))
    for r in rows:
        print(",".join(f"{r[c]:.3f}" if isinstance(r[c], float) else str(r[c]) for c in COLUMNS))
    if a.out:
        a.out.parent.mkdir(parents=True, exist_ok=True)
        with a.out.open("w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=COLUMNS)
            w.writeheader()
            w.writerows(rows)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""The kinetic energy of each letter's pour after a time, from its series.csv: whether a bed that
passed the settling criterion stays quiet or bursts (grains rocking unstably).

    /usr/bin/python3 studies/seed002/kinetic_after.py runs/seed002_packing_mu0.1 --from 2.0 --out FILE.csv

RUNS holds one folder per letter (studies/seed002/packing.py --runs). Per letter: the energy
(translational + rotational, J) at the first row at or after --from, the largest after it and when,
and the last row's.
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from grainflow.outputs import Run  # noqa: E402


def letter_row(folder, start):
    s = Run(folder).series
    after = s["time"] >= start - 1e-9
    if not after.any():
        return None
    t = s["time"][after]
    ke = (s["ke_translational"] + s["ke_rotational"])[after]
    top = int(ke.argmax())
    return {"ke_at_start_J": float(ke[0]), "max_ke_after_J": float(ke[top]), "time_of_max_s": float(t[top]),
            "ke_last_J": float(ke[-1]), "last_s": float(t[-1])}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs")
    ap.add_argument("--from", dest="start", type=float, default=2.0, help="s")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    out = []
    for letter in "OTZKAC":
        folder = os.path.join(a.runs, letter)
        if os.path.exists(os.path.join(folder, "series.csv")):
            r = letter_row(folder, a.start)
            if r:
                out.append({"letter": letter, "from_s": a.start} | r)
    if not out:
        sys.exit(f"{a.runs}: no letter folder with a series.csv reaching {a.start} s")
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(out[0]))
        w.writeheader()
        w.writerows(out)
    for r in out:
        print(r)


if __name__ == "__main__":
    main()

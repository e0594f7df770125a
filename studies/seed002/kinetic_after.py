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


def letter_row(series, start):
    with open(series, newline="") as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    after = [r for r in rows if r["time"] >= start - 1e-9]
    if not after:
        return None
    ke = [r["ke_translational"] + r["ke_rotational"] for r in after]
    top = max(range(len(ke)), key=ke.__getitem__)
    return {"ke_at_start_J": ke[0], "max_ke_after_J": ke[top], "time_of_max_s": after[top]["time"],
            "ke_last_J": ke[-1], "last_s": after[-1]["time"]}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs")
    ap.add_argument("--from", dest="start", type=float, default=2.0, help="s")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    out = []
    for letter in "OTZKAC":
        path = os.path.join(a.runs, letter, "series.csv")
        if os.path.exists(path):
            r = letter_row(path, a.start)
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

#!/usr/bin/python3
"""Surge-front error of a dam-break run against the experiments in studies/seed003/results/dam_break_experiments.csv.

usage: front_error.py RUN_DIR [a_m]   (a: the column width, default 0.146 m)
Prints, per experimental point with Z/a < 3.9 (before the front meets the far wall at Z/a = 4), our Z/a
interpolated at the same T = t sqrt(2 g / a) and the relative difference, then the mean and max per source.
"""
import csv
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
EXP = os.path.join(HERE, "results", "dam_break_experiments.csv")
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))


def _outputs():
    """grainflow.outputs, imported where run files are read: it needs numpy, the tables do not."""
    import grainflow.outputs
    return grainflow.outputs



def experiments():
    with open(EXP) as f:
        rows = [l for l in f if not l.startswith("#")]
    return [(r["source"], float(r["T"]), float(r["Z_over_a"])) for r in csv.DictReader(rows)]


def front_curve(series, a, g=9.81):
    """(T, Z/a) of a series {column: array}: T = t sqrt(2 g / a), Z the surge front."""
    T = [float(t) * math.sqrt(2 * g / a) for t in series["time"]]
    Z = [float(z) / a for z in series["surge_front"]]
    return T, Z


def front_series(run_dir, a, g=9.81):
    return front_curve(_outputs().Run(run_dir).series, a, g)


def series_rows(run_dir):
    """A run's series.csv as a list of rows, each {column: float}."""
    return _outputs().rows_of(_outputs().Run(run_dir).series)


def interp(T, Z, t):
    for i in range(1, len(T)):
        if T[i] >= t:
            f = (t - T[i - 1]) / (T[i] - T[i - 1])
            return Z[i - 1] + f * (Z[i] - Z[i - 1])
    return float("nan")


def errors(run_dir, a=0.146):
    T, Z = front_series(run_dir, a)
    out = {}
    for src, t, z in experiments():
        if z >= 3.9 or t > T[-1]:
            continue
        out.setdefault(src, []).append((t, z, interp(T, Z, t)))
    return out


def main():
    run_dir = sys.argv[1]
    a = float(sys.argv[2]) if len(sys.argv) > 2 else 0.146
    for src, pts in errors(run_dir, a).items():
        rel = [(ours - z) / z for _, z, ours in pts]
        for (t, z, ours), r in zip(pts, rel):
            print(f"{src:22s} T={t:5.3f} exp Z/a={z:5.3f} ours={ours:5.3f} {100 * r:+6.1f} %")
        print(f"{src:22s} mean {100 * sum(rel) / len(rel):+6.1f} %  max |err| {100 * max(abs(r) for r in rel):5.1f} %")


if __name__ == "__main__":
    main()

"""The last rows of two series.csv files agree: the same time and counts, the energies within a
relative bound. Used by checkpoint_resume.cmake for a run resumed on another number of ranks.

    python3 compare_series_end.py REFERENCE OTHER RELATIVE_BOUND
"""
import csv
import sys


def last_row(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    return rows[-1]


def main():
    ref, other, bound = last_row(sys.argv[1]), last_row(sys.argv[2]), float(sys.argv[3])
    bad = [k for k in ("time", "contacts", "wall_contacts") if ref[k] != other[k]]
    for k in ("ke_translational", "ke_rotational"):
        a, b = float(ref[k]), float(other[k])
        if abs(a - b) > bound * abs(a):
            bad.append(f"{k} {b!r} against {a!r}")
    if bad:
        sys.exit(f"{sys.argv[2]}'s last row differs from {sys.argv[1]}'s: " + "; ".join(bad))
    print(f"{sys.argv[2]}: last row agrees within {bound:g}")


if __name__ == "__main__":
    main()

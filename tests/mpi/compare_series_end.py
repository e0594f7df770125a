"""The last rows of two series.csv files agree: the same time and counts, the energies within a
relative bound; or of two walls.csv files: the same time, each force, torque and power within the
bound times the largest of its kind in the reference row (a wall's small components are sums of
larger ones that cancel). Used by checkpoint_resume.cmake for a run resumed on another number of ranks.

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


def kind(column):
    """force, torque or power: the part of a walls.csv column's name after its wall's."""
    return column.rsplit(".", 1)[-1][0]


def wall_differences(ref, other, bound):
    scale = {}
    for k, v in ref.items():
        if k != "time":
            scale[kind(k)] = max(scale.get(kind(k), 0.0), abs(float(v)))
    bad = []
    for k in ref:
        if k == "time":
            continue
        a, b = float(ref[k]), float(other[k])
        if abs(a - b) > bound * scale[kind(k)]:
            bad.append(f"{k} {b!r} against {a!r}")
    return bad


def main():
    ref, other, bound = last_row(sys.argv[1]), last_row(sys.argv[2]), float(sys.argv[3])
    if ref.keys() != other.keys():
        sys.exit(f"{sys.argv[2]} has other columns than {sys.argv[1]}")
    if "ke_translational" not in ref:
        bad = ([] if ref["time"] == other["time"] else ["time"]) + wall_differences(ref, other, bound)
        if bad:
            sys.exit(f"{sys.argv[2]}'s last row differs from {sys.argv[1]}'s: " + "; ".join(bad))
        print(f"{sys.argv[2]}: last row agrees within {bound:g}")
        return
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

"""Checks of the runs with feeds and outlets made by rank_flow.cmake.

    python3 rank_flow_check.py same REFERENCE.csv OTHER.csv RELATIVE_BOUND
        the same header and rows, every value within the relative bound (nan only against nan)
    python3 rank_flow_check.py conserved RUN_FOLDER FILL_GRAINS
        every grain accounted for once: the fill's ids 0..FILL_GRAINS-1 and the fed ones after them
        are either in final_state.csv or in residence.csv, never both, never twice; residence.csv has
        a row for each grain the summary counts out, no entry time for a grain of the fill and
        exit >= entry for a fed one; the series' last row holds the final state's grain count
"""
import csv
import json
import math
import os
import sys


def rows(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


def same(ref_path, other_path, bound):
    ref, other = rows(ref_path), rows(other_path)
    if ref[0] != other[0]:
        sys.exit(f"{other_path}: header {other[0]} against {ref[0]}")
    if len(ref) != len(other):
        sys.exit(f"{other_path}: {len(other) - 1} rows against {len(ref) - 1}")
    for n, (a_row, b_row) in enumerate(zip(ref[1:], other[1:]), start=1):
        for key, a, b in zip(ref[0], a_row, b_row):
            x, y = float(a), float(b)
            if math.isnan(x) or math.isnan(y):
                ok = math.isnan(x) and math.isnan(y)
            else:
                ok = abs(x - y) <= bound * max(abs(x), abs(y))
            if not ok:
                sys.exit(f"{other_path}: row {n}, {key} = {b} against {a} (bound {bound:g} relative)")
    print(f"{other_path}: {len(ref) - 1} rows agree within {bound:g}")


def conserved(run, fill):
    flow = json.load(open(os.path.join(run, "summary.json")))["flow"]
    final = [int(r[0]) for r in rows(os.path.join(run, "final_state.csv"))[1:]]
    out = rows(os.path.join(run, "residence.csv"))
    head, out = out[0], out[1:]
    col = {k: head.index(k) for k in ("id", "entry_time", "exit_time")}
    left = [int(float(r[col["id"]])) for r in out]
    bad = []
    if len(out) != flow["discharged"]:
        bad.append(f"{len(out)} residence rows, the summary counts {flow['discharged']} out")
    if len(set(left)) != len(left):
        bad.append("a grain counted out twice")
    if len(set(final)) != len(final):
        bad.append("an id twice in the final state")
    if set(final) & set(left):
        bad.append(f"grains both held and counted out: {sorted(set(final) & set(left))[:5]}")
    every = set(range(fill + flow["fed_grains"]))
    if set(final) | set(left) != every:
        missing = sorted(every - set(final) - set(left))[:5]
        extra = sorted((set(final) | set(left)) - every)[:5]
        bad.append(f"ids missing {missing}, ids not handed out {extra}")
    for r in out:
        i, entry, exit_ = int(float(r[col["id"]])), float(r[col["entry_time"]]), float(r[col["exit_time"]])
        if (i < fill) != math.isnan(entry) or (i >= fill and not exit_ >= entry):
            bad.append(f"grain {i}: entry {entry}, exit {exit_}")
            break
    series = rows(os.path.join(run, "series.csv"))
    if int(float(series[-1][series[0].index("grains")])) != len(final):
        bad.append(f"series' last row holds {series[-1][series[0].index('grains')]} grains, the final state {len(final)}")
    if bad:
        sys.exit(f"{run}: " + "; ".join(bad))
    print(f"{run}: {fill} + {flow['fed_grains']} fed = {len(final)} held + {len(left)} counted out")


def main():
    if sys.argv[1] == "same":
        same(sys.argv[2], sys.argv[3], float(sys.argv[4]))
    elif sys.argv[1] == "conserved":
        conserved(sys.argv[2], int(sys.argv[3]))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()

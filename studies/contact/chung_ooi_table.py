#!/usr/bin/python3
"""The README's Chung & Ooi table from the results file the Hertz-Mindlin tests write.

    GRAINFLOW_RESULTS=studies/contact/results ./build/tests/hertz_mindlin_test   # writes studies/contact/results/chung_ooi.csv
    /usr/bin/python3 studies/contact/chung_ooi_table.py studies/contact/results/chung_ooi.csv
"""
import csv
import sys


def main(path):
    print("| test | quantity | reference | grainflow | error |")
    print("|---|---|---|---|---|")
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            ref, ours, err = float(row["reference"]), float(row["grainflow"]), float(row["relative_error"])
            print(f"| {row['test']} | {row['quantity']} | {ref:.4g} | {ours:.5g} | {100 * err:+.3f} % |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "studies/contact/results/chung_ooi.csv")

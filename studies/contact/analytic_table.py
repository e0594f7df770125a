#!/usr/bin/python3
"""The README's table "Contact physics against analytic values" from the results file the tests write.

Each row of studies/contact/results/analytic.csv is one figure a test asserts on, recorded where it asserts
(gf::test::record_analytic in tests/test_support.hpp): the closed form, its value and the engine's
where the check compares values, the error the test compares with its tolerance, and that tolerance.
Regenerate the file from the repository root, after building the tests in ./build:

    rm -f studies/contact/results/analytic.csv && for t in pair_contact_test wall_contact_test integrate_test linear_spring_dashpot_test; do GRAINFLOW_RESULTS=studies/contact/results ./build/tests/$t || break; done

and print the table with

    /usr/bin/python3 studies/contact/analytic_table.py [studies/contact/results/analytic.csv]
"""
import csv
import math
import sys

UNIT = {"relative %": " %", "relative": "", "absolute": ""}


def cell(text):
    return text.replace("|", "\\|")


def number(text, digits):
    """A recorded number with `digits` significant digits; a dash where none was recorded."""
    if text == "":
        return "—"
    v = float(text)
    return "0" if v == 0 else f"{v:.{digits}g}"


def main(path):
    print("| case | quantity | closed form | reference | ours | error | tolerance |")
    print("|---|---|---|---|---|---|---|")
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            kind = row["error_kind"]
            if kind not in UNIT:
                sys.exit(f"{path}: unknown error_kind '{kind}'")
            err, tol = float(row["error"]), float(row["tolerance"])
            if not math.isfinite(err) or not abs(err) <= tol:
                sys.exit(f"{path}: '{row['case']}', {row['quantity']}: error {err} outside its tolerance {tol}")
            unit = UNIT[kind]
            print(f"| {cell(row['case'])} | {cell(row['quantity'])} | {cell(row['closed_form'])} | "
                  f"{number(row['reference'], 5)} | {number(row['measured'], 5)} | "
                  f"{number(row['error'], 3)}{unit} | {number(row['tolerance'], 2)}{unit} |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "studies/contact/results/analytic.csv")

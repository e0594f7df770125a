#!/usr/bin/python3
"""The README's liquid validation table from the results file the liquid tests write.

Each row of studies/seed003/results/validation.csv is one figure a liquid test measures, recorded where it checks it
(gf::test::record_liquid in tests/mps_support.hpp): the quantity and its unit, the reference (name and value,
where there is one), ours, the signed relative error in percent, the test's bound in words, and what the run
cost: steps, fluid nodes, wall and dummy nodes, simulated time and the wall time of the stepping. A test run
again appends its figures again; the last row of each (test, case, quantity, reference) is the one shown.
Regenerate the file from the repository root, after building the tests in ./build:

    rm -f studies/seed003/results/validation.csv && for t in mps_kernel_test mps_hydrostatic_test mps_dam_break_test \\
      validation/mps_hydrostatic_validation_test validation/mps_dam_break_validation_test \\
      validation/mps_poiseuille_validation_test validation/mps_pipe_validation_test; do \\
      GRAINFLOW_RESULTS=studies/seed003/results ./build/tests/$(basename $t) || break; done

and print the table with

    /usr/bin/python3 studies/seed003/validation_table.py [studies/seed003/results/validation.csv]
"""
import csv
import math
import sys

# Cases in the table's order: by test program, then in the order the program recorded them.
TESTS = ["mps_kernel_test", "mps_hydrostatic_test", "mps_hydrostatic_validation_test", "mps_dam_break_test",
         "mps_dam_break_validation_test", "mps_poiseuille_validation_test", "mps_pipe_validation_test"]


def cell(text):
    return text.replace("|", "\\|") if text else "—"


def num(text):
    return float(text) if text != "" else math.nan


def sig(v, digits=4):
    """`v` to `digits` significant digits, trailing zeros dropped; in exponent notation (1.2e-3) below 0.01
    and from 1e5 up."""
    if v == 0:
        return "0"
    if abs(v) < 0.01 or abs(v) >= 1e5:
        mantissa, exponent = f"{v:.{digits - 1}e}".split("e")
        return f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"
    return f"{v:.{digits}g}"


def main(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    latest, order = {}, []
    for r in rows:
        if r["test"] not in TESTS:
            sys.exit(f"{path}: test '{r['test']}' is not one of the table's tests (studies/seed003/validation_table.py)")
        key = (r["test"], r["case"], r["quantity"], r["reference_name"])
        if key not in latest:
            order.append(key)
        latest[key] = r
    cases = []
    for key in order:
        if key[:2] not in cases:
            cases.append(key[:2])
    cases.sort(key=lambda c: TESTS.index(c[0]))

    print("| case | quantity | reference | ours | error | test's bound | steps × fluid nodes (+ wall and dummy nodes) "
          "| wall time of the stepping (s, measured with other work running) | test |")
    print("|---|---|---|---|---|---|---|---|---|")
    for test, case in cases:
        first = True
        for key in order:
            if key[:2] != (test, case):
                continue
            r = latest[key]
            unit = f" {r['unit']}" if r["unit"] not in ("", "relative") else ""
            ref, ours, err = num(r["reference"]), num(r["measured"]), num(r["error_pct"])
            reference = r["reference_name"] + (f" = {sig(ref)}{unit}" if not math.isnan(ref) else "")
            if r["unit"] == "relative":  # the figure is itself a relative deviation from the exact value
                shown, error = "—", sig(ours, 2)
            else:
                shown = f"{sig(ours)}{unit}" if not math.isnan(ours) else "—"
                if math.isnan(err):
                    error = "—"
                elif "|" in r["quantity"]:
                    error = f"{err:.1f} %"
                else:
                    error = f"{err:+.2f} %" if abs(err) < 10 else f"{err:+.1f} %"
            cost = wall = name = ""
            if first:
                steps = int(r["steps"])
                if steps > 0:
                    cost = (f"{steps:,} steps ({float(r['simulated_s']):.3g} s) × {int(r['fluid_nodes']):,} "
                            f"(+ {int(r['boundary_nodes']):,})")
                    wall = f"{float(r['wall_s']):.3g}"
                else:
                    cost, wall = "no stepping", "—"
                name = f"`{test}`"
            print(f"| {cell(case) if first else ''} | {cell(r['quantity'])} | {cell(reference)} | {shown} "
                  f"| {error} | {cell(r['bound'])} | {cost} | {wall} | {name} |")
            first = False


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "studies/seed003/results/validation.csv")

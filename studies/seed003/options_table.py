#!/usr/bin/python3
"""The README's table "Options against pressure noise and clustering" from studies/seed003/results/options.csv
(studies/seed003/options.py): one liquid option changed at a time on the 2D tank and the 2D dam break.

usage: options_table.py [OPTIONS_CSV]   (default studies/seed003/results/options.csv)
"""
import csv
import math
import sys


def main(path):
    print("| case | option | status | error | floor pressure RMS (Pa) | wall time (s, 2 cores shared with other work) |")
    print("|---|---|---|---|---|---|")
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            done = r["status"] == "completed"
            status = "completed" if done else f"{r['status']} ({r['failure']})"
            err, rms = float(r["error"]), float(r["pressure_rms_pa"])
            err_s = f"{100 * err:+.2f} %" if done and not math.isnan(err) else "-"
            rms_s = f"{rms:.1f}" if not math.isnan(rms) else "-"
            print(f"| {r['case']} | {r['option']} | {status} | {err_s} | {rms_s} | {float(r['wall_seconds']):.1f} |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "studies/seed003/results/options.csv")

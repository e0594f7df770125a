#!/usr/bin/python3
"""The README's flow-agreement table from docs/liggghts/flow_agreement.csv (tools/liggghts/flow_agreement.py).

    /usr/bin/python3 tools/liggghts/flow_agreement_table.py docs/liggghts/flow_agreement.csv
"""
import csv
import json
import os
import sys


def main(path):
    rows = list(csv.DictReader(open(path)))
    s = json.load(open(os.path.join(os.path.dirname(path), "flow_agreement.json")))
    print("| t (s) | surface angle, LIGGGHTS (°) | grainflow (°) | difference (°) | mean \\|v\\|, LIGGGHTS (m/s) | grainflow (m/s) | difference |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {float(r['t']):.1f} | {float(r['angle_liggghts_deg']):.2f} | {float(r['angle_grainflow_deg']):.2f} | "
              f"{float(r['angle_diff_deg']):+.2f} | {float(r['speed_liggghts']):.4f} | {float(r['speed_grainflow']):.4f} | "
              f"{100 * float(r['speed_diff_rel']):+.1f} % |")
    print(f"| from {s['from_t']} s: largest | | | {s['max_angle_diff_deg']:.2f} (tolerance {s['angle_tolerance_deg']}) | | | "
          f"{100 * s['max_speed_diff_rel']:.1f} % (tolerance {100 * s['speed_tolerance_rel']:.0f} %) |")
    print(f"\nCommit {s['commit']}: {'within both tolerances' if s['pass'] else 'OUTSIDE a tolerance'}.")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/liggghts/flow_agreement.csv")

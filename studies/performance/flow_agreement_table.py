#!/usr/bin/python3
"""The README's flow-agreement tables (studies/performance/flow_agreement.py): one grainflow run against
LIGGGHTS, or (--ensemble) LIGGGHTS against the range of an ensemble of grainflow runs.

    /usr/bin/python3 studies/performance/flow_agreement_table.py studies/performance/results/flow_agreement.csv
    /usr/bin/python3 studies/performance/flow_agreement_table.py --ensemble studies/performance/results/flow_ensemble.csv
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
    print(f"\nCommit {s['commit']}: {'within both tolerances' if s['pass'] else 'OUTSIDE a tolerance'}.", end="")
    sh = s.get("shared_liggghts_state_1.5s")
    if sh:  # another LIGGGHTS run of the same input, measured the same way
        print(f" The shared LIGGGHTS state at 1.5 s (`{sh['file']}`, another LIGGGHTS run of the same input): "
              f"{sh['angle_deg']:.2f}°, {sh['speed']:.4f} m/s.", end="")
    print()


def ensemble(path):
    rows = list(csv.DictReader(open(path)))
    s = json.load(open(os.path.join(os.path.dirname(path), "flow_ensemble.json")))
    print(f"| t (s) | angle, LIGGGHTS (°) | grainflow, {len(s['members'])} runs (°) | mean \\|v\\|, LIGGGHTS (m/s) | "
          f"grainflow, {len(s['members'])} runs (m/s) | grainflow's own spread: angle, speed |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {float(r['t']):.1f} | {float(r['angle_liggghts_deg']):.2f} | {float(r['angle_min_deg']):.2f} – "
              f"{float(r['angle_max_deg']):.2f} | {float(r['speed_liggghts']):.4f} | {float(r['speed_min']):.4f} – "
              f"{float(r['speed_max']):.4f} | {float(r['angle_spread_deg']):.2f}°, {100 * float(r['speed_spread_rel']):.1f} % |")
    print(f"\nFrom {s['from_t']} s LIGGGHTS lies outside grainflow's range by at most {s['max_angle_outside_deg']:.2f}° "
          f"(tolerance {s['angle_tolerance_deg']}°) and {100 * s['max_speed_outside_rel']:.1f} % of the mean speed "
          f"(tolerance {100 * s['speed_tolerance_rel']:.0f} %): {'within both' if s['pass'] else 'OUTSIDE a tolerance'}. "
          f"grainflow's own runs spread by up to {s['max_angle_spread_deg']:.2f}° and "
          f"{100 * s['max_speed_spread_rel']:.1f} %. Members: {', '.join('`' + m + '`' for m in s['members'])}; commit {s['commit']}.")


if __name__ == "__main__":
    if "--ensemble" in sys.argv[1:]:
        ensemble(next((a for a in sys.argv[1:] if not a.startswith("--")), "studies/performance/results/flow_ensemble.csv"))
    else:
        main(sys.argv[1] if len(sys.argv) > 1 else "studies/performance/results/flow_agreement.csv")

#!/usr/bin/python3
"""The README's speed-against-accuracy table from studies/seed000/results/speed_accuracy.json (speed_accuracy.py).

    /usr/bin/python3 studies/seed000/speed_accuracy_table.py studies/seed000/results/speed_accuracy.json
A stopped run shows the step and the overlap its stability message names.
"""
import json
import re
import sys

LABELS = {"dt 1e-5 (seed)": "dt = 1e-5 s (the seed's)", "dt 2e-5": "dt = 2e-5 s", "dt 3e-5": "dt = 3e-5 s",
          "dt 4e-5": "dt = 4e-5 s", "small drum, dt 3e-5": "small drum (2,987 grains), dt = 3e-5 s"}


def row(r):
    label = LABELS.get(r["label"], r["label"])
    frac = f"{r['critical_fraction']:.3f}"
    if r["status"] == "completed":
        rms = r.get("rms_vs_seed_dt")
        rms = "—" if rms is None or "small" in r["label"] else ("0" if rms == 0 else f"{rms:.3f}")
        return (f"| {label} | {frac} | {r['wall_seconds']:.3g} | {r['segregation_index']:.3f} | {rms} "
                f"| {r['max_overlap_ratio']:.3f} |")
    m = re.search(r"by ([0-9.e+-]+) of .* in step (\d+)", r["failure"])
    overlap, step = (m.group(1), m.group(2)) if m else ("?", "?")
    return (f"| {label} | {frac} | {r['wall_seconds']:.2g} (stopped in step {step}, at {r['angle']:.2f} rad) | — "
            f"| unstable | {overlap} (the stopping contact) |")


def main(path):
    print("| run | dt / smallest period | wall time (s) | segregation index at 0.3 rad | RMS from dt = 1e-5 "
          "| largest overlap / d |")
    print("|---|---|---|---|---|---|")
    for r in json.load(open(path)):
        print(row(r))


if __name__ == "__main__":
    main(sys.argv[1])

#!/usr/bin/python3
"""The README's table of the seed's drum runs from a copy of `study.py report`'s table.json.

    /usr/bin/python3 studies/seed000/study.py report     # writes studies/seed000/results/seed_drum_table.json
    /usr/bin/python3 studies/seed000/study_table.py studies/seed000/results/seed_drum_table.json
"""
import json
import sys
from pathlib import Path

ARMS = Path(__file__).resolve().parents[2] / "studies" / "seed000" / "results" / "petal_arms"


def arms(case, angle):
    """Most small-grain arms crossing a ring inside the bed, from petal_arms.py on the final state
    (studies/seed000/results/petal_arms/<case>/), for a case that reached 30 rad."""
    f = ARMS / case / "petal_arms.json"
    if angle < 30 - 1e-9 or not f.is_file():
        return "—"
    rings = json.loads(f.read_text())["rings"]
    best = max(r["arms"] for r in rings)
    at = "/".join(f"{r['r_over_R']:.1f}" for r in rings if r["arms"] == best)
    return f"{best} (at {at} R)"


def main(path):
    rows = json.load(open(path))
    print("| fill | ω (rad/s) | seed at 30 rad | ours (classifier) at the angle reached | rotation reached (rad) | "
          "arms inside the bed (most at a ring) | segregation index | wall time | particle-steps/s (threads) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if not r["ran"]:
            continue
        lobes = ""
        if r.get("ring_lobes"):
            radii = "/".join(f"{x:g}" for x in r["ring_radii"])
            # -1: a ring with too little bed or too few large grains to count (systems/analysis/pattern.hpp)
            counts = "/".join(str(n) if n >= 0 else "—" for n in r["ring_lobes"])
            lobes = f"; lobes crossing {radii} R: {counts}"
        print(f"| {r['fill']} | {r['omega']:.2f} | {r['seed']} | {r['ours']} (contrast {r['contrast']:.2f}{lobes}) | "
              f"{r['angle']:.2f} of 30 | {arms(r['case'], r['angle'])} | {r['segregation_index']:.3f} | {r['wall_seconds'] / 3600:.2f} h | "
              f"{r['particle_steps_per_second']:.3g} ({','.join(map(str, r['threads']))}) |")
    for r in rows:
        if r.get("rerun_angle") is not None:
            print(f"\nThe {r['omega']:.2f} rad/s case runs again from the start, "
                  f"at {r['rerun_angle']:.2f} rad so far; its row is the first run's until the rerun passes it.")
    waiting = [r["seed"] for r in rows if not r["ran"]]
    if waiting:
        print(f"\nNot started yet: {len(waiting)} of the {len(rows)} cases.")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "studies/seed000/results/seed_drum_table.json")

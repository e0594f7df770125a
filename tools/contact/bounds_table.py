#!/usr/bin/python3
"""What the step's parts could give at most, from their measured costs, against what seven times
LIGGGHTS per core needs. Each bound is the share of a one-thread step of the flowing drum that a part
takes, as if a change made it free:
  - a pair-kernel part: the pair kernel's share of the step (docs/bench/drum_time_split_flowing.json)
    times 1 - r, r the per-round median of the kernel's time with the part removed against the
    unchanged kernel (docs/contact/pair_ablation.csv, tools/contact/pair_ablation.py);
  - the law's arithmetic: its cost from a second evaluation (lawtwice, r - 1), of which mixed precision
    could take at most half;
  - the wall springs: 1 - 1/q, q the per-round median of the step rate without them against the
    unchanged build (docs/contact/bench_wall_nosprings.csv, one thread);
  - the neighbour search and the integration: their whole shares of the step.
The needed factor is 7 over the per-round median ratio to LIGGGHTS of each flowing-drum comparison
window (docs/liggghts/comparison_flowing*.log). The bounds are not additive targets: no part can be
made free, and each change measured so far took a few per cent of one of them at most.

    /usr/bin/python3 tools/contact/bounds_table.py
"""
import csv
import json
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "liggghts"))
from comparison_table import parse, round_ratios  # noqa: E402

ABLATION = ROOT / "docs/contact/pair_ablation.csv"
SPLIT = ROOT / "docs/bench/drum_time_split_flowing.json"
WALL = ROOT / "docs/contact/bench_wall_nosprings.csv"
TARGET = 7.0


def ablation_ratios():
    """Per variant, the ratios of its time to the unchanged kernel's in the same round."""
    rounds = {}
    for r in csv.DictReader(ABLATION.open()):
        rounds.setdefault(r["round"], {})[r["variant"]] = float(r["median_ms"])
    out = {}
    for v in rounds.values():
        for name, t in v.items():
            if name != "base" and "base" in v:
                out.setdefault(name, []).append(t / v["base"])
    return out


def wall_ratio():
    runs = {}
    for r in csv.DictReader(WALL.open()):
        if r["threads"] == "1":
            runs.setdefault(r["round"], {})[r["build"]] = float(r["particle_steps_per_s"])
    return statistics.median(v["B"] / v["A"] for v in runs.values() if "A" in v and "B" in v)


def main():
    split = {t["system"]: t["fraction"] for t in json.loads(SPLIT.read_text())["time_per_system"]}
    pair = split["pair_contact"]
    ab = {k: statistics.median(v) for k, v in ablation_ratios().items()}
    rows = [
        ("the overlap test (a float test or cluster-pair tiles)", "`noprefilter`", pair * (1 - ab["noprefilter"])),
        ("the slab sums (another design of the scatter)", "`nosums`", pair * (1 - ab["nosums"])),
        ("six partner gathers (velocity, spin)", "`localpartner`", pair * (1 - ab["localpartner"])),
        ("the law in mixed precision (half its arithmetic)", "`lawtwice`", pair * (ab["lawtwice"] - 1) / 2),
        ("the wall springs (a packed list of wall contacts)", "no wall springs", 1 - 1 / wall_ratio()),
        ("the neighbour search and its rebuilds", "its share", split["broadphase"]),
        ("the integration", "its share", split["integrate_positions"] + split["integrate_velocities"]),
    ]
    print("| part made free | measured by | share of a one-thread step |")
    print("|---|---|---|")
    for what, how, b in rows:
        print(f"| {what} | {how} | {100 * b:.1f} % |")
    need = {1: [], 2: []}
    for log in sorted((ROOT / "docs/liggghts").glob("comparison_flowing*.log")):
        runs = parse(log)[0]
        for n, q in round_ratios(runs).items():
            if q:
                need[n].append(TARGET / statistics.median(q))
    for n in (1, 2):
        print(f"| needed for ×{TARGET:g} LIGGGHTS on {n} thread{'s' if n > 1 else ''}, over the "
              f"{len(need[n])} flowing windows | | the step ×{min(need[n]):.2f}–{max(need[n]):.2f} as fast: "
              f"{100 * (1 - 1 / min(need[n])):.0f}–{100 * (1 - 1 / max(need[n])):.0f} % of it removed |")


if __name__ == "__main__":
    main()

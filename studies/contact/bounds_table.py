#!/usr/bin/python3
"""What the step's parts could give at most, from their measured costs, against what seven times
LIGGGHTS per core needs. Each bound is the share of a one-thread step of the flowing drum that a part
takes, as if a change made it free:
  - a pair-kernel part: the pair kernel's share of the step (studies/performance/results/drum_time_split_flowing.json)
    times 1 - r, r the per-round median of the kernel's time with the part removed against the
    unchanged kernel (studies/contact/results/pair_ablation.csv, studies/contact/pair_ablation.py (a probe that patched the C++ kernel in a scratch tree; removed, kept in the history: git show 984d50cd9d25:tools/contact/pair_ablation.py));
  - the law's arithmetic: its cost from a second evaluation (lawtwice, r - 1), of which mixed precision
    could take at most half;
  - the wall springs: 1 - 1/q, q the per-round median of the step rate without them against the
    unchanged build (studies/contact/results/bench_wall_nosprings.csv, one thread);
  - the neighbour search and the integration: their whole shares of the step;
  - the whole step run over blocks of space that fit the cache: 1 - 1/c, c the one-thread rate of the
    fastest settled layer smaller than the drum against the layer nearest the drum's grain count (within
    20 %) in the same window of studies/performance/bench_scaling.sh, the median over such windows, on the AMD EPYC
    (studies/performance/results/scaling_knee.log) and the Intel Xeon (every studies/performance/results/scaling_*xeon.log). The last row
    counts the flowing windows whose one-thread ratio times the larger c reaches 7.
The needed factor is 7 over the per-round median ratio to LIGGGHTS of each flowing-drum comparison
window (studies/performance/results/comparison_flowing*.log). The bounds are not additive targets: no part can be
made free, and each change measured so far took a few per cent of one of them at most.

    /usr/bin/python3 studies/contact/bounds_table.py
"""
import csv
import json
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "studies" / "performance"))
from comparison_table import parse, round_ratios  # noqa: E402
from scaling_table import one_thread_windows  # noqa: E402

ABLATION = ROOT / "studies/contact/results/pair_ablation.csv"
SPLIT = ROOT / "studies/performance/results/drum_time_split_flowing.json"
WALL = ROOT / "studies/contact/results/bench_wall_nosprings.csv"
TARGET = 7.0
DRUM_GRAINS = 47108
SCALING = {"AMD EPYC": ["studies/performance/results/scaling_knee.log"],
           "Intel Xeon": sorted(str(p) for p in (ROOT / "studies/performance/results").glob("scaling_*xeon.log"))}


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


def cache_gain(logs):
    """Per window, the fastest smaller layer's rate over the rate of the layer nearest the drum's grain
    count (within 20 %): the median and the range over the windows holding both, and how many they are."""
    gains = []
    for w in one_thread_windows([ROOT / log for log in logs]):
        drum = min(w, key=lambda g: abs(g - DRUM_GRAINS))
        smaller = [w[g] for g in w if g < drum]
        if abs(drum - DRUM_GRAINS) < 0.2 * DRUM_GRAINS and smaller:
            gains.append(max(smaller) / w[drum])
    return statistics.median(gains), min(gains), max(gains), len(gains)


def flowing_ratios():
    """Per thread count, the per-round median ratio to LIGGGHTS of each flowing-drum window."""
    out = {1: [], 2: []}
    for log in sorted((ROOT / "studies/performance/results").glob("comparison_flowing*.log")):
        for n, q in round_ratios(parse(log)[0]).items():
            if q:
                out[n].append(statistics.median(q))
    return out


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
    gains = {}
    for cpu, logs in SCALING.items():
        c, lo, hi, n = cache_gain(logs)
        gains[cpu] = c
        rows.append((f"the whole step at the rate of the fastest smaller layer ({cpu}; blocks of space)",
                     f"windows timing a layer within 20 % of the drum's {DRUM_GRAINS:,} grains: {n}, the gain "
                     f"×{c:.2f}" + (f" (×{lo:.2f}–{hi:.2f})" if n > 1 else ""), 1 - 1 / c))
    print("| part made free | measured by | share of a one-thread step |")
    print("|---|---|---|")
    for what, how, b in rows:
        print(f"| {what} | {how} | {100 * b:.1f} % |")
    ratios = flowing_ratios()
    need = {n: [TARGET / q for q in r] for n, r in ratios.items()}
    for n in (1, 2):
        print(f"| needed for ×{TARGET:g} LIGGGHTS on {n} thread{'s' if n > 1 else ''}, over the "
              f"{len(need[n])} flowing windows | | the step ×{min(need[n]):.2f}–{max(need[n]):.2f} as fast: "
              f"{100 * (1 - 1 / min(need[n])):.0f}–{100 * (1 - 1 / max(need[n])):.0f} % of it removed |")
    c = max(gains.values())
    reached = sum(q * c >= TARGET for q in ratios[1])
    print(f"| flowing windows reaching ×{TARGET:g} on 1 thread with the step ×{c:.2f} as fast (the larger cache bound) | | "
          f"{reached} of {len(ratios[1])} (their ratios ×{min(ratios[1]):.2f}–{max(ratios[1]):.2f} would become "
          f"×{c * min(ratios[1]):.2f}–{c * max(ratios[1]):.2f}); the median window, ×{statistics.median(ratios[1]):.2f}, "
          f"would still need the step ×{TARGET / (c * statistics.median(ratios[1])):.2f} as fast besides |")


if __name__ == "__main__":
    main()

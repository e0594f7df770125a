#!/usr/bin/env python3
"""The README's LIGGGHTS comparison table from a log of studies/performance/run_comparison.sh.

    REPEATS=5 studies/performance/run_comparison.sh > studies/performance/results/comparison.log
    /usr/bin/python3 studies/performance/comparison_table.py studies/performance/results/comparison.log

Medians over the rounds, and the per-round ratios grainflow / LIGGGHTS (each round runs both codes
back to back, so its ratio is the least disturbed by the machine's drift): median and range.
"""
import re
import statistics
import sys

ROW = re.compile(r"^(liggghts|grainflow_mpi|grainflow)\s+(\d+)\s+(\d+)\s+([0-9.]+)\s+([0-9.]+)\s+([0-9.eE+-]+)\s+([0-9.eE+-]+|nan)\s+([0-9.]+)(?:\s+(-?\d+))?$")


SKIN = re.compile(r"^# state .*, skin ([0-9.eE+-]+) m,")
CPU = re.compile(r"^# cpu: (.+)$")


def parse(path):
    """The log's rates by (code, threads, round), rebuild counts by code, skin and processor."""
    runs, builds, skin, cpu = {}, {}, None, None
    for line in open(path):
        k = SKIN.match(line.strip())
        if k:
            skin = float(k.group(1))
        c = CPU.match(line.strip())
        if c:
            cpu = c.group(1)
        m = ROW.match(line.strip())
        if m:
            runs[m.group(1), int(m.group(2)), int(m.group(3))] = float(m.group(6))
            if m.group(9) is not None:
                builds.setdefault(m.group(1), set()).add(int(m.group(9)))
    return runs, builds, skin, cpu


def round_ratios(runs):
    """grainflow / LIGGGHTS per round, by thread count (1, 2)."""
    rounds = sorted({k[2] for k in runs})
    return {n: [runs["grainflow", n, r] / runs["liggghts", n, r] for r in rounds
                if ("grainflow", n, r) in runs and ("liggghts", n, r) in runs] for n in (1, 2)}


def main(path):
    runs, builds, skin, cpu = parse(path)
    rounds = sorted({k[2] for k in runs})
    med = {(c, n): statistics.median(runs[c, n, r] for r in rounds if (c, n, r) in runs)
           for c in ("liggghts", "grainflow") for n in (1, 2)}
    ratio = round_ratios(runs)
    print("| code | 1 core | 2 cores | 1 → 2 |")
    print("|---|---|---|---|")
    print(f"| LIGGGHTS 3.8 (mesh drum, `hooke/stiffness`, `epsd` rolling; MPI ranks), median of {len(rounds)} | "
          f"{med['liggghts', 1]:.3g} | {med['liggghts', 2]:.3g} | ×{med['liggghts', 2] / med['liggghts', 1]:.2f} |")
    print(f"| grainflow (analytic drum, seed-000 law; TBB threads), median of {len(rounds)} | "
          f"{med['grainflow', 1]:.3g} | {med['grainflow', 2]:.3g} | ×{med['grainflow', 2] / med['grainflow', 1]:.2f} |")
    cells = [f"**×{statistics.median(ratio[n]):.2f}** (×{min(ratio[n]):.2f}–{max(ratio[n]):.2f})" for n in (1, 2)]
    print(f"| ratio grainflow / LIGGGHTS per round: median (range) | {cells[0]} | {cells[1]} | |")
    mpi = [runs["grainflow_mpi", 2, r] for r in rounds if ("grainflow_mpi", 2, r) in runs]
    if mpi:  # logs of MPI=1 runs: grainflow_mpi on 2 ranks of one thread
        per = [runs["grainflow_mpi", 2, r] / runs["liggghts", 2, r] for r in rounds
               if ("grainflow_mpi", 2, r) in runs and ("liggghts", 2, r) in runs]
        print(f"| grainflow_mpi (the same, domain decomposition; 2 MPI ranks of one thread), median of {len(mpi)} | "
              f"| {statistics.median(mpi):.3g} | ×{statistics.median(mpi) / med['grainflow', 1]:.2f} against 1 thread |")
        print(f"| ratio grainflow_mpi / LIGGGHTS per round, 2 ranks each: median (range) | | "
              f"**×{statistics.median(per):.2f}** (×{min(per):.2f}–{max(per):.2f}) | |")
    if builds:  # neighbour-list rebuilds per run (logs from before the column have none)
        text = "; ".join(f"{'LIGGGHTS' if c == 'liggghts' else c} {'/'.join(map(str, sorted(v)))}"
                         for c, v in sorted(builds.items(), reverse=True))
        print(f"| neighbour-list rebuilds per run | {text} | | |")
    if skin is not None:  # logs from before the SKIN setting ran at the scene's, 0.15 mm
        print(f"| Verlet skin, both codes | {skin * 1e3:g} mm | | |")
    if cpu:  # logs from before the cpu line name the machine in the README's text
        print(f"| processor | {cpu} | | |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "studies/performance/results/comparison.log")

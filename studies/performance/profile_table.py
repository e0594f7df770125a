#!/usr/bin/python3
"""The README's profile table from studies/performance/results/profile_flowing.txt (studies/performance/profile.sh): self time
of the flowing drum's step grouped by the kernel each function belongs to.

    /usr/bin/python3 studies/performance/profile_table.py studies/performance/results/profile_flowing.txt
"""
import sys

# (kernel, test on a perf symbol), first match wins: the specific before the general. TBB prints a
# parallel loop as work_balance / start_for of its body, so a kernel's loops are found by the
# function and lambda they name; the pair kernel's prefilter is lambda #1 of compute_pair_forces.
GROUPS = [
    ("pair contact: slab sums of forces and torques into rows", lambda n: "SlabSums" in n or "evaluate_and_sum" in n),
    ("pair contact: overlap prefilter over list pairs",
     lambda n: "compute_pair_forces<" in n and "double)::{lambda(unsigned long)#1}" in n),
    ("pair contact: compaction of touching pairs into contacts", lambda n: "compact_avx512" in n or "compact_scalar" in n),
    ("pair contact: the law (geometry, springs, forces) per batch of contacts",
     lambda n: "compute_pair_forces<" in n or "evaluate_one" in n),
    ("wall contact", lambda n: "compute_wall_forces" in n or "WallHistory>::permute" in n),
    ("neighbour search (by size class)", lambda n: "PairSearch" in n),
    ("list check past skin/2 (movers)", lambda n: "list_covers_contacts" in n or "needs_rebuild" in n),
    ("neighbour rebuild: sort, list, spring carry",
     lambda n: any(k in n for k in ("rebuild_neighbors", "permute", "collect_active", "CellGrid"))),
    ("integration (kicks, drift)", lambda n: "kick_rows" in n or "kick_pass" in n),
    ("memory fill and copy (libc)", lambda n: any(k in n for k in ("memset", "memmove", "memcpy"))),
]


def group_of(name):
    for label, test in GROUPS:
        if test(name):
            return label
    return None


def main(path):
    header, total, sums, other = [], 0.0, {}, 0.0
    for line in open(path):
        if line.startswith("#"):
            header.append(line[1:].strip())
            continue
        pct, _, name = line.partition(" | ")
        p = float(pct.strip().rstrip("%"))
        total += p
        g = group_of(name)
        if g is None:
            other += p
            continue
        sums[g] = sums.get(g, 0.0) + p
    print("| kernel | share of the cycles |")
    print("|---|---|")
    for g, p in sorted(sums.items(), key=lambda kv: -kv[1]):
        print(f"| {g} | {p:.1f} % |")
    print(f"| other (output, the rest of the top 40) | {other:.1f} % |")
    print(f"\n{header[0] if header else ''}; the top 40 functions cover {total:.1f} % of the samples.")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "studies/performance/results/profile_flowing.txt")

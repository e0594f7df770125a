#!/usr/bin/python3
"""How many neighbour-list pairs a list of each skin holds per touching pair, from a state file:
pairs closer than r_i + r_j + skin for several skins (0 is the touching pairs). A second, tighter
list inside the Verlet list saves the prefilter and compaction of the pairs it leaves out; this
says how many those are.

    /usr/bin/python3 studies/contact/list_shells.py scenes/data/drum_flowing_t1.5s_47108.csv > studies/contact/results/list_shells.json
"""
import json
import sys

import numpy as np

from state_pairs import gaps, read_state

SKINS = [0.0, 0.05e-3, 0.075e-3, 0.1e-3, 0.15e-3]  # m; the drum's skin is 0.15 mm


def main(path):
    p, r = read_state(path)
    count = np.zeros(len(SKINS), dtype=np.int64)
    for gap in gaps(p, r, max(SKINS)):
        for s, skin in enumerate(SKINS):
            count[s] += int(np.sum(gap < skin))
    out = {"state": path, "grains": len(r),
           "shells": [{"skin_m": s, "pairs": int(c), "per_touching_pair": float(c / count[0])}
                      for s, c in zip(SKINS, count)]}
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main(sys.argv[1])

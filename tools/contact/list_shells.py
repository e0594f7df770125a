#!/usr/bin/python3
"""How many neighbour-list pairs a list of each skin holds per touching pair, from a state file:
pairs closer than r_i + r_j + skin for several skins (0 is the touching pairs). A second, tighter
list inside the Verlet list saves the prefilter and compaction of the pairs it leaves out; this
says how many those are.

    /usr/bin/python3 tools/contact/list_shells.py scenes/data/drum_flowing_t1.5s_47108.csv > docs/contact/list_shells.json
"""
import json
import sys
from collections import defaultdict

import numpy as np

SKINS = [0.0, 0.05e-3, 0.075e-3, 0.1e-3, 0.15e-3]  # m; the drum's skin is 0.15 mm


def main(path):
    d = np.genfromtxt(path, delimiter=",", names=True)
    p = np.stack([d["x"], d["y"], d["z"]], 1)
    r = d["diameter"] / 2
    cell = 2 * r.max() + max(SKINS)  # every pair within reach lies in neighbouring cells
    cells = defaultdict(list)
    for i, k in enumerate(map(tuple, np.floor(p / cell).astype(np.int64))):
        cells[k].append(i)
    cells = {k: np.array(v) for k, v in cells.items()}
    count = np.zeros(len(SKINS), dtype=np.int64)
    for k, a in cells.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    b = cells.get((k[0] + dx, k[1] + dy, k[2] + dz))
                    if b is None:
                        continue
                    dist = np.linalg.norm(p[a][:, None, :] - p[b][None, :, :], axis=2)
                    gap = dist - (r[a][:, None] + r[b][None, :])
                    once = a[:, None] < b[None, :]
                    for s, skin in enumerate(SKINS):
                        count[s] += int(np.sum(once & (gap < skin)))
    out = {"state": path, "grains": len(r),
           "shells": [{"skin_m": s, "pairs": int(c), "per_touching_pair": float(c / count[0])}
                      for s, c in zip(SKINS, count)]}
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main(sys.argv[1])

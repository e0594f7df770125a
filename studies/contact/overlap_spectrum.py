#!/usr/bin/python3
"""How deep the contacts of a state are, against the resolution of single precision: a prefilter
that tests overlap in float must hand every pair within its error band of touching to the double
test. For the state's list pairs (within the skin) this gives the quantiles of the overlaps, and the
share of list pairs, and of batches of eight list pairs, inside the band of a float test at
absolute coordinates (half-width 4 * 2^-23 X + 2^-19 (r_i + r_j), X the largest coordinate
magnitude; the test of studies/contact/results/float_prefilter.patch) and of one at coordinates relative to cells of the
list's size (X replaced by the cell size). The batch share assumes pairs independent.

    /usr/bin/python3 studies/contact/overlap_spectrum.py scenes/data/drum_flowing_grainflow_t3.0s_47108.csv > studies/contact/results/overlap_spectrum.json
"""
import json
import sys

import numpy as np

from state_pairs import gaps, read_state

SKIN = 0.15e-3  # m, the drum scenes' skin
BATCH = 8       # list pairs per prefilter batch (AVX-512 doubles)


def main(path):
    p, r = read_state(path)
    g = np.concatenate(list(gaps(p, r, SKIN)))
    rs = 2 * np.median(r)  # r_i + r_j of a typical pair, for the relative part of the band
    x_abs = float(np.abs(p).max())
    cell = float(2 * r.max() + SKIN)
    overlap = -g[g < 0]
    bands = {}
    for name, x in (("absolute", x_abs), ("cell_relative", cell)):
        e = 4 * 2.0 ** -23 * x + 2.0 ** -19 * rs
        share = float(np.mean(np.abs(g) < e))
        bands[name] = {"coordinate_scale_m": x, "half_width_m": e, "list_pairs_in_band": share,
                       "batches_with_one_in_band": 1 - (1 - share) ** BATCH}
    q = [0.01, 0.1, 0.5, 0.9, 0.99]
    out = {"state": path, "grains": len(r), "list_pairs": int(g.size), "touching_pairs": int(overlap.size),
           "overlap_quantiles_m": {str(k): float(v) for k, v in zip(q, np.quantile(overlap, q))},
           "bands": bands}
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main(sys.argv[1])

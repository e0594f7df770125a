"""Pairs of grains in a state file (id, type, diameter, x, y, z, ...) and their gaps, by a cell search:
the shared part of the list and overlap studies in this folder."""
from collections import defaultdict

import numpy as np


def read_state(path):
    """Positions (n x 3, m) and radii (m) of a state file."""
    d = np.genfromtxt(path, delimiter=",", names=True)
    return np.stack([d["x"], d["y"], d["z"]], 1), d["diameter"] / 2


def gaps(p, r, reach):
    """The gap |x_j - x_i| - r_i - r_j of every pair (i < j) closer than reach, one array per pair of
    cells (cells of 2 r_max + reach, so every such pair lies in neighbouring cells)."""
    cell = 2 * r.max() + reach
    cells = defaultdict(list)
    for i, k in enumerate(map(tuple, np.floor(p / cell).astype(np.int64))):
        cells[k].append(i)
    cells = {k: np.array(v) for k, v in cells.items()}
    for k, a in cells.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    b = cells.get((k[0] + dx, k[1] + dy, k[2] + dz))
                    if b is None:
                        continue
                    dist = np.linalg.norm(p[a][:, None, :] - p[b][None, :, :], axis=2)
                    gap = dist - (r[a][:, None] + r[b][None, :])
                    once = (a[:, None] < b[None, :]) & (gap < reach)
                    yield gap[once]

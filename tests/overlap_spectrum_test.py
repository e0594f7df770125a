#!/usr/bin/python3
"""studies/contact/state_pairs.py and overlap_spectrum.py on a hand-made state: a row of grains whose
gaps are set by hand (overlaps of 1e-9, 1e-8 and 1e-6 m, a gap of 1e-4 m inside the 0.15 mm skin,
and one of 1e-3 m outside it), so every pair, overlap and band share is known exactly."""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

STUDY = Path(__file__).resolve().parents[1] / "studies" / "contact"
sys.path.insert(0, str(STUDY))
from state_pairs import gaps, read_state  # noqa: E402

D = 0.002  # m, every grain's diameter
GAPS = [-1e-9, -1e-8, -1e-6, 1e-4, 1e-3]  # between grain k and k + 1, along x


def write_state(path):
    x = [0.01]
    for g in GAPS:
        x.append(x[-1] + D + g)
    with open(path, "w") as f:
        f.write("id,type,diameter,x,y,z\n")
        for k, v in enumerate(x):
            f.write(f"{k},1,{D},{v!r},0.0,0.0\n")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "row.csv"
        write_state(path)
        p, r = read_state(str(path))
        found = np.sort(np.concatenate(list(gaps(p, r, 0.15e-3))))
        # Neighbours only: the next-but-one grains are a diameter apart, past the skin. Exact up to
        # the rounding of the coordinates near 0.01 m (a few 1e-18 m), so 1e-15 m is ample.
        expected = np.sort(np.array(GAPS[:4]))
        assert found.shape == expected.shape, (found, expected)
        assert np.all(np.abs(found - expected) < 1e-15), (found, expected)

        out = json.loads(subprocess.run([sys.executable, str(STUDY / "overlap_spectrum.py"), str(path)],
                                        check=True, capture_output=True, text=True).stdout)
        assert out["list_pairs"] == 4 and out["touching_pairs"] == 3, out
        # The median of the three overlaps is 1e-8 m.
        assert abs(out["overlap_quantiles_m"]["0.5"] - 1e-8) < 1e-15, out
        # Absolute band: 4 * 2^-23 * X + 2^-19 * 2 r, X the largest coordinate (the last grain's x).
        x_max = 0.01 + 5 * D + sum(GAPS)
        e = 4 * 2.0 ** -23 * x_max + 2.0 ** -19 * D
        band = out["bands"]["absolute"]
        assert abs(band["half_width_m"] - e) < 1e-20, band
        # Inside it (1.4e-8 m with X = 0.021 m): the overlaps of 1e-9 and 1e-8 m, two of the four
        # list pairs; the cell-relative band (X = the cell, 2.15 mm, and the relative part: 4.8e-9 m)
        # holds the 1e-9 m overlap only.
        assert 1e-8 < e < 1e-6 and band["list_pairs_in_band"] == 0.5, band
        assert abs(band["batches_with_one_in_band"] - (1 - 0.5 ** 8)) < 1e-12, band
        cell = out["bands"]["cell_relative"]
        assert abs(cell["coordinate_scale_m"] - (D + 0.15e-3)) < 1e-15 and cell["list_pairs_in_band"] == 0.25, cell
    print("overlap_spectrum: pairs, overlaps and bands as set by hand")


if __name__ == "__main__":
    main()

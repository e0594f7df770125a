#!/usr/bin/python3
"""The flow's pulsation in a drum run: the dominant period of the free-surface angle and of the
kinetic energy (nearly all of a rolling bed's kinetic energy is in its flowing layer) over a window
of rotation, from series.csv; and, where the run wrote surface.csv (builds from the free surface's
speed and bulge on; a run resumed by such a build has it from its resume on), those of the surface
speed and of the surface's bulge (convex > 0, concave < 0), with their correlation.

    /usr/bin/python3 studies/seed000/pulsation.py runs/seed000/half_w0.50 [--from 10] [--to 30] [--out DIR]

Seed 000 reports that once petals form, the free surface alternates between concave and convex and
the surface flows fast and slow in turn. Each signal is detrended (a straight line over the window),
windowed (Hann) and Fourier transformed; the dominant period is the spectrum's highest peak between
twice the sampling interval and a third of the window, refined by a parabola through the peak's
three bins. Its prominence is the peak's power over the median power within an octave of it (the
peak's bins left out): a value near 1 means no period stands out of the red spectrum. Writes DIR/pulsation.json and DIR/pulsation.png (default: the run folder).
"""
import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from grainflow.resumable import load_series  # noqa: E402


def load_surface(folder, lo, hi):
    """surface.csv's rows between lo and hi rad (None when it has fewer than 16 there)."""
    path = folder / "surface.csv"
    if not path.is_file():
        return None
    d = np.atleast_1d(np.genfromtxt(path, delimiter=",", names=True))
    if d.size == 0:
        return None
    d = d[(d["angle"] >= lo) & (d["angle"] <= hi) & np.isfinite(d["surface_speed"]) & np.isfinite(d["surface_bulge"])]
    return d if len(d) >= 16 else None


def dominant_period(t, y):
    """(period s, prominence, frequencies, power) of signal y sampled at the uniform times t."""
    dt = float(np.median(np.diff(t)))
    y = y - np.polyval(np.polyfit(t, y, 1), t)
    y = y * np.hanning(len(y))
    power = np.abs(np.fft.rfft(y)) ** 2
    f = np.fft.rfftfreq(len(y), dt)
    band = (f >= 3.0 / (t[-1] - t[0])) & (f <= 0.5 / dt)
    if band.sum() < 3:
        return None, None, f, power
    idx = np.flatnonzero(band)
    k = idx[np.argmax(power[idx])]
    fk = f[k]
    if 0 < k < len(power) - 1:  # parabola through the peak's bins, in log power
        a, b, c = np.log(power[k - 1: k + 2] + 1e-300)
        shift = 0.5 * (a - c) / (a - 2 * b + c) if a - 2 * b + c != 0 else 0.0
        fk = f[k] + shift * (f[1] - f[0])
    # Prominence against the spectrum near the peak (an octave either side, the peak's bins left
    # out): a red spectrum always peaks at its low end, so the band's median would flatter it.
    near = (f >= fk / 2) & (f <= 2 * fk) & (np.abs(np.arange(len(f)) - k) > 2)
    return 1.0 / fk, float(power[k] / np.median(power[near])), f, power


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", type=Path)
    ap.add_argument("--from", dest="lo", type=float, default=10.0, help="rad of rotation where the window starts")
    ap.add_argument("--to", dest="hi", type=float, default=30.0, help="rad where it ends (or the run's last row)")
    ap.add_argument("--out", type=Path, default=None)
    a = ap.parse_args()
    s = load_series(a.run)
    if s is None:
        sys.exit(f"pulsation: no series.csv in {a.run}")
    w = s[(s["angle"] >= a.lo) & (s["angle"] <= a.hi)]
    if len(w) < 16:
        sys.exit(f"pulsation: the run has {len(w)} rows between {a.lo} and {a.hi} rad (it reached "
                 f"{float(s['angle'][-1]):.2f} rad); too few for a spectrum")
    omega = float((w["angle"][-1] - w["angle"][0]) / (w["time"][-1] - w["time"][0]))
    result = {"run": str(a.run), "from_rad": float(w["angle"][0]), "to_rad": float(w["angle"][-1]), "rows": len(w),
              "omega": omega}
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    signals = [(w, "surface_angle", "free-surface angle (deg)", 180 / math.pi),
               (w, "ke_translational", "kinetic energy (J)", 1.0)]
    surf = load_surface(a.run, a.lo, a.hi)
    if surf is not None:
        signals += [(surf, "surface_speed", "surface speed (m/s)", 1.0),
                    (surf, "surface_bulge", "surface bulge (mm; convex > 0)", 1e3)]
        speed, bulge = surf["surface_speed"], surf["surface_bulge"]
        result["surface_window_rad"] = [float(surf["angle"][0]), float(surf["angle"][-1])]
        result["speed_bulge_correlation"] = float(np.corrcoef(speed, bulge)[0, 1])
    fig, axes = plt.subplots(len(signals), 2, figsize=(10, 2.75 * len(signals)))
    for row, (d, col, label, scale) in enumerate(signals):
        y = d[col] * scale
        period, prominence, f, power = dominant_period(d["time"], y)
        result[col] = {"period_s": period, "period_rad": None if period is None else period * omega,
                       "prominence": prominence, "mean": float(np.mean(y)), "std": float(np.std(y)),
                       "from_rad": float(d["angle"][0]), "to_rad": float(d["angle"][-1])}
        axes[row][0].plot(d["angle"], y, lw=0.6)
        axes[row][0].set_xlabel("drum rotation (rad)")
        axes[row][0].set_ylabel(label)
        axes[row][1].semilogy(f[1:], power[1:], lw=0.6)
        if period:
            axes[row][1].axvline(1 / period, color="tab:red", lw=0.8,
                                 label=f"period {period:.2f} s ({period * omega:.2f} rad), prominence {prominence:.1f}")
            axes[row][1].legend(fontsize=7)
        axes[row][1].set_xlabel("frequency (Hz)")
        axes[row][1].set_ylabel("power")
    fig.suptitle(f"{a.run.name}: {result['from_rad']:.1f} to {result['to_rad']:.1f} rad", fontsize=10)
    fig.tight_layout()
    out = a.out or a.run
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "pulsation.png", dpi=110)
    (out / "pulsation.json").write_text(json.dumps(result, indent=1))
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()

"""The standard plots of a run folder, with matplotlib: the time series, what the walls feel, and a
frame's grains seen along an axis. Each function draws on the axes it is given (or a new figure's) and
returns them; `summary_figure` puts the three side by side and `python3 -m grainflow.plots RUN` saves it.

    from grainflow.outputs import Run
    from grainflow import plots
    ax = plots.series(Run("runs/drum_quick"), ["ke_translational", "ke_rotational"])
    ax.figure.savefig("energy.png")
"""
import argparse
import math
from pathlib import Path

import numpy as np

from grainflow.outputs import Run

# Units of the columns grainflow writes (docs/manual/running.md), for the axes' labels.
UNITS = {"time": "s", "angle": "rad", "ke_translational": "J", "ke_rotational": "J", "surface_angle": "rad",
         "holdup_mass": "kg", "fed_mass": "kg", "discharged_mass": "kg", "feed_backlog": "kg",
         "fx": "N", "fy": "N", "fz": "N", "tx": "N m", "ty": "N m", "tz": "N m", "power": "W"}


def _axes(ax):
    if ax is not None:
        return ax
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt.figure(figsize=(6, 4)).add_subplot()


def _label(name):
    unit = UNITS.get(name)
    return f"{name} ({unit})" if unit else name


def series(run, columns, ax=None, x="time"):
    """series.csv's `columns` (a name or a list) against `x`, one line each."""
    ax = _axes(ax)
    s = run.series
    columns = [columns] if isinstance(columns, str) else list(columns)
    for c in columns:
        if c not in s:
            raise KeyError(f"{run.folder / 'series.csv'}: no column {c!r}; it has {', '.join(s)}")
        ax.plot(s[x], s[c], label=c)
    ax.set_xlabel(_label(x))
    ax.set_ylabel(_label(columns[0]) if len(columns) == 1 else ", ".join(columns))
    if len(columns) > 1:
        ax.legend()
    return ax


def walls(run, quantity="power", ax=None, names=None):
    """walls.csv: one quantity (fx, fy, fz, tx, ty, tz or power) of each wall (or of `names`) over time,
    each point the mean over its series interval."""
    ax = _axes(ax)
    w = run.walls
    for name in names or list(w):
        if name not in w:
            raise KeyError(f"{run.folder / 'walls.csv'}: no wall {name!r}; it has {', '.join(w)}")
        ax.plot(w[name]["time"], w[name][quantity], label=name)
    ax.set_xlabel(_label("time"))
    ax.set_ylabel(_label(quantity))
    ax.legend(fontsize="small")
    return ax


def frame(run, index=-1, ax=None, axis=2, colour="species"):
    """One frame's grains as discs of their true radius, seen along `axis` (0, 1 or 2), nearest on top,
    coloured by a point array (`species`, `speed`, ...)."""
    ax = _axes(ax)
    points, data = run.frame(index)
    right, up = [a for a in range(3) if a != axis]
    order = np.argsort(points[:, axis])
    from matplotlib.collections import EllipseCollection
    d = 2.0 * data["radius"][order]
    if colour not in data:
        raise KeyError(f"frame {index}: no point array {colour!r}; it has {', '.join(data)}")
    values = np.asarray(data[colour])
    values = values if values.ndim == 1 else np.linalg.norm(values, axis=1)
    discs = EllipseCollection(d, d, np.zeros_like(d), units="xy", offsets=points[order][:, [right, up]],
                              offset_transform=ax.transData, cmap="viridis")
    discs.set_array(values[order])
    ax.add_collection(discs)
    ax.autoscale_view()
    ax.set_aspect("equal")
    names = "xyz"
    ax.set_xlabel(f"{names[right]} (m)")
    ax.set_ylabel(f"{names[up]} (m)")
    time = run.frames()[index][0]
    ax.set_title(f"t = {time:.4g} s, coloured by {colour}")
    ax.figure.colorbar(discs, ax=ax, label=colour)
    return ax


def summary_figure(run, axis=2):
    """The kinetic energy, the walls' power (when the run wrote walls.csv) and the last frame, side by side."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    has_walls = (run.folder / "walls.csv").exists()
    has_frames = (run.folder / "frames.pvd").exists()
    n = 1 + has_walls + has_frames
    fig, axes = plt.subplots(1, n, figsize=(5 * n, 4), squeeze=False)
    axes = list(axes[0])
    energies = [c for c in ("ke_translational", "ke_rotational") if c in run.series]
    series(run, energies or [c for c in run.series if c != "time"][:1], ax=axes.pop(0))
    if has_walls:
        walls(run, "power", ax=axes.pop(0))
    if has_frames:
        frame(run, -1, ax=axes.pop(0), axis=axis)
    fig.tight_layout()
    return fig


def main(argv=None):
    p = argparse.ArgumentParser(description="Save a run folder's summary figure (energy, walls' power, last frame).")
    p.add_argument("run", help="a run folder written by grainflow run")
    p.add_argument("--out", help="the PNG to write (default RUN/summary.png)")
    p.add_argument("--axis", type=int, default=2, choices=(0, 1, 2), help="the frame is seen along this axis")
    a = p.parse_args(argv)
    run = Run(a.run)
    out = Path(a.out) if a.out else run.folder / "summary.png"
    summary_figure(run, a.axis).savefig(out, dpi=100)
    print(out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

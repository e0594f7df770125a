#!/usr/bin/python3
"""Remaining fraction against time of hopper runs of composite grains (seed 002, case 1).

Reads the `remaining_fraction` column of each run's series.csv (grainflow run with
`[analysis] outlet_height`) and draws them in one chart; prints, per run, the times at which the
fraction first falls below 0.9, 0.5 and 0.1, and the longest stretch without discharge after the
first prism left (a stalled arch over the outlet: the seed reports prisms arching at about 1.6 s
and 2.4 s).

    /usr/bin/python3 studies/seed002/remaining_fraction.py runs/hopper_prisms [more runs] -o chart.png
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "python"))
from grainflow.outputs import Run  # noqa: E402


def read_series(run):
    s = Run(run).series
    if len(s["time"]) == 0 or "remaining_fraction" not in s:
        sys.exit(f"{pathlib.Path(run) / 'series.csv'}: no remaining_fraction column (give the scene [analysis] "
                 "outlet_height)")
    return s["time"].tolist(), s["remaining_fraction"].tolist()


def first_below(t, f, level):
    return next((ti for ti, fi in zip(t, f) if fi < level), None)


def longest_stall(t, f):
    """Longest interval over which the fraction did not change, after it first fell and before it
    reached its last value (s), and where it began."""
    start = first_below(t, f, f[0])
    if start is None:
        return 0.0, None
    best, since, at = 0.0, None, None
    for k in range(1, len(t)):
        if t[k] < start or f[k] == f[-1]:
            since = None
            continue
        if f[k] == f[k - 1]:
            since = t[k - 1] if since is None else since
            if t[k] - since > best:
                best, at = t[k] - since, since
        else:
            since = None
    return best, at


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="run folders holding series.csv")
    ap.add_argument("-o", "--output", help="PNG chart to write")
    a = ap.parse_args()
    series = {run: read_series(run) for run in a.runs}
    for run, (t, f) in series.items():
        marks = ", ".join(
            f"< {lvl}: {first_below(t, f, lvl):.2f} s" if first_below(t, f, lvl) is not None else f"< {lvl}: not reached"
            for lvl in (0.9, 0.5, 0.1))
        stall, at = longest_stall(t, f)
        stall_text = f"longest stall {stall:.2f} s from {at:.2f} s" if at is not None else "no stall"
        print(f"{run}: t = {t[0]:.2f} .. {t[-1]:.2f} s, remaining {f[0]:.3f} -> {f[-1]:.3f}; {marks}; {stall_text}")
    if a.output:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        for run, (t, f) in series.items():
            ax.plot(t, f, label=pathlib.Path(run).name)
        ax.set_xlabel("time after the gate opened (s)")
        ax.set_ylabel("remaining fraction")
        ax.set_ylim(0, 1.02)
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(a.output, dpi=120)
        print(f"chart: {a.output}")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Figure sheet of drum pictures: one row per run folder, one column per rotation angle, each panel
captioned with the run, the angle and the pattern the classifier reported there (series.csv row
nearest the angle). Seed 000's Figs. 3-5 are such sheets.

    /usr/bin/python3 studies/seed000/figure_sheet.py runs/w050 runs/w025 --angles 2 10 18 30 \
        --label runs/w050="omega = 0.5 rad/s" --out fig4_5.png

Pictures are the runs' pictures/angle_XX.XX.png (scene key output.picture_angles). Without
--angles, every angle found in any run is a column. A picture that a run lacks leaves its panel
marked "not drawn" and is listed on stderr; the exit status is then 1, so a script notices.
"""
import argparse
import math
import os
import re
import sys
import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from grainflow.outputs import Run  # noqa: E402

NAME = re.compile(r"^angle_(\d+\.\d\d)\.png$")
KINDS = {-1: "undecided", 0: "moon", 1: "petals"}


def picture_name(angle):
    return f"angle_{abs(angle):05.2f}.png"


def angles_in(run):
    folder = run / "pictures"
    if not folder.is_dir():
        return []
    return sorted(float(m.group(1)) for p in folder.iterdir() if (m := NAME.match(p.name)))


def default_label(run):
    """The folder name, plus the --set overrides the run was started with (summary.json)."""
    label = run.name
    try:
        overrides = Run(run).summary.get("overrides", [])
    except (OSError, ValueError):
        overrides = []
    return label + ("\n" + textwrap.fill(", ".join(overrides), 36) if overrides else "")


def load_series(run):
    """series.csv as {column: array}, or None when the run has none with the pattern's columns."""
    r = Run(run)
    if not r.has("series.csv"):
        return None
    data = r.series
    if "pattern" not in data or len(data["pattern"]) == 0:
        return None
    return data


def pattern_at(series, angle, tolerance):
    """Classifier result in the series row nearest `angle` (rad), or '' if none within tolerance."""
    if series is None:
        return ""
    k = int(np.argmin(np.abs(np.abs(series["angle"]) - angle)))
    if abs(abs(series["angle"][k]) - angle) > tolerance:
        return ""
    kind = KINDS.get(int(series["pattern"][k]), "?")
    if kind == "petals":
        kind += f" ({int(series['petals'][k])})"
    tilt = series["surface_angle"][k]
    return kind + ("" if math.isnan(tilt) else f", surface {math.degrees(tilt):.0f}°")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", type=Path, help="run folders (grainflow run --out)")
    ap.add_argument("--angles", nargs="+", type=float, help="rotation angles (rad); default: all found")
    ap.add_argument("--label", action="append", default=[], metavar="RUN=TEXT", help="row caption for a run")
    ap.add_argument("--title", default="")
    ap.add_argument("--panel", type=float, default=3.0, help="panel size (inches)")
    ap.add_argument("--tolerance", type=float, default=0.1,
                    help="largest gap (rad) between a picture's angle and the series row read for its caption")
    ap.add_argument("--out", type=Path, required=True, help="output image (.png, .pdf, .svg)")
    args = ap.parse_args()

    labels = {}
    for item in args.label:
        run, sep, text = item.partition("=")
        if not sep:
            ap.error(f"--label {item!r}: write RUN=TEXT")
        labels[Path(run).resolve()] = text
    for run in args.runs:
        if not run.is_dir():
            ap.error(f"{run}: not a folder")
    angles = args.angles or sorted({a for run in args.runs for a in angles_in(run)})
    if not angles:
        ap.error("no pictures found: give --angles, or run with output.picture_angles set")

    rows, cols = len(args.runs), len(angles)
    fig, axes = plt.subplots(rows, cols, figsize=(args.panel * cols, args.panel * rows + 0.6 * bool(args.title)),
                             squeeze=False)
    missing = []
    for i, run in enumerate(args.runs):
        series = load_series(run)
        label = labels.get(run.resolve(), default_label(run))
        for j, angle in enumerate(angles):
            ax = axes[i][j]
            ax.set_xticks([])
            ax.set_yticks([])
            path = run / "pictures" / picture_name(angle)
            if path.is_file():
                ax.imshow(mpimg.imread(path))
            else:
                missing.append(str(path))
                ax.text(0.5, 0.5, "not drawn", ha="center", va="center", transform=ax.transAxes)
            caption = f"{angle:g} rad"
            found = pattern_at(series, angle, args.tolerance)
            if found:
                caption += f": {found}"
            ax.set_xlabel(caption, fontsize=9)
            if j == 0:
                ax.set_ylabel(label, fontsize=9)
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.out, dpi=150)
    print(f"wrote {args.out}: {rows} runs x {cols} angles")
    if missing:
        print("pictures missing:\n  " + "\n  ".join(missing), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

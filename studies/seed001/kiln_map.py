#!/usr/bin/python3
"""Seed 001's mixing map: the kiln slice of scenes/kiln_seed001.toml over size ratio d_L/d_S and
density ratio rho_L/rho_S, each case run in resumable pieces.

    /usr/bin/python3 studies/seed001/kiln_map.py run [--budget-minutes 30] [--threads 1] [--cases s2.0_r1.5 ...]
    /usr/bin/python3 studies/seed001/kiln_map.py snapshot [--binary build/grainflow]
    /usr/bin/python3 studies/seed001/kiln_map.py report [--out runs/seed001] [--docs studies/seed001/results]

Each case sets species.1 (the large grains) to d_L = ratio x 2 mm and rho_L = ratio x 2800 kg/m^3
with --set, keeps equal solid volumes (the fill's volume fractions), and turns the kiln REVS
revolutions. `run` gives each unfinished case (corners and centre first, so a partial map already
spans the plane) at most --budget-minutes per invocation; a stopped case continues from its
checkpoint the next time, and finished cases are skipped. `snapshot` measures each finished case's
final state (final_state.csv) with --binary, zero steps from that state, into end_snapshot.json: the
measures of the binary at hand for cases run before they existed (the depth index), and the radial
index again, which must equal the series' last row (the same state and code). `report` writes map.json (per case: the
Lacey index and the signed radial index averaged over the last AVERAGE_REVS revolutions, with their
spread, the grains, the mean grains per Lacey cell, wall time), the heat map with the balance line
(map.png), the mixing curves (curves.png) and the corner pictures (corners.png).

Every case's results (series, summary, pieces, end snapshot, first and last picture; an unfinished
case's checkpoint too) are archived under studies/seed001/results/cases/NAME after each piece, and a run folder
missing under --out is restored from there, so the study resumes in a new checkout. A case in the
committed map.json whose results were never archived (the map's first cases) keeps its row there;
its mixing curve is then missing from curves.png.
"""
import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
from grainflow.resumable import archive, load_series, pieces, restore, run_piece  # noqa: E402

SCENE = REPO / "scenes" / "kiln_seed001.toml"
D_SMALL = 2.0e-3  # m
RHO_SMALL = 2800.0  # kg/m^3
DT_SCENE = 1.2e-5  # s, scenes/kiln_seed001.toml's
SIZE_RATIOS = [1.0, 1.5, 2.0, 2.5, 3.0]
DENSITY_RATIOS = [0.5, 1.0, 1.5, 2.0, 3.0]
REVS = 5.0  # revolutions per case
AVERAGE_REVS = 2.0  # the steady index: mean over the last two revolutions
# The corners (the pictures) and the centre first, then the rest in rows.
FIRST = [(1.0, 0.5), (3.0, 0.5), (1.0, 3.0), (3.0, 3.0), (2.0, 1.5)]


def case_name(size, density):
    return f"s{size:.1f}_r{density:.1f}"


def cases():
    rest = [(s, r) for s in SIZE_RATIOS for r in DENSITY_RATIOS if (s, r) not in FIRST]
    return FIRST + rest


def step(size, density):
    """The scene's step (0.29 of the small grain's Rayleigh time) where the small grains set the
    smallest Rayleigh time; else the same fraction of the large grain's, which scales as d sqrt(rho)."""
    return DT_SCENE * min(1.0, size * math.sqrt(density))


def overrides(size, density):
    omega = 1.2  # rad/s, the scene's
    end = REVS * 2 * math.pi + 0.01  # past the last picture's angle, which round-off could miss
    return [
        f"species.1.diameter={size * D_SMALL}",
        f"species.1.density={density * RHO_SMALL}",
        f"run.dt={step(size, density)}",
        f"run.end_angle={end}",
        f"output.checkpoint_interval={0.5 * 2 * math.pi / omega}",  # every half revolution
        "output.series_interval=0.05",
        f"output.picture_interval={2 * math.pi}",
    ]


def done(series):
    return float(series[-1]["angle"]) >= REVS * 2 * math.pi - 1e-6


def steady(series):
    """Mean and standard deviation over the last AVERAGE_REVS revolutions of the Lacey and radial indices."""
    rev = series["angle"] / (2 * math.pi)
    tail = series[rev >= rev[-1] - AVERAGE_REVS]
    return {k: (float(np.nanmean(tail[k])), float(np.nanstd(tail[k]))) for k in ("lacey_index", "radial_segregation")}


def resolved(case):
    """Whether a case's mean radial index stands out of its own fluctuation over the averaging window."""
    mean, std = case["radial"]
    return abs(mean) > std


def balance_line(table):
    """Per size ratio, the density ratio where the mean radial index changes sign (linear interpolation
    in log density ratio) between two cases whose means both stand out of their fluctuation, or
    nothing when no such pair brackets zero over the map's density ratios."""
    line = []
    for s in SIZE_RATIOS:
        pts = sorted((r, table[case_name(s, r)]["radial"][0]) for r in DENSITY_RATIOS
                     if case_name(s, r) in table and resolved(table[case_name(s, r)]))
        for (r0, y0), (r1, y1) in zip(pts, pts[1:]):
            if y0 * y1 < 0:
                f = y0 / (y0 - y1)
                line.append((s, math.exp(math.log(r0) + f * (math.log(r1) - math.log(r0)))))
                break
    return line


def near_zero(table):
    """The cases whose mean radial index lies within its fluctuation of zero: (size ratio, density ratio)."""
    return sorted((c["size_ratio"], c["density_ratio"]) for c in table.values() if not resolved(c))


def snapshot_scene(final_state):
    """The kiln scene with its fill replaced by the grains of final_state.csv and no settling."""
    text = SCENE.read_text()
    start = text.index("[[fill]]")
    end = text.index("[output]")
    fill = ('[[fill]]\nkind = "file"\npath = ' + json.dumps(str(final_state.resolve())) +
            '\ntypes = { 1 = "small", 2 = "large" }\n\n')
    return text[:start] + fill + text[end:]


def snapshot(out, binary, names):
    """end_snapshot.json per finished case: the final state's measures by `binary`, zero steps."""
    import tempfile

    for name, (size, density) in names.items():
        folder = out / name
        s = load_series(folder)
        if s is None or not done(s) or not (folder / "final_state.csv").is_file():
            continue
        with tempfile.TemporaryDirectory() as tmp:
            scene = Path(tmp) / "kiln_end.toml"
            scene.write_text(snapshot_scene(folder / "final_state.csv"))
            sets = []
            for o in overrides(size, density)[:3]:  # the species and the step; no rotation is run
                sets += ["--set", o]
            r = subprocess.run([str(binary), "run", str(scene), "--steps", "0", "--threads", "1", "--quiet",
                                "--out", str(Path(tmp) / "out")] + sets, capture_output=True, text=True)
            if r.returncode != 0:
                sys.exit(f"kiln_map snapshot {name}: {r.stderr.strip()}")
            final = json.loads((Path(tmp) / "out" / "summary.json").read_text())["final"]
        last = float(s[-1]["radial_segregation"])
        if not math.isclose(final["radial_segregation"], last, rel_tol=1e-9, abs_tol=1e-12):
            sys.exit(f"kiln_map snapshot {name}: radial index {final['radial_segregation']} of the final state "
                     f"differs from the series' last row {last}")
        rec = {"binary": str(binary), "radial_segregation": final["radial_segregation"],
               "depth_segregation": final["depth_segregation"], "lacey_index": final["lacey_index"],
               "surface_angle": final["surface_angle"], "angle": float(s[-1]["angle"])}
        (folder / "end_snapshot.json").write_text(json.dumps(rec, indent=1))
        print(f"{name}: radial {rec['radial_segregation']:+.3f} (series {last:+.3f}), depth {rec['depth_segregation']:+.3f}")


def keep(out, docs, name, size, density, binary):
    """After a piece: the end snapshot of a case that has just finished, then its archive."""
    folder = out / name
    s = load_series(folder)
    finished = s is not None and done(s)
    if finished and not (folder / "end_snapshot.json").is_file():
        snapshot(out, binary, {name: (size, density)})
    pics = sorted((folder / "pictures").glob("angle_*.png")) if (folder / "pictures").is_dir() else []
    archive(folder, docs / "cases" / name, finished, [p.name for p in pics[:1] + pics[-1:]])


def earlier_rows(docs):
    """The committed map.json's cases, for those whose results were not archived."""
    path = docs / "map.json"
    return json.loads(path.read_text()).get("cases", {}) if path.is_file() else {}


def report(out, docs):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    table = {}
    earlier = earlier_rows(docs)
    for size, density in cases():
        name = case_name(size, density)
        folder = out / name
        restore(folder, docs / "cases" / name)
        s = load_series(folder)
        if s is None or not done(s):
            if name in earlier:
                table[name] = {**earlier[name], "series_archived": False}
            continue
        st = steady(s)
        summary = json.loads((folder / "summary.json").read_text())
        ps = pieces(folder)
        end = folder / "end_snapshot.json"
        end = json.loads(end.read_text()) if end.is_file() else {}
        table[name] = {
            "size_ratio": size, "density_ratio": density,
            "lacey": st["lacey_index"], "radial": st["radial_segregation"],
            "lacey_start": float(s[0]["lacey_index"]),
            "grains": summary["grains"], "lacey_cell": summary["final"].get("lacey_cell"),
            "lacey_cell_grains": float(np.mean(s["lacey_cell_grains"])),
            "wall_seconds": sum((p["wall_seconds"] or 0) + p.get("settle_wall_seconds", 0.0) for p in ps),
            "threads": sorted({p["threads"] for p in ps}),
            "depth_end": end.get("depth_segregation"), "radial_end": end.get("radial_segregation"),
            "series_archived": True,
        }
    line = balance_line(table)
    fit = None
    pos = [(s, r) for s, r in line if s > 1.0]
    if len(pos) >= 2:
        x = np.log([s for s, _ in pos])
        y = np.log([r for _, r in pos])
        fit = float(np.sum(x * y) / np.sum(x * x))  # rho_L/rho_S = (d_L/d_S)^k through (1, 1)
    result = {"revolutions": REVS, "average_revolutions": AVERAGE_REVS, "cases": table,
              "balance_line": line, "balance_exponent": fit, "radial_near_zero": near_zero(table),
              "complete": len(table), "of": len(SIZE_RATIOS) * len(DENSITY_RATIOS)}
    docs.mkdir(parents=True, exist_ok=True)
    (docs / "map.json").write_text(json.dumps(result, indent=1))
    print(f"kiln map: {len(table)} of {result['of']} cases; balance exponent {fit}")
    if not table:
        return

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.8))
    for ax, key, title, cmap, lim in ((axes[0], "lacey", "Lacey index M (1 mixed, 0 segregated)", "viridis", (0, 1)),
                                      (axes[1], "radial", "radial index (+: large at the periphery)", "coolwarm", (-1, 1))):
        grid = np.full((len(DENSITY_RATIOS), len(SIZE_RATIOS)), np.nan)
        for v in table.values():
            grid[DENSITY_RATIOS.index(v["density_ratio"]), SIZE_RATIOS.index(v["size_ratio"])] = v[key][0]
        im = ax.imshow(grid, origin="lower", cmap=cmap, vmin=lim[0], vmax=lim[1], aspect="auto")
        for (i, j), val in np.ndenumerate(grid):
            if not np.isnan(val):
                ax.text(j, i, f"{val:.2f}", ha="center", va="center", fontsize=7,
                        color="white" if key == "lacey" and val < 0.5 else "black")
        ax.set_xticks(range(len(SIZE_RATIOS)), [f"{s:g}" for s in SIZE_RATIOS])
        ax.set_yticks(range(len(DENSITY_RATIOS)), [f"{r:g}" for r in DENSITY_RATIOS])
        ax.set_xlabel("size ratio d_L/d_S")
        ax.set_ylabel("density ratio rho_L/rho_S")
        ax.set_title(title, fontsize=9)
        fig.colorbar(im, ax=ax)
        # The balance line and the candidate laws rho_L/rho_S = (d_L/d_S)^k, in the grid's index coordinates.
        def to_index(vals, ticks):
            return np.interp(np.log(vals), np.log(ticks), np.arange(len(ticks)))
        if line:
            ax.plot(to_index([s for s, _ in line], SIZE_RATIOS), to_index([r for _, r in line], DENSITY_RATIOS),
                    "k-o", ms=3, lw=1.5, label="radial index = 0 (ours)")
        ss = np.linspace(1.0, 3.0, 50)
        for k, style in ((1, ":"), (2, "--")):
            rr = ss ** k
            keep = rr <= DENSITY_RATIOS[-1]
            ax.plot(to_index(ss[keep], SIZE_RATIOS), to_index(rr[keep], DENSITY_RATIOS), "k" + style, lw=0.8,
                    label=f"(d_L/d_S)^{k}")
        ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3)
    fig.suptitle(f"Kiln slice, {REVS:g} revolutions, mean over the last {AVERAGE_REVS:g}", fontsize=10)
    fig.tight_layout()
    fig.savefig(docs / "map.png", dpi=110)

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    for size, density in cases():
        f = out / case_name(size, density)
        s = load_series(f)
        if s is None:
            continue
        rev = s["angle"] / (2 * math.pi)
        axes[0].plot(rev, s["lacey_index"], lw=0.7, label=case_name(size, density))
        axes[1].plot(rev, s["radial_segregation"], lw=0.7)
    axes[0].set_ylabel("Lacey index")
    axes[1].set_ylabel("radial index")
    for ax in axes:
        ax.set_xlabel("revolutions")
    axes[0].legend(fontsize=5, ncol=3)
    fig.tight_layout()
    fig.savefig(docs / "curves.png", dpi=110)

    corners = [(s, r) for s, r in FIRST[:4] if case_name(s, r) in table]
    missing = [case_name(s, r) for s, r in corners if not (out / case_name(s, r) / "pictures").is_dir()]
    if missing:  # the committed sheet stays until every corner's pictures are archived again
        print(f"kiln map: corners.png not redrawn, no pictures for {missing}", file=sys.stderr)
    elif corners:
        labels = []
        for s, r in corners:
            labels += ["--label", f"{out / case_name(s, r)}=d_L/d_S = {s:g}, rho_L/rho_S = {r:g}"]
        subprocess.run([sys.executable, str(REPO / "studies/seed000/figure_sheet.py")] +
                       [str(out / case_name(s, r)) for s, r in corners] + labels +
                       ["--angles", "0", f"{REVS * 2 * math.pi:.2f}", "--out", str(docs / "corners.png")])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=["run", "snapshot", "report"])
    ap.add_argument("--out", type=Path, default=REPO / "runs" / "seed001")
    ap.add_argument("--docs", type=Path, default=REPO / "studies" / "seed001" / "results")
    ap.add_argument("--binary", type=Path, default=REPO / "build" / "grainflow")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--budget-minutes", type=float, default=30.0, help="wall time per case in this invocation")
    ap.add_argument("--cases", nargs="*", default=None, help="names like s2.0_r1.5 (default: all)")
    a = ap.parse_args()
    names = {case_name(s, r): (s, r) for s, r in cases()}
    wanted = a.cases if a.cases else list(names)
    unknown = set(wanted) - set(names)
    if unknown:
        sys.exit(f"kiln_map: unknown case(s) {sorted(unknown)}; cases are {list(names)}")
    if a.command == "run":
        if not a.binary.is_file():
            sys.exit(f"kiln_map: {a.binary} not found: build grainflow first (README)")
        for name in [n for n in names if n in wanted]:
            size, density = names[name]
            restore(a.out / name, a.docs / "cases" / name)
            run_piece(name, a.binary, SCENE, a.out / name, overrides(size, density), a.threads,
                      60 * a.budget_minutes, done)
            keep(a.out, a.docs, name, size, density, a.binary)
    elif a.command == "snapshot":
        snapshot(a.out, a.binary, {n: names[n] for n in wanted})
    else:
        report(a.out, a.docs)


if __name__ == "__main__":
    main()

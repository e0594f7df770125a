#!/usr/bin/python3
"""Seed 000's six drum cases (Zhao & Cheng 2007, Table 5), run in resumable pieces.

    /usr/bin/python3 studies/seed000/study.py run [--size full|small] [--budget-minutes 10] [--threads 1] [--cases ...]
    /usr/bin/python3 studies/seed000/study.py report [--size full|small]

--size full (default) is the seed's drum (150 mm x 8 mm, 1 and 3 mm grains, 47,108 or 23,554
grains, dt 1e-5 s). --size small is the same six cases in the small drum of scenes/drum_quick.toml
(80 mm x 16 mm, 2 and 6 mm grains in the seed's size and volume ratios, 2,987 or 1,494 grains
poured and settled, dt 3e-5 s): about 50 times cheaper per radian, so it reaches 30 rad here.

`run` gives each case (in turn) at most --budget-minutes of wall time, then stops it with SIGINT:
grainflow finishes the step in flight and writes its checkpoint, so the next `run` continues the
case where it stopped (bit-identical to an uninterrupted run), until it reaches 30 rad. Every piece
is logged in <out>/<case>/pieces.jsonl (steps, wall time, particle-steps/s). Cases are the half-fill
state (scenes/drum_seed000_settled.toml) at 2, 1, 0.5 and 0.25 rad/s and the quarter-fill state
(scenes/drum_seed000_quarter.toml) at 0.5 and 0.25 rad/s, with pictures every radian and at the
seed's angles.

After each piece of a full-size case its results (series, summary, pieces, log, the pictures at
the seed's angles, and at the end the final state) are archived under studies/seed000/results/study/<case>,
with the checkpoint (gzip-compressed, checkpoints/checkpoint.gfc.gz) while the case is unfinished;
a case whose working folder is missing (a new checkout) is restored from there first, so the study
goes on in any checkout (grainflow.resumable). Commit the archived checkpoint when you stop
for the day rather than after every piece: every committed version stays in the history.

`report` writes studies/seed000/results/seed_drum_table.json for the full size (the README's table: its rows
for the cases run here, the committed rows kept for the others) and, for each case archived with its
final state, studies/seed000/results/petal_arms/<case>/ (studies/seed000/petal_arms.py), <out>/table.md (seed outcome, ours at the angle reached, rotation reached, wall
time, particle-steps/s), <out>/table.json, the figure sheet <out>/sheet.png (every case at the
angles they reached), the formation sequence <out>/formation.png (0.5 rad/s at 2, 10, 18, 30 rad,
or as far as it got) and the free-surface angle against rotation <out>/surface_angle.png.
"""
import argparse
import json
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
from grainflow.resumable import archive, load_series, pieces, restore, run_piece  # noqa: E402
HALF = "scenes/drum_seed000_settled.toml"
QUARTER = "scenes/drum_seed000_quarter.toml"
# name, scene, omega (rad/s), the seed's outcome after 30 rad
SMALL = "scenes/drum_quick.toml"
CASES = [
    ("half_w2.00", HALF, 2.00, "moon"),
    ("half_w1.00", HALF, 1.00, "moon (slightly wavy interface)"),
    ("half_w0.50", HALF, 0.50, "5 petals"),
    ("half_w0.25", HALF, 0.25, "7 petals"),
    ("quarter_w0.50", QUARTER, 0.50, "moon"),
    ("quarter_w0.25", QUARTER, 0.25, "moon (rough interface)"),
]
END_ANGLE = 30.0
KINDS = {-1: "undecided", 0: "moon", 1: "petals"}


def case_overrides(omega, size, scene):
    if size == "small":
        length = [f"run.duration={END_ANGLE / omega}"]
        if scene == QUARTER:  # half the grains of the small drum's half fill, same ratio
            length += ["fill.0.count.large=54", "fill.0.count.small=1440"]
    else:
        length = [f"run.end_angle={END_ANGLE}"]
    return length + [
        f"wall.0.omega={omega}",
        "output.picture_interval=1.0",
        "output.frame_interval=0",
        # A checkpoint every 2.5 % of the case: a crash or kill loses at most that.
        f"output.checkpoint_interval={0.025 * END_ANGLE / omega}",
        f"output.series_interval={min(0.01, 0.02 / omega)}",
    ]


ARCHIVE = REPO / "studies" / "seed000" / "results" / "study"
SEED_ANGLES = (2, 10, 18, 30)  # rad: the seed's Figs. 4-6


def run_case(name, scene, omega, out, binary, threads, budget_s, size):
    path = SMALL if size == "small" else scene
    keep = size == "full"
    if keep:
        restore(out / name, ARCHIVE / name)
    # Done when the series has reached the end angle (a piece run with --steps also ends
    # "completed", short of it).
    done = lambda s: float(s[-1]["angle"]) >= END_ANGLE - 1e-9  # noqa: E731
    run_piece(name, binary, REPO / path, out / name, case_overrides(omega, size, scene), threads, budget_s, done)
    s = load_series(out / name)
    if keep and s is not None:
        finished = done(s)
        archive(out / name, ARCHIVE / name, finished, [f"angle_{a:05.2f}.png" for a in SEED_ANGLES],
                ["final_state.csv"] if finished else [])


def keep_committed_rows(rows):
    """studies/seed000/results/seed_drum_table.json (the README's table) with this report's rows for the cases
    that ran here, and the committed rows kept for cases whose runs this checkout does not hold. A
    case run again from the start keeps its committed row while the rerun is short of it, with the
    rerun's angle noted (`rerun_angle`)."""
    docs = REPO / "studies" / "seed000" / "results" / "seed_drum_table.json"
    committed = {r["case"]: r for r in json.loads(docs.read_text())} if docs.is_file() else {}

    def pick(r):
        old = committed.get(r["case"])
        if old is None or not old["ran"]:
            return r
        if not r["ran"]:
            return old
        if r["angle"] >= old["angle"] - 1e-9:
            return r
        return {key: value for key, value in old.items() if key != "rerun_angle"} | {"rerun_angle": r["angle"]}

    docs.write_text(json.dumps([pick(r) for r in rows], indent=1))


def report(out):
    rows = []
    for name, scene, omega, seed in CASES:
        folder = out / name
        s = load_series(folder)
        ps = pieces(folder)
        if s is None or not ps:
            rows.append({"case": name, "seed": seed, "ran": False})
            continue
        last = s[-1]
        # Main stage plus settling (the quarter fill settles its cut surface first).
        wall = sum((p["wall_seconds"] or 0) + p.get("settle_wall_seconds", 0.0) for p in ps)
        steps = sum(p["steps"] or 0 for p in ps)
        summary = json.loads((folder / "summary.json").read_text())
        grains = summary["grains"]
        # Lobes crossing the rings at 0.6-0.9 R, from the last state (builds that count them).
        ring_lobes = summary.get("final", {}).get("ring_lobes")
        kind = KINDS.get(int(last["pattern"]), "?")
        ours = f"{int(last['petals'])} petals" if kind == "petals" else kind
        rows.append({
            "case": name, "seed": seed, "ran": True, "fill": "1/2" if scene == HALF else "1/4", "omega": omega,
            "angle": float(last["angle"]), "ours": ours, "contrast": float(last["pattern_contrast"]),
            "segregation_index": float(last["segregation_index"]), "surface_angle": float(last["surface_angle"]),
            "wall_seconds": wall, "steps": steps, "grains": grains,
            "particle_steps_per_second": steps * grains / sum(p["wall_seconds"] or 0 for p in ps),
            "threads": sorted({p["threads"] for p in ps}),
            "ring_lobes": ring_lobes, "ring_radii": summary.get("final", {}).get("ring_radii"),
        })
    (out / "table.json").write_text(json.dumps(rows, indent=1))
    if out == REPO / "runs" / "seed000":
        keep_committed_rows(rows)
        # The small-grain arms inside the bed of each finished case's final state (the README's table).
        for r in rows:
            state = ARCHIVE / r["case"] / "final_state.csv"
            if r["ran"] and r["angle"] >= END_ANGLE - 1e-9 and state.is_file():
                subprocess.run([sys.executable, str(REPO / "studies/seed000/petal_arms.py"), str(state.relative_to(REPO)),
                                "--out", str(REPO / "studies/seed000/results/petal_arms" / r["case"])],
                               cwd=REPO, stdout=subprocess.DEVNULL, check=True)
    lines = ["| fill | ω (rad/s) | seed at 30 rad | ours (classifier) | rotation reached (rad) | segregation index | "
             "wall time | particle-steps/s (threads) |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if not r["ran"]:
            lines.append(f"| | | {r['seed']} | not run | 0 | | | |")
            continue
        lines.append(f"| {r['fill']} | {r['omega']:.2f} | {r['seed']} | {r['ours']} (contrast {r['contrast']:.2f}) | "
                     f"{r['angle']:.2f} of {END_ANGLE:.0f} | {r['segregation_index']:.3f} | "
                     f"{r['wall_seconds'] / 60:.1f} min | {r['particle_steps_per_second']:.3g} "
                     f"({','.join(map(str, r['threads']))}) |")
    (out / "table.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))

    ran = [out / r["case"] for r in rows if r["ran"]]
    if not ran:
        return
    sheet = [str(REPO / "studies/seed000/figure_sheet.py")] + [str(f) for f in ran]
    reached = min((r["angle"] for r in rows if r["ran"]), default=0.0)
    angles = [a for a in (1, 2, 5, 10, 18, 30) if a <= reached + 1e-9] or [0]
    subprocess.run([sys.executable] + sheet + ["--angles"] + [str(a) for a in angles] + ["--out", str(out / "sheet.png")])
    w050 = out / "half_w0.50"
    if w050.is_dir():
        got = [a for a in (2, 10, 18, 30) if (w050 / "pictures" / f"angle_{a:05.2f}.png").is_file()]
        if got:
            subprocess.run([sys.executable, str(REPO / "studies/seed000/figure_sheet.py"), str(w050), "--angles"] +
                           [str(a) for a in got] + ["--out", str(out / "formation.png")])
    fig, ax = plt.subplots(figsize=(7, 3.5))
    for f in ran:
        s = load_series(f)
        ax.plot(s["angle"], np.degrees(s["surface_angle"]), lw=0.8, label=f.name)
    ax.set_xlabel("drum rotation (rad)")
    ax.set_ylabel("free-surface angle (deg)")
    ax.set_title("Free surface of the bed (series.csv surface_angle)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "surface_angle.png", dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=["run", "report"])
    ap.add_argument("--size", choices=["full", "small"], default="full")
    ap.add_argument("--out", type=Path, default=None, help="default runs/seed000 (full) or runs/seed000_small")
    ap.add_argument("--binary", type=Path, default=REPO / "build" / "grainflow")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--budget-minutes", type=float, default=10.0, help="wall time per case in this invocation")
    ap.add_argument("--cases", nargs="*", default=[c[0] for c in CASES])
    a = ap.parse_args()
    unknown = set(a.cases) - {c[0] for c in CASES}
    if unknown:
        sys.exit(f"study: unknown case(s) {sorted(unknown)}; cases are {[c[0] for c in CASES]}")
    if a.out is None:
        a.out = REPO / "runs" / ("seed000" if a.size == "full" else "seed000_small")
    a.out.mkdir(parents=True, exist_ok=True)
    if a.command == "run":
        if not a.binary.is_file():
            sys.exit(f"study: {a.binary} not found: build grainflow first (README)")
        for name, scene, omega, _ in CASES:
            if name in a.cases:
                run_case(name, scene, omega, a.out, a.binary, a.threads, 60 * a.budget_minutes, a.size)
    report(a.out)


if __name__ == "__main__":
    main()

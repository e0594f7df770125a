#!/usr/bin/python3
"""Seed 002's second hopper: the four composite shapes of scenes/generators/armour_shapes.py discharged
from scenes/hopper_seed002_shapes.toml, each run in resumable pieces (grainflow.resumable).

    /usr/bin/python3 studies/seed002/shapes_hopper.py run [--budget-minutes 30] [--shapes NAME ...]
    /usr/bin/python3 studies/seed002/shapes_hopper.py report     # studies/seed002/results/shapes/shapes.json, remaining.png
    /usr/bin/python3 studies/seed002/shapes_hopper.py table      # the README table from shapes.json

The case hollow_block_long discharges the hollow block, the one shape that drains through the 12 s,
for up to 40 s, and stops earlier once no grain has left for 2 s (the heap the seed measures is then
left behind): its series is read while a piece runs, and the piece is stopped with its checkpoint
once that holds; it is a row of its own in the table.

Working runs under runs/seed002_shapes/NAME; after each piece a run's results (and, unfinished, its
checkpoint) are archived under studies/seed002/results/shapes/NAME, from which a new checkout resumes.

Observables per shape, from series.csv's remaining_fraction (t = 0 when the orifice opens,
crossings interpolated linearly between rows): the mean discharge rate between fractions 0.9 and
0.5, in grains/s and kg/s (the shape's mass from summary.json's moving mass over the grains), the
fraction left at the end, and the angle of repose of the crater left about the orifice:
summary.json's `repose` (across x and across z, two flanks each), their mean and range.
"""
import argparse
import json
import math
import shutil
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "studies" / "seed002"))


def resumable():
    """grainflow.resumable, imported where runs are read (it needs numpy; the table does not)."""
    import grainflow.resumable as r

    return r

SCENE = REPO / "scenes" / "hopper_seed002_shapes.toml"
SHAPES = ["hollow_block", "tetrapod", "twisted_i", "twisted_king"]  # the seed's order, simplest first
DURATION = 12.0  # s after the orifice opens, the scene's run.duration
# Longer discharges: case -> (shape, duration in s after the orifice opens).
LONG = {"hollow_block_long": ("hollow_block", 40.0)}
# What makes three shapes arch? case -> (shape, duration in s after the orifice opens, overrides, what
# changes). Short: the scene's grains arch within 1 to 4 s of the orifice opening.


def _friction(mu):
    return [f"contact.friction={mu}", f"contact.wall.friction={mu}"]


# The seed's 4000 grains: the lattice twice as tall (to 58 m), and 2 s more for it to land and settle.
SEED_COUNT = ["bodies.3.count=4000", 'bodies.3.region={ shape = "box", lo = [-10.0, 0.1, -10.0], hi = [10.0, 70.0, 10.0] }',
              "settle.time=7.0"]
CAUSES = {"twisted_i_friction_0.2": ("twisted_i", 4.0, _friction(0.2), "friction 0.2 (the scene: 0.5)"),
          "tetrapod_friction_0.2": ("tetrapod", 4.0, _friction(0.2), "friction 0.2 (the scene: 0.5)"),
          "twisted_i_friction_0": ("twisted_i", 4.0, _friction(0.0), "no friction"),
          "twisted_i_4000": ("twisted_i", 4.0, SEED_COUNT, "4000 grains, the seed's (the scene: 2000)")}
CASES = SHAPES + list(LONG) + list(CAUSES)
STOPPED = 2.0  # s without a grain leaving: a long discharge has stopped
ORIFICE = 8.0  # m, the side of the scene's square orifice


def shape_of(case):
    return LONG[case][0] if case in LONG else CAUSES[case][0] if case in CAUSES else case


def duration_of(case):
    return LONG[case][1] if case in LONG else CAUSES[case][1] if case in CAUSES else DURATION


def label_of(case):
    name = shape_of(case).replace("_", " ")
    if case in LONG:
        return f"{name} (up to {duration_of(case):g} s)"
    if case in CAUSES:
        return f"{name}, {CAUSES[case][3]}, {duration_of(case):g} s"
    return name


def stopped(series):
    """No grain left over the last STOPPED s of the series (only after the 12 s every shape runs)."""
    t, f = [float(x) for x in series["time"]], [float(x) for x in series["remaining_fraction"]]
    if t[-1] < DURATION + STOPPED:
        return False
    before = [fk for tk, fk in zip(t, f) if tk <= t[-1] - STOPPED]
    return bool(before) and before[-1] == f[-1]


def done_for(case):
    def done(series):
        return float(series["time"][-1]) >= duration_of(case) - 1e-9 or (case in LONG and stopped(series))
    return done


def stop_for(case):
    """The test that ends a long case's piece while it runs (it has stopped draining); None for
    the 12 s cases, which the scene's duration ends."""
    return stopped if case in LONG else None


def overrides(case):
    o = [f'shape.0.path="data/shapes/{shape_of(case)}.obj"', "output.checkpoint_interval=1.0"]
    if case in LONG or case in CAUSES:
        o.append(f"run.duration={duration_of(case)}")
    if case in CAUSES:
        o += CAUSES[case][2]
    return o


def crossing(t, f, level):
    for k in range(1, len(t)):
        if f[k] <= level < f[k - 1]:
            return t[k - 1] + (t[k] - t[k - 1]) * (f[k - 1] - level) / (f[k - 1] - f[k])
    return None


def fraction_at(t, f, when):
    """The remaining fraction at time `when` (linear between rows), None past the series."""
    for k in range(1, len(t)):
        if t[k - 1] <= when <= t[k]:
            return f[k - 1] + (f[k] - f[k - 1]) * (when - t[k - 1]) / (t[k] - t[k - 1]) if t[k] > t[k - 1] else f[k]
    return None


def bed_top_at_opening(folder):
    """The highest grain centre (m above the bottom) in the run's first frame, when the orifice opens: the
    bed's depth less half a grain. None without that frame (archives keep no frames)."""
    from grainflow.outputs import read_csv, rows_of

    first = folder / "frames" / "frame_000000.csv"
    if not first.is_file():
        return None
    return max(float(r["y"]) for r in rows_of(read_csv(first)) if r["motion"] == "moving")


def measure(folder, case):
    r = resumable()
    s = r.load_series(folder)
    if s is None or not done_for(case)(s):
        return None
    summary = json.loads((folder / "summary.json").read_text())
    t, f = list(s["time"]), list(s["remaining_fraction"])
    t9, t5 = crossing(t, f, 0.9), crossing(t, f, 0.5)
    grains = summary["bodies"]["moving"]
    mass = summary["shapes"]["grain"]["mass"] if "shapes" in summary else None
    angles = []
    for heap in summary.get("repose", {}).values():
        for side in ("first", "second"):
            a = heap.get(side, {}).get("angle_deg")
            if a is not None:
                angles.append(a)
    rate = 0.4 * grains / (t5 - t9) if t9 is not None and t5 is not None else None
    return {"grains": grains, "end_s": t[-1], "t_0.9": t9, "t_0.5": t5, "rate_grains_per_s": rate,
            "rate_kg_per_s": rate * mass if rate is not None and mass else None, "grain_mass": mass,
            "left_at_end": f[-1], "left_at_4s": fraction_at(t, f, 4.0), "bed_top_at_opening_m": bed_top_at_opening(folder),
            "repose": summary.get("repose", {}),
            "repose_mean_deg": sum(angles) / len(angles) if angles else None,
            "repose_range_deg": [min(angles), max(angles)] if angles else None,
            "repose_flanks": len(angles),  # of 4: a flank without a slope to fit (a flat bed) has none
            "wall_seconds": sum((p["wall_seconds"] or 0) + p.get("settle_wall_seconds", 0.0) for p in r.pieces(folder))}


def report(out, docs):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    r = resumable()
    rows = {}
    committed = json.loads((docs / "shapes.json").read_text())["shapes"] if (docs / "shapes.json").is_file() else {}
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for shape in CASES:
        folder = out / shape
        r.restore(folder, docs / shape)
        m = measure(folder, shape)
        s = r.load_series(folder)
        if m is None:
            if s is not None:  # running: how far it got, drawn dashed
                top = bed_top_at_opening(folder) or committed.get(shape, {}).get("bed_top_at_opening_m")
                rows[shape] = {"in_progress": float(s[-1]["time"]), "bed_top_at_opening_m": top}
                ax.plot(s["time"], s["remaining_fraction"], "--",
                        label=f"{label_of(shape)} (running, to {float(s[-1]['time']):.2f} s)")
            continue
        if m["bed_top_at_opening_m"] is None:  # no frames here: the committed reading
            m["bed_top_at_opening_m"] = committed.get(shape, {}).get("bed_top_at_opening_m")
        rows[shape] = m
        ax.plot(s["time"], s["remaining_fraction"], ":" if shape in CAUSES else "-", label=label_of(shape))
    docs.mkdir(parents=True, exist_ok=True)
    if rows:
        ax.set_xlabel("time after the orifice opens (s)")
        ax.set_ylabel("remaining fraction")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(docs / "remaining.png", dpi=110)
    (docs / "shapes.json").write_text(json.dumps({"shapes": rows, "of": CASES}, indent=1))
    done = sum(1 for v in rows.values() if "in_progress" not in v)
    print(f"shapes hopper: {done} of {len(CASES)} cases finished, {len(rows) - done} running")


def fmt(v, spec):
    return "—" if v is None else format(v, spec)


def table(path):
    doc = json.loads(Path(path).read_text())
    lines = ["| shape | grains | t(0.9) (s) | t(0.5) (s) | rate 0.9→0.5 (grains/s) | rate (t/s) | left at 4 s | left at the end | "
             "end (s) | angle of repose (°, mean of the flanks with a slope) | range (°; flanks with a slope, of 4) | "
             "wall time (h, one thread) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for case in doc["of"]:
        r = doc["shapes"].get(case)
        name = label_of(case)
        if r is None or "in_progress" in r:
            state = "not run yet" if r is None else f"running: {r['in_progress']:.2f} s of {duration_of(case):g}"
            lines.append(f"| {name} | {state} | | | | | | | | | | |")
            continue
        rng = r["repose_range_deg"]
        lines.append(f"| {name} | {r['grains']} | {fmt(r['t_0.9'], '.2f')} | {fmt(r['t_0.5'], '.2f')} | "
                     f"{fmt(r['rate_grains_per_s'], '.0f')} | "
                     f"{fmt(None if r['rate_kg_per_s'] is None else r['rate_kg_per_s'] / 1000, '.0f')} | "
                     f"{fmt(r.get('left_at_4s'), '.3f')} | {r['left_at_end']:.3f} | {r.get('end_s', DURATION):.1f} | {fmt(r['repose_mean_deg'], '.1f')} | "
                     f"{'—' if rng is None else f'{rng[0]:.1f}–{rng[1]:.1f}'} ({r.get('repose_flanks', '?')} of 4) | "
                     f"{r['wall_seconds'] / 3600:.2f} |")
    print("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=["run", "report", "table"])
    ap.add_argument("path", nargs="?", default=str(REPO / "studies" / "seed002" / "results" / "shapes" / "shapes.json"))
    ap.add_argument("--out", type=Path, default=REPO / "runs" / "seed002_shapes")
    ap.add_argument("--docs", type=Path, default=REPO / "studies" / "seed002" / "results" / "shapes")
    ap.add_argument("--binary", type=Path, default=REPO / "build" / "grainflow")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--budget-minutes", type=float, default=30.0)
    ap.add_argument("--shapes", nargs="*", default=SHAPES, help=f"cases to run: {' '.join(CASES)}")
    a = ap.parse_args()
    unknown = set(a.shapes) - set(CASES)
    if unknown:
        sys.exit(f"shapes_hopper: unknown case(s) {sorted(unknown)}; cases are {CASES}")
    if a.command == "table":
        table(a.path)
        return
    if a.command == "report":
        report(a.out, a.docs)
        return
    if not a.binary.is_file():
        sys.exit(f"shapes_hopper: {a.binary} not found: build grainflow first (README)")
    r = resumable()
    for shape in [s for s in CASES if s in a.shapes]:
        folder = a.out / shape
        r.restore(folder, a.docs / shape)
        done = done_for(shape)
        r.run_piece(shape, a.binary, SCENE, folder, overrides(shape), a.threads, 60 * a.budget_minutes, done,
                    stop=stop_for(shape))
        s = r.load_series(folder)
        finished = s is not None and done(s)
        pics = sorted((folder / "pictures").glob("time_*.png")) if (folder / "pictures").is_dir() else []
        r.archive(folder, a.docs / shape, finished, [p.name for p in pics])
        if finished and shape in LONG:
            keep_what_is_left(folder, a.docs / shape)


def keep_what_is_left(folder, dest):
    """A finished long discharge's last body frame, archived as dest/last_frame.csv, and what it
    leaves in the hopper (studies/seed002/left_in_hopper.py) as dest/left_in_hopper.json."""
    from left_in_hopper import left_in_hopper  # it puts the Python package on the path
    from grainflow.outputs import read_csv, rows_of

    last = str(read_csv(folder / "frames" / "frames.csv")["file"][-1])
    shutil.copy2(folder / "frames" / last, dest / "last_frame.csv")
    left = left_in_hopper(rows_of(read_csv(dest / "last_frame.csv")), ORIFICE)
    (dest / "left_in_hopper.json").write_text(json.dumps({"frame": f"{dest.name}/last_frame.csv"} | left, indent=1) + "\n")


if __name__ == "__main__":
    main()

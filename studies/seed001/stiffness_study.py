#!/usr/bin/python3
"""Speed against accuracy for the kiln map: one mid-map case (size ratio 2, density ratio 1.5) with
Young's modulus reduced 10 to 100,000 times from glass (48 GPa), the step scaled with it (0.29 of
the Rayleigh time, dt proportional to E^-1/2), the linear law with its stiffness matched, and the
map's own setting (E/1000) from three fill seeds for the case-to-case noise.

    /usr/bin/python3 studies/seed001/stiffness_study.py run [--budget-minutes 30] [--variants ...]
    /usr/bin/python3 studies/seed001/stiffness_study.py report [--out runs/seed001_stiffness] [--docs studies/seed001/results]

Each variant runs REVS revolutions in resumable pieces (grainflow.resumable); `report`
writes stiffness.json (per variant: the Lacey and radial indices over the last revolution, wall
time, particle-steps/s) and stiffness.png (index against wall time, the seeds' spread shaded).
Each variant's results (and an unfinished one's checkpoint) are archived under
studies/seed001/results/stiffness_cases/NAME after each piece and restored from there into a missing run
folder; a variant of the committed stiffness.json with nothing archived keeps its row.
"""
import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
from grainflow.resumable import archive, load_series, pieces, restore, run_piece  # noqa: E402

SCENE = REPO / "scenes" / "kiln_seed001.toml"
E_GLASS = 4.8e10  # Pa, Chung & Ooi (2011)
DT_MAP = 1.2e-5  # s, the scene's step at E/1000
REVS = 3.0
AVERAGE_REVS = 1.0
SIZE_RATIO, DENSITY_RATIO = 2.0, 1.5


def hertz(factor, seed=1):
    e = E_GLASS * factor
    dt = DT_MAP * math.sqrt(1e-3 / factor)
    return {"law": "hertz_mindlin", "youngs_modulus": e, "dt": dt, "seed": seed}


# name -> settings; the linear law's stiffness: the small-small contact lasts as long as the Hertz
# contact at E/1000 and the scene's impact speed (0.3 m/s): t_c = 2.87 (m*^2/(R* E*^2 v))^(1/5) =
# 1.49e-4 s with m* = 5.86e-6 kg, R* = 5e-4 m, E* = E / (2 (1 - nu^2)) = 2.5e7 Pa; then
# kn = m* (pi^2 + ln^2 e) / t_c^2 = 2.6e3 N/m, kt = 2/7 kn (the linear law's usual ratio),
# rolling friction mu_r R_small = 0.01 x 1 mm = 1e-5 m.
VARIANTS = {
    "E1e-1": hertz(1e-1),
    "E1e-2": hertz(1e-2),
    "E1e-3_seed1": hertz(1e-3, 1),
    "E1e-3_seed2": hertz(1e-3, 2),
    "E1e-3_seed3": hertz(1e-3, 3),
    "E1e-4": hertz(1e-4),
    "E1e-5": hertz(1e-5),
    "linear": {"law": "linear_spring_dashpot", "kn": 2.6e3, "kt": 2.6e3 * 2 / 7, "dt": DT_MAP, "seed": 1},
}


def linear_scene(folder):
    """The kiln scene with the linear law instead of Hertz-Mindlin (same grains, friction, restitution)."""
    text = SCENE.read_text()
    text = "\n".join(l for l in text.splitlines() if not l.startswith(("youngs_modulus", "poisson_ratio")))
    a = text.index("[contact]")
    b = text.index("[periodic]")
    v = VARIANTS["linear"]
    contact = (f"[contact]\nmodel = \"linear_spring_dashpot\"\nkn = {v['kn']}\nkt = {v['kt']}\nkr = 0.0\n"
               "en = 0.9\net = 0.9\ner = 0.0\nfriction = 0.3\nrolling_friction = 1.0e-5\n\n")
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "kiln_linear.toml"
    path.write_text(text[:a] + contact + text[b:])
    return path


def overrides(v):
    out = [
        f"species.1.diameter={SIZE_RATIO * 2.0e-3}",
        f"species.1.density={DENSITY_RATIO * 2800.0}",
        f"run.dt={v['dt']}",
        f"run.seed={v['seed']}",
        f"settle.time={0.6}",
        f"run.end_angle={REVS * 2 * math.pi + 0.01}",
        f"output.checkpoint_interval={math.pi / 1.2}",
        "output.series_interval=0.05",
        f"output.picture_interval={2 * math.pi}",
    ]
    if v["law"] == "hertz_mindlin":
        out += [f"species.0.youngs_modulus={v['youngs_modulus']}", f"species.1.youngs_modulus={v['youngs_modulus']}"]
    return out


def done(series):
    return float(series[-1]["angle"]) >= REVS * 2 * math.pi - 1e-6


def report(out, docs):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = {}
    path = docs / "stiffness.json"
    earlier = json.loads(path.read_text())["variants"] if path.is_file() else {}
    for name, v in VARIANTS.items():
        folder = out / name
        restore(folder, docs / "stiffness_cases" / name)
        s = load_series(folder)
        if s is None and name in earlier:
            rows[name] = {**earlier[name], "series_archived": False}
            continue
        ps = pieces(folder)
        if ps and ps[-1]["status"] == "failed":  # the run stopped itself: the reason is the log's last line
            reason = (folder / "log.txt").read_text().strip().splitlines()[-1].replace("grainflow: error: ", "")
            reason = reason.split(". Fix:")[0]
            rows[name] = {**v, "failed": reason}
            continue
        if s is None or not done(s):
            continue
        rev = s["angle"] / (2 * math.pi)
        tail = s[rev >= rev[-1] - AVERAGE_REVS]
        ps = pieces(folder)
        summary = json.loads((folder / "summary.json").read_text())
        rows[name] = {**v, "lacey": float(np.nanmean(tail["lacey_index"])), "lacey_std": float(np.nanstd(tail["lacey_index"])),
                      "radial": float(np.nanmean(tail["radial_segregation"])),
                      "wall_seconds": sum((p["wall_seconds"] or 0) + p.get("settle_wall_seconds", 0.0) for p in ps),
                      "grains": summary["grains"], "max_overlap_ratio": summary["final"]["max_overlap_ratio"]}
    # Case-to-case noise: the three fill seeds of the map's setting, per measure (mean and range); a
    # variant departs when a measure lies farther from the seeds' mean than their range.
    seeds = [rows[n] for n in rows if n.startswith("E1e-3_seed") and "lacey" in rows[n]]
    noise = None
    if len(seeds) >= 2:
        noise = {k: {"mean": float(np.mean([r[k] for r in seeds])), "range": float(np.ptp([r[k] for r in seeds]))}
                 for k in ("lacey", "radial")}
        noise.update(noise["lacey"])  # the Lacey index's, as the chart shades it
        for r in rows.values():
            if "lacey" in r:
                r["departs_by"] = [k for k in ("lacey", "radial")
                                   if abs(r[k] - noise[k]["mean"]) > max(noise[k]["range"], 1e-9)]
                r["departs"] = bool(r["departs_by"])
    docs.mkdir(parents=True, exist_ok=True)
    (docs / "stiffness.json").write_text(json.dumps({"revolutions": REVS, "average_revolutions": AVERAGE_REVS,
                                                      "size_ratio": SIZE_RATIO, "density_ratio": DENSITY_RATIO,
                                                      "seed_noise": noise, "variants": rows}, indent=1))
    print(f"stiffness study: {len(rows)} of {len(VARIANTS)} variants; seed noise {noise}")
    if not rows:
        return
    fig, ax = plt.subplots(figsize=(6.5, 4))
    if noise:
        ax.axhspan(noise["mean"] - noise["range"], noise["mean"] + noise["range"], color="0.85",
                   label="E/1000, three seeds: mean ± range")
    for name, r in rows.items():
        if "lacey" not in r:
            continue
        bad = r.get("departs", False)
        ax.plot(r["wall_seconds"] / 60, r["lacey"], "s" if r["law"] != "hertz_mindlin" else "o",
                color="tab:red" if bad else "tab:blue")
        ax.annotate(name, (r["wall_seconds"] / 60, r["lacey"]), fontsize=7, xytext=(4, 2), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_xlabel("wall time, 1 thread (min)")
    ax.set_ylabel(f"Lacey index, mean of the last {AVERAGE_REVS:g} revolution")
    ax.set_title(f"Kiln d_L/d_S = {SIZE_RATIO:g}, rho_L/rho_S = {DENSITY_RATIO:g}: stiffness against accuracy "
                 "(red: departs by more than the seeds' range)", fontsize=8)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(docs / "stiffness.png", dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=["run", "report"])
    ap.add_argument("--out", type=Path, default=REPO / "runs" / "seed001_stiffness")
    ap.add_argument("--docs", type=Path, default=REPO / "studies" / "seed001" / "results")
    ap.add_argument("--binary", type=Path, default=REPO / "build" / "grainflow")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--budget-minutes", type=float, default=30.0)
    ap.add_argument("--variants", nargs="*", default=list(VARIANTS))
    a = ap.parse_args()
    unknown = set(a.variants) - set(VARIANTS)
    if unknown:
        sys.exit(f"stiffness_study: unknown variant(s) {sorted(unknown)}; variants are {list(VARIANTS)}")
    if a.command == "report":
        report(a.out, a.docs)
        return
    # The cheapest first: a partial study already brackets the map's setting.
    order = ["E1e-5", "E1e-4", "E1e-3_seed1", "E1e-3_seed2", "E1e-3_seed3", "linear", "E1e-2", "E1e-1"]
    for name in [n for n in order if n in a.variants]:
        v = VARIANTS[name]
        folder = a.out / name
        scene = linear_scene(folder) if v["law"] != "hertz_mindlin" else SCENE
        restore(folder, a.docs / "stiffness_cases" / name)
        run_piece(name, a.binary, scene, folder, overrides(v), a.threads, 60 * a.budget_minutes, done)
        s = load_series(folder)
        ps = pieces(folder)
        finished = (s is not None and done(s)) or bool(ps and ps[-1]["status"] == "failed")
        archive(folder, a.docs / "stiffness_cases" / name, finished)


if __name__ == "__main__":
    main()

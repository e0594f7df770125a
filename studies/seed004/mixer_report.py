#!/usr/bin/env python3
"""The seed-004 mixer runs made into result files, charts and the README table.

  mixer_report.py report [--runs runs/seed004] [--docs studies/seed004/results]
      For every finished design run (runs/seed004/designN, scenes/mixer_seed004_designN.toml):
      the steady state (from the first series row whose hold-up mass is within 5 % of the mean
      hold-up of the run's last third), Vc(L) as the mean of layers.csv's pooled rows inside it
      (with their smallest and largest), the residence-time distribution of the grains that entered
      and left inside it (mean, spread, the dimensionless variance sigma^2 / t_mean^2), the hold-up
      and its solid fraction of the housing. Writes mixer.json, vc_profile.csv, rtd.csv, the charts
      vc_profile.png, rtd.png, holdup.png, and copies each run's series, layers, residence, summary
      and final-state files under studies/seed004/results/designN/ (dem_fK for the sphere runs). A run whose
      working folder is gone (a new checkout) is read from that copy; a copy made before the final
      state was kept gives its solid fraction from the mixer.json it replaces, and its picture stays.
  mixer_report.py table studies/seed004/results/mixer.json
      The README's table (tools/readme/tables.py calls it).
  mixer_report.py picture final_state.csv out.png [--title T]
      Side view and three cross-sections of a mixer state, coloured by component.
"""
import argparse
import json
import math
import pathlib
import shutil
import sys

try:  # the README's table needs only the JSON; reports and charts need numpy
    import numpy as np
except ImportError:
    np = None

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scenes" / "generators"))
sys.path.insert(0, str(ROOT / "python"))
import mixer_scene as geometry  # noqa: E402  (the scenes' dimensions, one source)

# The seed's Fig. 4 trend, read from its text: Vc about 30-35 % near the inlet, 5-10 % by L = 0.4 m.
SEED_NEAR_INLET = (0.30, 0.35)
SEED_AT_04 = (0.05, 0.10)


def read_csv(path):
    """A run's CSV file as {column: array} (the Python package's reader)."""
    from grainflow.outputs import read_csv as read
    return read(path)


def rows_where(table, mask):
    """The rows of a {column: array} table where `mask` holds."""
    return {name: values[mask] for name, values in table.items()}


def summary_of(run):
    """A run folder's summary.json as a dict."""
    from grainflow.outputs import Run
    return Run(run).summary


def steady_start(series):
    mass = series["holdup_mass"]
    tail = mass[len(mass) * 2 // 3:]
    level = float(np.mean(tail))
    inside = np.nonzero(np.abs(mass - level) <= 0.05 * level)[0]
    return float(series["time"][inside[0]]) if len(inside) else float("nan"), level


def sampling_corrected_vc(vc, lacey, c):
    """Vc with the random-mixture variance of the cells taken out: a representative volume stands
    for hundreds of grains, so a cell holding n of them has the binomial spread of n draws, which a
    cell of the real mixture (the seed's images) does not. With s^2 = (Vc c)^2, s0^2 = c (1 - c) and
    Lacey's M = (s0^2 - s^2) / (s0^2 - sr^2) from the same cells, sr^2 = s0^2 - (s0^2 - s^2) / M and
    the corrected Vc is sqrt(max(0, s^2 - sr^2)) / c."""
    s2, s02 = (vc * c) ** 2, c * (1.0 - c)
    with np.errstate(divide="ignore", invalid="ignore"):
        sr2 = s02 - (s02 - s2) / lacey
        return np.sqrt(np.maximum(0.0, s2 - sr2)) / c


def vc_profile(layers, t0):
    rows = rows_where(layers, layers["time"] >= t0)
    out = []
    for d in sorted(set(rows["distance"].tolist())):
        at = rows_where(rows, (rows["distance"] == d) & np.isfinite(rows["vc"]) & np.isfinite(rows["lacey"]))
        v = at["vc"]
        corr = sampling_corrected_vc(at["vc"], at["lacey"], at["fraction_a"])
        n = len(v)
        out.append({"distance": d, "vc_mean": float(np.mean(v)) if n else None,
                    "vc_min": float(np.min(v)) if n else None, "vc_max": float(np.max(v)) if n else None,
                    "vc_corrected_mean": float(np.mean(corr)) if n else None,
                    "lacey_mean": float(np.mean(at["lacey"])) if n else None,
                    "grains_per_cell": float(np.mean(at["grains"] / at["cells"])) if n else None,
                    "pools": int(n)})
    return out


# The distribution counts the grains that entered after the steady state began and left before the
# run ended: a grain that stays longer than the time left is missing from it, so its mean is biased
# short; the table gives the hold-up over the feed rate (the unbiased mean) beside it.
def rtd(residence, t0):
    inside = rows_where(residence, np.isfinite(residence["entry_time"]) & (residence["entry_time"] >= t0))
    t = inside["residence_time"]
    if len(t) < 2:
        return {"grains": int(len(t))}, None
    mean = float(np.mean(t))
    var = float(np.var(t))
    edges = np.linspace(0.0, float(np.max(t)) * 1.02, 31)
    hist, _ = np.histogram(t, bins=edges, density=True)
    return ({"grains": int(len(t)), "mean": mean, "std": math.sqrt(var), "dimensionless_variance": var / mean ** 2,
             "median": float(np.median(t)), "p10": float(np.percentile(t, 10)), "p90": float(np.percentile(t, 90))},
            (edges, hist))


KEPT = ["series.csv", "layers.csv", "residence.csv", "summary.json", "final_state.csv", "pieces.jsonl"]


def wall_seconds(run, summary):
    """The run's wall time: its pieces' (grainflow.resumable) when it ran in several, else the summary's."""
    pieces = run / "pieces.jsonl"
    if pieces.exists():
        rows = [json.loads(line) for line in pieces.read_text().splitlines() if line.strip()]
        return sum(r.get("wall_seconds") or 0.0 for r in rows)
    return summary.get("wall_seconds")


def core_seconds(run, summary):
    """Wall time times threads, summed over the run's pieces (one piece: the summary's), and the thread
    counts the pieces ran on."""
    pieces = run / "pieces.jsonl"
    if pieces.exists():
        rows = [json.loads(line) for line in pieces.read_text().splitlines() if line.strip()]
        return (sum((r.get("wall_seconds") or 0.0) * r.get("threads", 1) for r in rows),
                sorted({r.get("threads", 1) for r in rows}))
    threads = summary.get("threads", 1)
    return (summary.get("wall_seconds") or 0.0) * threads, [threads]


def run_folder(runs, docs, name):
    """The run's working folder, or its copy under results/ when the working folder is gone."""
    work = runs / name
    return work if (work / "summary.json").exists() else docs / name


def completed(run):
    return (run / "summary.json").exists() and summary_of(run).get("status") == "completed"


def design_result(run, design, docs, name=None, earlier=None):
    series = read_csv(run / "series.csv")
    layers = read_csv(run / "layers.csv")
    residence = read_csv(run / "residence.csv")
    summary = summary_of(run)
    t0, level = steady_start(series)
    steady = rows_where(series, series["time"] >= t0)
    housing = math.pi * geometry.RADIUS ** 2 * geometry.LENGTH
    stats, hist = rtd(residence, t0)
    keep = docs / (name or f"design{design}")
    keep.mkdir(parents=True, exist_ok=True)
    for file in KEPT:
        if (run / file).exists() and run.resolve() != keep.resolve():
            shutil.copyfile(run / file, keep / file)
    if (run / "final_state.csv").exists():
        final = read_csv(run / "final_state.csv")
        solid = float(np.sum(math.pi / 6.0 * final["diameter"] ** 3)) / housing
        draw(run / "final_state.csv", docs / f"{name or f'design{design}'}_state.png",
             f"{name or f'design {design}'} at {float(series['time'][-1]):.0f} s (side view: every grain; "
             "below: slices one carrier diameter thick)")
    else:
        solid = (earlier or {}).get("holdup_solid_fraction_final")
    return {
        "design": design,
        "blade_lengths_m": list(geometry.DESIGNS[design]),
        "scene": f"scenes/mixer_seed004_design{design}.toml",
        "simulated_s": float(series["time"][-1]),
        "wall_seconds": wall_seconds(run, summary),
        "core_seconds": core_seconds(run, summary)[0],
        "threads": core_seconds(run, summary)[1],
        "pieces": sum(1 for _ in open(run / "pieces.jsonl")) if (run / "pieces.jsonl").exists() else 1,
        "particle_steps_per_second": summary.get("particle_steps_per_second"),
        "steady_from_s": t0,
        "holdup_mass_kg": level,
        "holdup_grains_mean": float(np.mean(steady["grains"])) if len(steady["grains"]) else None,
        "holdup_solid_fraction_final": solid,
        "feed_rate_kg_s": geometry.RATE,
        # Little's law: in a steady state the mean residence time is the hold-up over the throughput.
        "mean_residence_holdup_over_rate_s": level / geometry.RATE,
        "fed_kg": float(series["fed_mass"][-1]),
        "discharged_kg": float(series["discharged_mass"][-1]),
        "feed_backlog_kg_max": float(np.max(series["feed_backlog"])),
        "rtd": stats,
        "vc": vc_profile(layers, t0),
    }, hist


def charts(results, hists, docs):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.8))
    for r in results:
        d = [p["distance"] for p in r["vc"] if p["vc_mean"] is not None]
        m = [100 * p["vc_mean"] for p in r["vc"] if p["vc_mean"] is not None]
        lo = [100 * p["vc_min"] for p in r["vc"] if p["vc_mean"] is not None]
        hi = [100 * p["vc_max"] for p in r["vc"] if p["vc_mean"] is not None]
        line, = ax.plot(d, m, "o-", label=f"design {r['design']} (blades " +
                        "/".join(f"{1000 * b:.0f}" for b in r["blade_lengths_m"]) + " mm)")
        ax.fill_between(d, lo, hi, alpha=0.15, color=line.get_color())
        ax.plot(d, [100 * p["vc_corrected_mean"] for p in r["vc"] if p["vc_mean"] is not None], "--",
                color=line.get_color(), lw=1)
    ax.add_patch(plt.Rectangle((0.0, 100 * SEED_NEAR_INLET[0]), 0.06, 100 * (SEED_NEAR_INLET[1] - SEED_NEAR_INLET[0]),
                               color="k", alpha=0.25, label="seed Fig. 4, as its text reads it"))
    ax.add_patch(plt.Rectangle((0.37, 100 * SEED_AT_04[0]), 0.06, 100 * (SEED_AT_04[1] - SEED_AT_04[0]), color="k",
                               alpha=0.25))
    for i, x in enumerate(geometry.STAGES):
        ax.axvline(x, color="grey", lw=0.8, ls="--")
        ax.text(x, ax.get_ylim()[1] * 0.97, "I" * (i + 1), ha="center", va="top")
    for x in geometry.PARTITIONS:
        ax.axvline(x, color="grey", lw=0.6, ls=":")
    ax.set_xlabel("distance from the inlet L (m)")
    ax.set_ylabel("inhomogeneity Vc (%)")
    ax.set_title("Seed 004 mixer, representative volumes: Vc(L) in steady state (mean of pooled 20 s rows, band:\n"
                 "their range; dashed lines: sampling-corrected; grey dashed: blade stages, dotted: partitions)",
                 fontsize=9)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
    fig.tight_layout()
    fig.savefig(docs / "vc_profile.png", dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 3.6))
    for r, h in zip(results, hists):
        if h is None:
            continue
        edges, dens = h
        ax.step(edges[:-1], dens, where="post", label=f"design {r['design']}: mean {r['rtd']['mean']:.0f} s, "
                f"sigma^2/t^2 = {r['rtd']['dimensionless_variance']:.2f}")
    ax.set_xlabel("residence time (s)")
    ax.set_ylabel("E(t) (1/s)")
    ax.set_title("Residence-time distribution (grains fed and discharged in steady state)", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(docs / "rtd.png", dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 3.6))
    for r in results:
        s = read_csv(docs / f"design{r['design']}" / "series.csv")
        ax.plot(s["time"], s["holdup_mass"], label=f"design {r['design']}")
        ax.axvline(r["steady_from_s"], lw=0.6, ls=":")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("hold-up (kg)")
    ax.set_title("Hold-up from an empty mixer (dotted: start of the steady state)", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(docs / "holdup.png", dpi=110)
    plt.close(fig)


def report(args):
    runs, docs = pathlib.Path(args.runs), pathlib.Path(args.docs)
    docs.mkdir(parents=True, exist_ok=True)
    before = docs / "mixer.json"
    before = json.loads(before.read_text()) if before.exists() else {"designs": [], "models": []}
    results, hists = [], []
    for design in sorted(geometry.DESIGNS):
        run = run_folder(runs, docs, f"design{design}")
        if not completed(run):
            print(f"design {design}: not finished, left out")
            continue
        earlier = next((d for d in before["designs"] if d["design"] == design), None)
        r, h = design_result(run, design, docs, earlier=earlier)
        results.append(r)
        hists.append(h)
    models = model_results(runs, docs, results, before["models"])
    (docs / "mixer.json").write_text(json.dumps({"designs": results, "models": models}, indent=1) + "\n")
    with open(docs / "vc_profile.csv", "w") as f:
        f.write("design,distance,vc_mean,vc_min,vc_max,pools\n")
        for r in results:
            for p in r["vc"]:
                f.write(f"{r['design']},{p['distance']},{p['vc_mean']},{p['vc_min']},{p['vc_max']},{p['pools']}\n")
    with open(docs / "rtd.csv", "w") as f:
        f.write("design,bin_lo,bin_hi,density\n")
        for r, h in zip(results, hists):
            if h is not None:
                for a, b, e in zip(h[0][:-1], h[0][1:], h[1]):
                    f.write(f"{r['design']},{a:.4g},{b:.4g},{e:.6g}\n")
    if results:
        charts(results, hists, docs)
    if len(models) > 1:
        model_chart(models, docs)
    print(f"wrote {docs / 'mixer.json'} ({len(results)} designs)")


def model_results(runs, docs, designs, earlier_models=()):
    """Design 1 as representative volumes and as sphere DEM at each coarse-graining factor run, with
    each model's Vc(L) difference from the finest DEM run (root mean square over the layers both
    report) and its wall time per simulated second."""
    rv = next((r for r in designs if r["design"] == 1), None)
    models = []
    if rv is not None:
        models.append(dict(rv, model="representative volumes", factor=None))
    names = sorted({p.name for p in list(runs.glob("dem_f*")) + list(docs.glob("dem_f*")) if p.is_dir()})
    for name in names:
        run = run_folder(runs, docs, name)
        if not completed(run):
            continue
        f = float(name[len("dem_f"):])
        earlier = next((m for m in earlier_models if m.get("factor") == f), None)
        r, _ = design_result(run, 1, docs, name=name, earlier=earlier)
        models.append(dict(r, model=f"sphere DEM, factor {f:g}", factor=f))
    dem = [m for m in models if m["factor"] is not None]
    if dem:
        finest = max(dem, key=lambda m: m["factor"])
        ref = {p["distance"]: p["vc_mean"] for p in finest["vc"] if p["vc_mean"] is not None}
        for m in models:
            d = [p["vc_mean"] - ref[p["distance"]] for p in m["vc"] if p["vc_mean"] is not None and p["distance"] in ref]
            m["vc_rms_difference_from_finest"] = float(np.sqrt(np.mean(np.square(d)))) if d else None
            m["finest"] = finest["model"]
            m["wall_seconds_per_simulated_second"] = m["wall_seconds"] / m["simulated_s"] if m["wall_seconds"] else None
            m["core_seconds_per_simulated_second"] = m["core_seconds"] / m["simulated_s"] if m["core_seconds"] else None
    return models


def model_chart(models, docs):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for m in models:
        d = [p["distance"] for p in m["vc"] if p["vc_mean"] is not None]
        v = [100 * p["vc_mean"] for p in m["vc"] if p["vc_mean"] is not None]
        time = (f"{m['wall_seconds'] / 60:.1f} min" if m.get("threads", [1]) == [1]
                else f"{m['core_seconds'] / 60:.0f} core-min")
        ax.plot(d, v, "o-", ms=3, label=f"{m['model']}: {m['holdup_grains_mean']:.0f} grains, "
                f"{time} for {m['simulated_s']:.0f} s")
    ax.set_xlabel("distance from the inlet L (m)")
    ax.set_ylabel("inhomogeneity Vc (%)")
    ax.set_title("Design 1: representative volumes against sphere DEM (legend: hold-up and wall time, 1 thread;\n"
                 "core time where pieces ran on more)", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(docs / "vc_models.png", dpi=110)
    plt.close(fig)


def near(profile, at):
    p = min(profile, key=lambda p: abs(p["distance"] - at))
    return p


def cost(m):
    """Wall s per simulated s of a one-thread run; core-s per simulated s of one whose pieces ran on more."""
    if m.get("threads", [1]) == [1]:
        return f"{m['wall_seconds_per_simulated_second']:.2f}"
    return (f"{m['core_seconds_per_simulated_second']:.2f} core-s (pieces on "
            f"{' and '.join(str(t) for t in m['threads'])} threads)")


def table(args):
    data = json.loads(pathlib.Path(args.file).read_text())
    rows = ["Each Vc cell: mean over the steady pools (their range); the sampling-corrected Vc; Lacey's M of the same "
            "cells.", "",
            "| design (blades I/II/III, mm) | Vc at L = 0.025 m | Vc at 0.2 m | Vc at 0.4 m | mean residence (s): hold-up / rate; "
            "of the grains that left (short-biased) | "
            "sigma^2/t^2 (of those) | hold-up (kg, grains) | steady from (s) | wall time (s) |",
            "|---|---|---|---|---|---|---|---|---|"]
    for r in data["designs"]:
        def vc(at):
            p = near(r["vc"], at)
            if p["vc_mean"] is None:
                return "n/a"
            return (f"{100 * p['vc_mean']:.1f} % ({100 * p['vc_min']:.1f}–{100 * p['vc_max']:.1f}); "
                    f"{100 * p['vc_corrected_mean']:.1f} %; M {p['lacey_mean']:.2f}")
        rt = r["rtd"]
        rows.append(f"| {r['design']} ({'/'.join(f'{1000 * b:.0f}' for b in r['blade_lengths_m'])}) | {vc(0.025)} | "
                    f"{vc(0.2)} | {vc(0.4)} | {r['mean_residence_holdup_over_rate_s']:.1f}; {rt.get('mean', float('nan')):.1f} | "
                    f"{rt.get('dimensionless_variance', float('nan')):.2f} | {r['holdup_mass_kg']:.2f}, "
                    f"{r['holdup_grains_mean']:.0f} | {r['steady_from_s']:.0f} | {r['wall_seconds']:.0f} |")
    if len(data.get("models", [])) > 1:
        rows.append("")
        rows.append("| design 1 as | hold-up (grains) | Vc at 0.025 / 0.2 / 0.4 m | Vc(L) RMS difference from "
                    "the finest | wall s per simulated s (1 thread; core-s where pieces ran on more) |")
        rows.append("|---|---|---|---|---|")
        for m in data["models"]:
            vcs = " / ".join("n/a" if near(m["vc"], a)["vc_mean"] is None else f"{100 * near(m['vc'], a)['vc_mean']:.1f} %"
                             for a in (0.025, 0.2, 0.4))
            diff = m.get("vc_rms_difference_from_finest")
            rows.append(f"| {m['model']} | {m['holdup_grains_mean']:.0f} | {vcs} | "
                        f"{'reference' if m['model'] == m.get('finest') else ('n/a' if diff is None else f'{100 * diff:.1f} points')} | "
                        f"{cost(m)} |")
    rows.append("")
    rows.append(f"The seed (Fig. 4, as its text reads it): Vc {100 * SEED_NEAR_INLET[0]:.0f}–"
                f"{100 * SEED_NEAR_INLET[1]:.0f} % near the inlet, {100 * SEED_AT_04[0]:.0f}–{100 * SEED_AT_04[1]:.0f} "
                "% by L = 0.4 m.")
    print("\n".join(rows))


def picture(args):
    draw(args.state, args.out, args.title)
    print("wrote", args.out)


def draw(state, out, title=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    s = read_csv(state)
    key = s["type"] == 2  # the scenes' second species, the key component
    fig = plt.figure(figsize=(10, 5.6))
    side = fig.add_axes([0.05, 0.5, 0.9, 0.42])

    def area(ax_width_in, span_m):  # marker area (pt^2) of a grain drawn to scale
        return (s["diameter"] / span_m * ax_width_in * 72.0) ** 2 * 0.8

    for sel, colour, label in [(~key, "#C8A040", "carrier (millet)"), (key, "#303090", "key (rapeseed)")]:
        side.scatter(s["x"][sel], s["y"][sel], s=area(6.1, geometry.LENGTH + 0.02)[sel], c=colour, label=label,
                     lw=0, alpha=0.6)
    for x in geometry.STAGES:
        side.axvline(x, color="grey", lw=0.8, ls="--")
    for x in geometry.PARTITIONS + [geometry.LENGTH]:
        side.axvline(x, color="k", lw=0.6, ls=":")
    side.set_xlim(0, geometry.LENGTH + 0.02)
    side.set_ylim(-geometry.RADIUS, geometry.RADIUS)
    side.set_aspect("equal")
    side.set_xlabel("x (m)")
    side.set_title(title or "side view", fontsize=9)
    side.legend(fontsize=7, loc="upper right", markerscale=0.3)
    for i, x in enumerate([0.13, 0.25, 0.45]):
        ax = fig.add_axes([0.05 + 0.31 * i, 0.02, 0.28, 0.36])
        near_x = np.abs(s["x"] - x) <= 0.5 * geometry.CARRIER[1]
        for sel, colour in [(~key & near_x, "#C8A040"), (key & near_x, "#303090")]:
            ax.scatter(s["z"][sel], s["y"][sel], s=area(2.2, 2 * geometry.RADIUS)[sel], c=colour, lw=0)
        ax.add_patch(plt.Circle((0, 0), geometry.RADIUS, fill=False, lw=0.8))
        ax.set_xlim(-geometry.RADIUS, geometry.RADIUS)
        ax.set_ylim(-geometry.RADIUS, geometry.RADIUS)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(f"cross-section at x = {x} m", fontsize=8)
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("report")
    r.add_argument("--runs", default=str(ROOT / "runs" / "seed004"))
    r.add_argument("--docs", default=str(ROOT / "studies" / "seed004" / "results"))
    t = sub.add_parser("table")
    t.add_argument("file")
    p = sub.add_parser("picture")
    p.add_argument("state")
    p.add_argument("out")
    p.add_argument("--title")
    args = ap.parse_args()
    {"report": report, "table": table, "picture": picture}[args.cmd](args)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Seed 003's transport pipe: what each numerical setting costs and what it changes, at 2 m/s.

Each variant is the pipe (scenes/liquid/transport_pipe.toml, as studies/seed003/transport_pipe.py runs it)
with one setting changed, run 2 s from rest on two threads, one run after the other, and read as
transport_pipe.py reads its cases (frames.csv, statistics from 1.0 s on). The variants:
  - the liquid's step dt from 5e-4 s up to where the program stops the run (its CFL or density check), the
    drive's relaxation scaled with it so that the mean speed's time constant stays 0.2 s;
  - the pressure solver (Jacobi CG; multigrid CG with its hierarchy kept 20 steps), and the solver's tolerance;
  - another pour (the fill's seed 2): how far two runs of the same case differ after 1 s of statistics, the
    yardstick for every other difference;
  - the DEM sub-steps per liquid step, twice the computed number (fewer are refused by the contact's step limit);
  - the seed's spacing l0 = 7.5 mm (2.4 times the nodes).

  /usr/bin/python3 studies/seed003/pipe_cost.py run [--only NAME ...] [--threads 2] [--binary build/grainflow]
      each variant into runs/liquid/pipe_cost/<name>, then collect
  /usr/bin/python3 studies/seed003/pipe_cost.py collect
      studies/seed003/results/pipe_cost.json: per variant its overrides, status (and what stopped it), wall time
      per simulated second, the pressure solve's mean iterations, the largest CFL number reached, and the
      observables (var(r/R) with the frames' spread, the volume-fraction peak, spin, grains' speed, centre/U)
  /usr/bin/python3 studies/seed003/pipe_cost.py chart
      studies/seed003/results/pipe_cost.png (run and collect draw it too): wall time per simulated second against
      each observable, the two pours' range shaded
  /usr/bin/python3 studies/seed003/pipe_cost.py table [studies/seed003/results/pipe_cost.json]
      the results page's table (tools/readme/tables.py calls it; needs no numpy)
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import transport_pipe as tp  # noqa: E402

SPEED, DURATION, FROM, TAU = 2.0, 2.0, 1.0, 0.2  # m/s, s, s, the drive's time constant (s)
RUNS = os.path.join(ROOT, "runs/liquid/pipe_cost")
OUT = os.path.join(ROOT, "studies/seed003/results/pipe_cost.json")
JACOBI = 'liquid.solver={preconditioner="jacobi"}'


def step(dt):
    """The liquid's step and the drive's relaxation that keeps its time constant at TAU."""
    return [f"run.dt={dt}", f"drive.relaxation={dt / TAU}"]


VARIANTS = {  # name: (what changes, overrides)
    "jacobi": ("Jacobi CG", [JACOBI]),
    "shipped": ("as shipped", []),
    "pour2": ("another pour (fill seed 2)", ["fill.0.seed=2"]),
    "tolerance_1e-6": ("solver tolerance 1e-6", ['liquid.solver={preconditioner="multigrid", multigrid_reuse=20, '
                                                 'tolerance=1e-6}']),
    "dt_7.5e-4": ("dt 7.5e-4 s", step(7.5e-4)),
    "dt_1e-3": ("dt 1e-3 s", step(1e-3)),
    "dt_1.25e-3": ("dt 1.25e-3 s", step(1.25e-3)),
    "dt_1.5e-3": ("dt 1.5e-3 s", step(1.5e-3)),
    "dt_2e-3": ("dt 2e-3 s", step(2e-3)),
    "substeps_36": ("DEM sub-steps 36 (twice the 18 computed)", ["coupling.substeps=36"]),
    "l0_7.5mm": ("l0 7.55 mm (the seed: 7.5; 53 spacings along the 0.4 m period)", ["liquid.l0=0.0075471698"]),
}


def run_one(name, binary, threads):
    folder = os.path.join(RUNS, name)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(RUNS, exist_ok=True)
    sets = tp.overrides(SPEED, 0.0, DURATION) + VARIANTS[name][1]
    cmd = [binary, "run", os.path.join(ROOT, tp.SCENE), "--out", folder, "--threads", str(threads)]
    for s in sets:
        cmd += ["--set", s]
    with open(os.path.join(RUNS, name + ".log"), "w") as log:
        rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, cwd=ROOT)
    tp.update_frames(folder)
    return rc


def series_stats(folder):
    """Mean pressure-solve iterations and the largest CFL number over the run's series."""
    path = os.path.join(folder, "series.csv")
    if not os.path.exists(path):
        return None, None
    rows = list(csv.DictReader(open(path)))[1:]
    its = [float(r["ppe_iterations"]) for r in rows]
    cfl = [float(r["cfl"]) for r in rows]
    return (sum(its) / len(its) if its else None), (max(cfl) if cfl else None)


def collect():
    out = {"speed": SPEED, "duration": DURATION, "from_s": FROM, "scene": tp.SCENE, "variants": []}
    for name, (what, sets) in VARIANTS.items():
        folder = os.path.join(RUNS, name)
        summary_path = os.path.join(folder, "summary.json")
        if not os.path.exists(summary_path):
            continue
        s = json.load(open(summary_path))
        its, cfl = series_stats(folder)
        row = {"name": name, "what": what, "overrides": tp.overrides(SPEED, 0.0, DURATION) + sets,
               "status": s.get("status"), "simulated_s": s.get("simulated_time"), "dt": s.get("dt"),
               "fluid_nodes": s.get("fluid_nodes"), "threads": s.get("threads"),
               "wall_seconds": s.get("wall_seconds"), "ppe_iterations": its, "cfl_max": cfl}
        if s.get("simulated_time"):
            row["wall_per_simulated_s"] = s["wall_seconds"] / s["simulated_time"]
        if s.get("status") == "failed":
            row["failure"] = s.get("failure", "")
        m = tp.measure(folder, FROM)
        if m and m.get("status") != "failed":
            row.update({k: m[k] for k in ("frames", "r_variance", "r_variance_frame_sd", "phi_peak_r", "phi_peak",
                                          "spin", "grain_speed")})
            row["centre_over_u"] = m["u_profile"][0] / SPEED
        out["variants"].append(row)
    with open(OUT, "w") as fh:
        json.dump(out, fh, indent=1)
    print("wrote", os.path.relpath(OUT, ROOT))


def fmt(v, spec):
    return "—" if v is None else format(v, spec)


def threads(v):
    """A variant run on other than two threads says so beside its wall time (not comparable with the others)."""
    return "" if v.get("threads") in (None, 2) else f" ({v['threads']} thread{'s' if v['threads'] != 1 else ''})"


def table(path):
    doc = json.load(open(path))
    lines = ["| variant | status | dt (s) | fluid nodes | wall s per simulated s | PPE iterations | largest CFL | "
             "var(r/R) (frames' sd) | peak r/R (%) | spin (rad/s) | grains' speed (m/s) | centre liquid / U |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for v in doc["variants"]:
        status = v["status"] if v["status"] != "failed" else f"stopped at {fmt(v.get('simulated_s'), '.3g')} s: " + \
            v.get("failure", "").split(":")[0][:80]
        var = f"{fmt(v.get('r_variance'), '.4f')} (± {fmt(v.get('r_variance_frame_sd'), '.4f')})" \
            if v.get("r_variance") is not None else "—"
        peak = f"{fmt(v.get('phi_peak_r'), '.2f')} ({fmt(v.get('phi_peak'), '.1f')})" if v.get("phi_peak_r") else "—"
        lines.append(f"| {v['what']} | {status} | {fmt(v.get('dt'), 'g')} | {fmt(v.get('fluid_nodes'), ',')} | "
                     f"{fmt(v.get('wall_per_simulated_s'), '.1f')}{threads(v)} | {fmt(v.get('ppe_iterations'), '.1f')} | "
                     f"{fmt(v.get('cfl_max'), '.2f')} | {var} | {peak} | {fmt(v.get('spin'), '.2f')} | "
                     f"{fmt(v.get('grain_speed'), '.2f')} | {fmt(v.get('centre_over_u'), '.3f')} |")
    return "\n".join(lines)


def chart(path, out):
    """Each completed variant's wall time per simulated second against its observables, the two pours' range
    shaded: what a setting buys in time and what it moves beyond the case's own spread."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    doc = json.load(open(path))
    done = [v for v in doc["variants"] if v["status"] == "completed"]
    pours = [v for v in done if v["name"] in ("shipped", "pour2")]
    keys = [("r_variance", "var(r/R)"), ("spin", "mean spin (rad/s)"), ("centre_over_u", "centre liquid / U"),
            ("grain_speed", "grains' speed (m/s)")]
    fig, axes = plt.subplots(1, len(keys), figsize=(4.0 * len(keys), 3.6))
    for ax, (key, label) in zip(axes, keys):
        lo, hi = min(v[key] for v in pours), max(v[key] for v in pours)
        ax.axhspan(lo, hi, color="0.85", label="two pours of the shipped case")
        for v in done:
            ax.plot(v["wall_per_simulated_s"], v[key], "o")
            ax.annotate(v["name"], (v["wall_per_simulated_s"], v[key]), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")
        ax.set_xscale("log")
        ax.set_xlabel("wall s per simulated s (2 threads)")
        ax.set_ylabel(label)
    axes[0].legend(fontsize=7, loc="lower left")
    failed = [v for v in doc["variants"] if v["status"] == "failed"]
    note = "; ".join(f"{v['name']}: stopped at {v['simulated_s']:.3g} s ({v.get('failure', '').split(':')[0]})"
                     for v in failed)
    fig.suptitle(f"Transport pipe at {doc['speed']:g} m/s, statistics over {doc['from_s']:g}-{doc['duration']:g} s"
                 + (f"\n{note}" if note else ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("wrote", os.path.relpath(out, ROOT))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--only", nargs="*")
    r.add_argument("--threads", type=int, default=2)
    r.add_argument("--binary", default=os.path.join(ROOT, "build/grainflow"))
    sub.add_parser("collect")
    sub.add_parser("chart")
    t = sub.add_parser("table")
    t.add_argument("path", nargs="?", default=OUT)
    a = p.parse_args()
    if a.cmd == "run":
        for name in a.only or VARIANTS:
            print(name, "exit", run_one(name, a.binary, a.threads), flush=True)
        collect()
        chart(OUT, OUT.replace(".json", ".png"))
    elif a.cmd == "collect":
        collect()
        chart(OUT, OUT.replace(".json", ".png"))
    elif a.cmd == "chart":
        chart(OUT, OUT.replace(".json", ".png"))
    else:
        print(table(a.path))


if __name__ == "__main__":
    main()

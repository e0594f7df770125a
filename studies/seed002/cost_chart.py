#!/usr/bin/python3
"""Cost and accuracy of composite grains in seed 002's hopper: one reduced hopper
(scenes/hopper_seed002_cost.toml, 300 particles) run five times per particle model, each to the
end of its discharge on one thread.

Particle models (the scene's [[shape]] "grain" table replaced by each):
  prism_r0.25, prism_r0.5, prism_r1.0   the rounded triangular prism (10 mm side, 10 mm long) with
                                        dilation radius r = 0.25, 0.5 (the reference), 1.0 mm; the
                                        builder moves the faces in by r, so the outer size stays
  clump_3, clump_9, clump_27            multi-sphere approximations of the same prism (below)
  sphere                                one sphere of the reference prism's volume (one-vertex shape)
  prism_grid1mm, prism_grid2mm          the reference prism with a mass-property grid of 1 mm and
                                        2 mm instead of 0.25 mm (10 and 5 voxels across the side)
Each model is poured five times (the [[bodies]] seed 7, 11, 12, 13, 14: random centres and
orientations), so the scatter of one run shows beside the models' differences.

Same mass: every model except the two grid ones takes the density that gives the reference prism's
mass (its volume measured by `grainflow check` on the model's own grid); the grid models keep
1400 kg/m^3, so their mass and inertia carry the coarse grid's error, as a user would get it.

Clumps, all inside the prism's outline (sharp or rounded: the spheres stay off the rounded edges),
rods of overlapping spheres along the prism's length, their end spheres touching the end faces:
  clump_3:  one rod on the axis, spheres of the triangle's inradius (2.89 mm), 3 along the length,
            each touching the three sides;
  clump_9:  three rods, one toward each corner on its median at 2/3 of the inradius from the axis,
            spheres of 2/3 of the inradius (1.92 mm), each touching the two sides at its corner, the
            three meeting over the axis; 3 along the length;
  clump_27: the same three rods with 9 along the length (smoother sides, the same cross-section).
The clumps leave out the corners (toward a corner clump_3 reaches 2.89 mm from the axis, clump_9 and
clump_27 3.85 mm, the rounded prism 5.27 mm) and hold 47 %, 58 % and 66 % of the prism's volume
(grid-measured), so they are denser for the same mass.

Observables, from series.csv's remaining_fraction (t = 0 when the gate opens; crossings interpolated
linearly between samples): the times at which it falls to 0.5 and to 0.1, and the mean discharge
rate (particles/s) between 0.9 and 0.5; also the time to 0.2, since 0.1 lies near what the dead
zones beside the outlet keep. Cost, from summary.json: wall seconds of the discharge and
of the settling, and body-steps per second of the discharge; and the run's CPU seconds (user and
system, measured around the process), over its steps times its grains: the CPU time per body-step,
which the chart plots, since other work sharing the machine inflates wall times unevenly.

    /usr/bin/python3 studies/seed002/cost_chart.py run [--jobs 2] [--only RUN...]   # resumable
    /usr/bin/python3 studies/seed002/cost_chart.py collect   # cost.json and cost_chart.png
    /usr/bin/python3 studies/seed002/cost_chart.py table     # the README table from cost.json

Working runs under runs/seed002_cost/NAME/ (scene.toml, out/); results in studies/seed002/results/cost/.
"""
import argparse
import json
import math
import os
import pathlib
import re
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))


def _outputs():
    """grainflow.outputs, imported where run files are read: it needs numpy, the tables do not."""
    import grainflow.outputs
    return grainflow.outputs


SCENE = ROOT / "scenes/hopper_seed002_cost.toml"
RUNS = ROOT / "runs/seed002_cost"
DOCS = ROOT / "studies/seed002/results/cost"
SIDE, LENGTH, R_REF, RHO_REF, GRID_REF = 0.010, 0.010, 0.0005, 1400.0, 2.5e-4
INRADIUS = SIDE / (2 * math.sqrt(3))


def prism_table(r, grid=GRID_REF, density=RHO_REF):
    return (f'[[shape]]\nname = "grain"\nkind = "triangular_prism"\nside = {SIDE!r}\nlength = {LENGTH!r}\n'
            f"radius = {r!r}\ndensity = {density!r}\ngrid = {grid!r}\n")


def file_table(path, r, density=RHO_REF, grid=GRID_REF):
    return (f'[[shape]]\nname = "grain"\nkind = "file"\npath = "{path}"\nradius = {r!r}\n'
            f"density = {density!r}\ngrid = {grid!r}\n")


def clump_centres(rods, n_len):
    """Sphere centres (m) and radius of a clump: `rods` (1 or 3) positions in the cross-section
    times n_len along the length. One rod: the triangle's incircle (radius its inradius). Three:
    one toward each corner, on the median at 2/3 of the inradius from the centroid, with radius 2/3
    of the inradius, so each touches the two sides at its corner and the three meet over the
    centroid (no hole along the axis)."""
    if rods == 1:
        rho, plane = INRADIUS, [(0.0, 0.0)]
    else:
        rho = 2 * INRADIUS / 3
        # the triangle as the builder makes it: centroid at the origin, one corner on +y
        plane = [(rho * math.cos(math.radians(a)), rho * math.sin(math.radians(a))) for a in (90, 210, 330)]
    zs = [-(LENGTH / 2 - rho) + k * (LENGTH - 2 * rho) / (n_len - 1) for k in range(n_len)]
    return [(x, y, z) for (x, y) in plane for z in zs], rho


CLUMPS = {"clump_3": (1, 3), "clump_9": (3, 3), "clump_27": (3, 9)}


def write_obj(path, centres):
    lines = ["# spheres of a clump: one group of one vertex each (the shape's radius is the spheres')"]
    for k, (x, y, z) in enumerate(centres):
        lines += [f"o s{k}", f"v {x:.9g} {y:.9g} {z:.9g}"]
    path.write_text("\n".join(lines) + "\n")


VARIANTS = ["prism_r0.5", "prism_r0.25", "prism_r1.0", "sphere", "clump_3", "clump_9", "clump_27",
            "prism_grid1mm", "prism_grid2mm"]
# The pours: the scene's [[bodies]] seed (7) and others. A run is NAME (seed 7) or NAME_seedS.
POURS = [7, 11, 12, 13, 14]


def pours(variant):
    return POURS
LABELS = {"prism_r0.5": "prism r = 0.5 mm (reference)", "prism_r0.25": "prism r = 0.25 mm",
          "prism_r1.0": "prism r = 1.0 mm", "sphere": "1 sphere, same volume", "clump_3": "clump of 3 spheres",
          "clump_9": "clump of 9 spheres", "clump_27": "clump of 27 spheres",
          "prism_grid1mm": "prism r = 0.5 mm, grid 1 mm", "prism_grid2mm": "prism r = 0.5 mm, grid 2 mm"}


def run_name(variant, pour):
    return variant if pour == POURS[0] else f"{variant}_seed{pour}"


def all_runs():
    """Every variant's first pour, then every variant's second, and so on."""
    return [run_name(v, p) for p in POURS for v in VARIANTS if p in pours(v)]


def grainflow():
    for b in ("build-cost", "build"):
        p = ROOT / b / "grainflow"
        if p.exists():
            return p
    sys.exit("no grainflow binary: cmake --build build-cost --target grainflow")


def check(scene):
    out = subprocess.run([str(grainflow()), "check", str(scene)], capture_output=True, text=True)
    m = re.search(r"shape grain: (\d+) parts, r = (\S+) m, mass (\S+) kg, volume (\S+) m\^3, moments (\S+) (\S+) (\S+)",
                  out.stdout + out.stderr)
    if out.returncode != 0 or not m:
        sys.exit(f"grainflow check {scene} failed:\n{out.stdout}{out.stderr}")
    return {"parts": int(m.group(1)), "radius_m": float(m.group(2)), "mass_kg": float(m.group(3)),
            "volume_m3": float(m.group(4)), "moments_kg_m2": [float(m.group(k)) for k in (5, 6, 7)]}


def scene_text(shape, pour_seed=None):
    base = SCENE.read_text()
    if pour_seed is not None:
        assert base.count("\nseed = 7\n") == 1
        base = base.replace("\nseed = 7\n", f"\nseed = {pour_seed}\n")
    start = base.index('[[shape]]\nname = "grain"')
    end = base.index("\n\n", start) + 1
    return base[:start] + shape + base[end:]


def shape_for(name, density):
    d = RUNS / name
    name = name.split("_seed")[0]
    if name.startswith("prism_r"):
        return prism_table(float(name[len("prism_r"):]) * 1e-3, density=density)
    if name.startswith("prism_grid"):
        return prism_table(R_REF, grid=float(name[len("prism_grid"):-2]) * 1e-3, density=density)
    if name == "sphere":
        centres, rho = [(0.0, 0.0, 0.0)], (3 * REF["volume_m3"] / (4 * math.pi)) ** (1 / 3)
    else:
        centres, rho = clump_centres(*CLUMPS[name])
    write_obj(d / "grain.obj", centres)
    return file_table("grain.obj", rho, density=density)


REF = {}


def prepare(name):
    """The variant's scene, its density set for the reference mass (not for the grid variants)."""
    d = RUNS / name
    d.mkdir(parents=True, exist_ok=True)
    scene = d / "scene.toml"
    pour = int(name.split("_seed")[1]) if "_seed" in name else None
    scene.write_text(scene_text(shape_for(name, RHO_REF), pour))
    props = check(scene)
    if not name.startswith("prism_grid"):
        rho = REF["mass_kg"] / props["volume_m3"]
        scene.write_text(scene_text(shape_for(name, rho), pour))
        props = check(scene)
    props["density"] = props["mass_kg"] / props["volume_m3"]
    (d / "shape.json").write_text(json.dumps(props, indent=1))
    return scene


def finished(name):
    s = RUNS / name / "out/summary.json"
    return s.exists() and json.loads(s.read_text()).get("status") == "completed"


def reference():
    d = RUNS / "reference_shape"
    d.mkdir(parents=True, exist_ok=True)
    (d / "scene.toml").write_text(scene_text(prism_table(R_REF)))
    REF.update(check(d / "scene.toml"))


def in_flight():
    """Runs of this sweep that some grainflow process is running now (this runner's or another's)."""
    names = set()
    for c in pathlib.Path("/proc").glob("[0-9]*/cmdline"):
        try:
            argv = c.read_bytes().split(b"\0")
        except OSError:
            continue
        if len(argv) > 3 and argv[0].endswith(b"grainflow") and argv[1] == b"run":
            scene = pathlib.Path(argv[2].decode(errors="replace"))
            if scene.parent.parent == RUNS:
                names.add(scene.parent.name)
    return names


def run(args):
    """Runs what is not finished, at most args.jobs at a time counting runs started elsewhere."""
    reference()
    todo = [n for n in (args.only or all_runs()) if not finished(n)]
    while True:
        busy = in_flight()
        todo = [n for n in todo if n not in busy and not finished(n)]
        if not todo and not busy:
            break
        if todo and len(busy) < args.jobs:
            name = todo.pop(0)
            scene = prepare(name)
            out = RUNS / name / "out"
            log = open(RUNS / name / "run.log", "w")
            cmd = [sys.executable, str(pathlib.Path(__file__).resolve()), "timed", str(RUNS / name / "cpu.json"), "--",
                   "nice", "-n", "5", str(grainflow()), "run", str(scene), "--out", str(out), "--threads", "1",
                   "--set", "run.dt=4e-5"]  # the committed chart's step (the scene now takes 3.5e-5 s)
            print(f"{time.strftime('%H:%M:%S')} start {name}", flush=True)
            subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
            log.close()
            time.sleep(1)
            continue
        time.sleep(5)
        for n in busy - in_flight():
            print(f"{time.strftime('%H:%M:%S')} {n}: {'done' if finished(n) else 'stopped'}", flush=True)
    # Reap any children this runner started.
    try:
        while os.waitpid(-1, os.WNOHANG) != (0, 0):
            pass
    except ChildProcessError:
        pass


def crossing(t, f, level):
    for k in range(1, len(t)):
        if f[k] <= level < f[k - 1] or (f[k] <= level and k == 1 and f[0] > level):
            return t[k - 1] + (t[k] - t[k - 1]) * (f[k - 1] - level) / (f[k - 1] - f[k])
    return None


def measure(name):
    d = RUNS / name
    run = _outputs().Run(d / "out")
    s = run.summary
    t, f = run.series["time"].tolist(), run.series["remaining_fraction"].tolist()
    t90, t50, t20, t10 = (crossing(t, f, x) for x in (0.9, 0.5, 0.2, 0.1))
    n = s["bodies"]["moving"]
    shape = json.loads((d / "shape.json").read_text())
    cpu = json.loads((d / "cpu.json").read_text()) if (d / "cpu.json").exists() else None
    return {"name": name, "label": LABELS[name.split("_seed")[0]], "status": s["status"], "bodies": n,
            "members": s["bodies"]["members"], "dt": s["dt"], "critical_term": s["critical_term"],
            "t_0.9_s": t90, "t_0.5_s": t50, "t_0.2_s": t20, "t_0.1_s": t10,
            "rate_0.9_to_0.5_per_s": (0.4 * n / (t50 - t90)) if t50 is not None and t90 is not None else None,
            "remaining_at_end": f[-1], "simulated_s": t[-1],
            "wall_s": s["wall_seconds"], "settle_wall_s": s["settle"]["wall_seconds"],
            "total_wall_s": s["total_wall_seconds"], "body_steps_per_second": s["body_steps_per_second"],
            "cpu_s": cpu["user_s"] + cpu["sys_s"] if cpu else None,
            "cpu_us_per_body_step": (cpu["user_s"] + cpu["sys_s"]) * 1e6 / ((s["steps"] + s["settle"]["steps"]) * n)
            if cpu else None,
            "shape": shape}


def stats(values):
    got = [v for v in values if v is not None]
    if not got:
        return {"mean": None, "min": None, "max": None, "reached": 0}
    return {"mean": sum(got) / len(got), "min": min(got), "max": max(got), "reached": len(got)}


KEYS = ["t_0.5_s", "t_0.2_s", "t_0.1_s", "rate_0.9_to_0.5_per_s", "remaining_at_end", "wall_s", "settle_wall_s",
        "total_wall_s", "body_steps_per_second", "cpu_s", "cpu_us_per_body_step"]


def collect(args):
    DOCS.mkdir(parents=True, exist_ok=True)
    variants, missing = [], []
    for v in VARIANTS:
        runs = []
        for pour in pours(v):
            n = run_name(v, pour)
            if finished(n):
                runs.append(dict(measure(n), pour=pour))
            else:
                missing.append(n)
        if not runs:
            continue
        if (RUNS / v / "grain.obj").exists():
            (DOCS / f"{v}.obj").write_text((RUNS / v / "grain.obj").read_text())
        row = {"name": v, "label": LABELS[v], "shape": runs[0]["shape"], "members": runs[0]["members"],
               "bodies": runs[0]["bodies"], "dt": runs[0]["dt"], "pours": len(runs)}
        row.update({k: stats([r[k] for r in runs]) for k in KEYS})
        row["runs"] = runs
        variants.append(row)
    doc = {"scene": "scenes/hopper_seed002_cost.toml", "threads": 1, "pour_seeds": POURS,
           "machine": "2 cores shared with other work; at most 2 of these runs at a time, nice 5",
           "variants": variants, "missing": missing}
    (DOCS / "cost.json").write_text(json.dumps(doc, indent=1) + "\n")
    chart(variants, DOCS / "cost_chart.png")
    print(table(doc), end="")


# Where the labels of the three points at the reference's cost go, so that they do not overlap.
LABEL_OFFSETS = {"prism_r0.5": (8, -12), "prism_grid1mm": (8, 6), "prism_grid2mm": (-10, -3)}


def chart(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8.5, 5.8))
    colours = {"prism": "#0072B2", "clump": "#D55E00", "spher": "#009E73"}
    for r in rows:
        col = colours[r["name"][:5]]
        x = r["cpu_us_per_body_step"]["mean"]
        mk = "s" if "grid" in r["name"] else "o"
        for key, fill in (("t_0.5_s", col), ("t_0.2_s", "none")):
            st = r[key]
            if st["mean"] is None:
                continue
            ax.errorbar([x], [st["mean"]], yerr=[[st["mean"] - st["min"]], [st["max"] - st["mean"]]], fmt=mk,
                        color=col, mfc=fill, ms=8, capsize=3, lw=1)
        y = r["t_0.5_s"]["mean"]
        if y is not None:
            dx, dy = LABEL_OFFSETS.get(r["name"], (8, -3))
            ax.annotate(r["label"], (x, y), textcoords="offset points", xytext=(dx, dy), fontsize=8,
                        ha="left" if dx > 0 else "right")
    ax.set_xscale("log")
    xs = [r["cpu_us_per_body_step"]["mean"] for r in rows]
    if xs:
        ax.set_xlim(min(xs) / 1.5, max(xs) * 3)
    ax.set_xlabel("CPU time per body-step (µs, one thread, settling and discharge, mean of the pours; log scale)")
    ax.set_ylabel("time after the gate opens (s)")
    ax.set_title("Reduced seed-002 hopper, 300 grains of the same mass: discharge time against cost\n"
                 "filled: remaining fraction 0.5; open: 0.2; bars: range over the pours; squares: coarse "
                 "mass-property grid", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def fmt(v, spec):
    return "–" if v is None else format(v, spec)


def span(st, spec):
    if st["mean"] is None:
        return "not reached"
    text = f"{format(st['mean'], spec)} ({format(st['min'], spec)}–{format(st['max'], spec)})"
    return text


def table(doc):
    rows = ["| particle model | members | mass (mg) | moments (1e-9 kg m²) | t(0.5) (s) | t(0.2) (s) | "
            "t(0.1) (s) | rate 0.9→0.5 (grains/s) | left at 1.5 s | wall, discharge (s) | body-steps/s | "
            "CPU per body-step (µs) | × sphere | pours |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    sphere = next((r for r in doc["variants"] if r["name"] == "sphere"), None)
    base = sphere["cpu_us_per_body_step"]["mean"] if sphere else None
    for r in doc["variants"]:
        sh, n = r["shape"], r["pours"]
        t10 = r["t_0.1_s"]
        t10s = "not reached" if t10["mean"] is None else f"{t10['mean']:.2f} in {t10['reached']} of {n}"
        t20 = span(r["t_0.2_s"], ".2f") + (f" in {r['t_0.2_s']['reached']} of {n}" if 0 < r["t_0.2_s"]["reached"] < n else "")
        rows.append(f"| {r['label']} | {sh['parts']} | {sh['mass_kg'] * 1e6:.1f} | "
                    f"{' '.join(f'{m * 1e9:.2f}' for m in sh['moments_kg_m2'])} | {span(r['t_0.5_s'], '.2f')} | "
                    f"{t20} | {t10s} | {span(r['rate_0.9_to_0.5_per_s'], '.0f')} | "
                    f"{span(r['remaining_at_end'], '.2f')} | {r['wall_s']['mean']:.0f} | "
                    f"{r['body_steps_per_second']['mean']:,.0f} | {fmt(r['cpu_us_per_body_step']['mean'], '.2f')} | "
                    f"{fmt(r['cpu_us_per_body_step']['mean'] / base if base and r['cpu_us_per_body_step']['mean'] else None, '.1f')} | "
                    f"{n} |")
    rows.append("")
    rows.append("Mean (smallest–largest) over the pours; t(x): time after the gate opens at which the remaining "
                "fraction falls to x. Wall time of the discharge and body-steps/s from summary.json (body-steps "
                "counted with the grains present when the gate opens); CPU per body-step: the run's CPU seconds "
                "(settling and discharge) over its steps times 300 grains, and its ratio to the sphere's. The "
                "machine's 2 cores were shared with other runs (load about 7), so wall times are inflated and "
                "vary; compare the variants with one another, not with other tables.")
    if doc.get("missing"):
        rows.append("")
        rows.append("Not measured (runs not finished): " + ", ".join(doc["missing"]) + ".")
    return "\n".join(rows) + "\n"


def timed(argv):
    """Runs argv and writes the CPU seconds it used (user and system, its children's rusage) to a
    JSON file: the cost measure that other work on the machine disturbs least."""
    import resource
    dest, cmd = argv[0], argv[argv.index("--") + 1:]
    code = subprocess.call(cmd)
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    pathlib.Path(dest).write_text(json.dumps({"user_s": ru.ru_utime, "sys_s": ru.ru_stime, "exit": code}) + "\n")
    return code


def main():
    if sys.argv[1:2] == ["timed"]:
        sys.exit(timed(sys.argv[2:]))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--jobs", type=int, default=2)
    r.add_argument("--only", nargs="*", help="runs (NAME or NAME_seedS), in this order")
    sub.add_parser("collect")
    t = sub.add_parser("table")
    t.add_argument("file", nargs="?", default=str(DOCS / "cost.json"))
    a = ap.parse_args()
    if a.cmd == "run":
        run(a)
    elif a.cmd == "collect":
        collect(a)
    else:
        print(table(json.loads(pathlib.Path(a.file).read_text())), end="")


if __name__ == "__main__":
    main()

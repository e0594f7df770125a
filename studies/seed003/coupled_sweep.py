#!/usr/bin/python3
"""Error against cost of the coupled liquid and grains, and what breaks first (seed 003's first rung).

The case is scenes/liquid/settling_grain.toml (a 2 mm glass bead settling in a closed 3D box of
liquid); its observable the grain's speed at the end (0.3 s, about 13 relaxation times) against
Schiller-Naumann's terminal velocity, the closed form tests/coupled_settling_test.cpp checks at the
scene's settings. Three knobs, one at a time from the scene's l0 = 5 mm, k = 40, dt = 1 ms:
  l0    the liquid's spacing, with the smoothing radius kept at 2.5 l0 (d/l0 from 0.2 to 0.8);
  k     DEM sub-steps per liquid step at dt = 1 ms, down to and past the contact law's limit;
  dt    the liquid's step with dt/k kept at 2.5e-5 s, up to and past what the liquid's detectors allow
        (run.allow_unstable_dt = true lets the load check through; the run-time detectors still apply).
Each run's status and, where the program refused or stopped it, its message's first line are kept.

  /usr/bin/python3 studies/seed003/coupled_sweep.py run [--binary build/grainflow] [--out studies/seed003/results]
      runs them one after another, writes coupled_sweep.csv and coupled_sweep.png
  /usr/bin/python3 studies/seed003/coupled_sweep.py chart [studies/seed003/results/coupled_sweep.csv]
      the chart again from the csv
  /usr/bin/python3 studies/seed003/coupled_sweep.py table [studies/seed003/results/coupled_sweep.csv]
      the README's table (tools/readme/tables.py calls it)
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))


def _outputs():
    """grainflow.outputs, imported where run files are read: it needs numpy, the tables do not."""
    import grainflow.outputs
    return grainflow.outputs


SCENE = "scenes/liquid/settling_grain.toml"
# The scene's grain and liquid (the closed form's inputs).
D, RHO_P, RHO_L, MU, G = 2.0e-3, 2500.0, 1000.0, 0.01, 9.81
FIELDS = ["knob", "l0", "k", "dt", "status", "wall_seconds", "grain_m_s", "steady_change", "liquid_at_grain_m_s",
          "liquid_fraction_at_grain", "error", "message"]


def schiller_naumann_speed():
    """Schiller-Naumann's drag (1/2) rho_l C_d A w^2 balancing weight less buoyancy, by bisection."""
    volume, area = math.pi / 6.0 * D ** 3, math.pi / 4.0 * D ** 2
    net = (RHO_P - RHO_L) * volume * G
    lo, hi = 0.0, 10.0
    for _ in range(200):
        w = 0.5 * (lo + hi)
        re = RHO_L * D * w / MU
        cd = 24.0 / re * (1.0 + 0.15 * re ** 0.687)
        lo, hi = (w, hi) if 0.5 * RHO_L * cd * area * w * w < net else (lo, w)
    return 0.5 * (lo + hi)


def wen_yu_balance(eps):
    """The slip at which the project's drag law above eps = 0.8 (Wen-Yu, the force F_d / eps) carries
    the weight less buoyancy: 0.75 C_d rho_l |w| w V / d eps^-2.65, C_d at Re = eps rho_l d w / mu."""
    volume = math.pi / 6.0 * D ** 3
    net = (RHO_P - RHO_L) * volume * G
    lo, hi = 0.0, 10.0
    for _ in range(200):
        w = 0.5 * (lo + hi)
        re = eps * RHO_L * D * w / MU
        cd = 24.0 / re * (1.0 + 0.15 * re ** 0.687) if re <= 1000 else 0.44
        lo, hi = (w, hi) if 0.75 * cd * RHO_L * w * w * volume / D * eps ** -2.65 < net else (lo, w)
    return 0.5 * (lo + hi)


def cases():
    for l0 in (0.01, 0.0075, 0.005, 0.0035, 0.0025):
        yield "l0", l0, 40, 1e-3
    for k in (20, 32, 80, 160):
        yield "k", 0.005, k, 1e-3
    for dt in (5e-4, 2e-3, 4e-3, 8e-3, 1.6e-2, 3.2e-2, 6.4e-2):
        yield "dt", 0.005, round(dt / 2.5e-5), dt


def last_rows(path):
    """A series.csv as a list of rows, each {column: float} (read by the Python package)."""
    return _outputs().rows_of(_outputs().read_csv(path))


def one(binary, knob, l0, k, dt, work):
    out = os.path.join(work, f"{knob}_{l0:g}_{k}_{dt:g}")
    series = dt * math.ceil(0.005 / dt - 1e-9)  # the scene's 5 ms rows, or one a step
    cmd = [binary, "run", SCENE, "--out", out, "--quiet", "--set", f"liquid.l0={l0!r}",
           "--set", f"coupling.smoothing_radius={2.5 * l0!r}", "--set", f"coupling.substeps={k}",
           "--set", f"run.dt={dt!r}", "--set", f"output.series_interval={series!r}"]
    if knob == "dt":
        cmd += ["--set", "run.allow_unstable_dt=true"]
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    row = {"knob": knob, "l0": l0, "k": k, "dt": dt}
    lines = [line for line in p.stderr.splitlines() if line.strip()]
    said = [line for line in lines if "error" in line.lower() or "stop" in line.lower()] or lines[-1:]
    summary = _outputs().Run(out).summary if os.path.exists(os.path.join(out, "summary.json")) else {}
    row["status"] = summary.get("status", f"refused (exit {p.returncode})") if p.returncode == 0 else (
        f"stopped (exit {p.returncode})" if summary else f"refused (exit {p.returncode})")
    row["wall_seconds"] = summary.get("wall_seconds", "")
    row["message"] = (said[0] if said else "")[:240] if p.returncode != 0 else ""
    if p.returncode == 0:
        rows = last_rows(os.path.join(out, "series.csv"))
        end, t_end = rows[-1], float(rows[-1]["time"])
        before = min(rows, key=lambda r: abs(float(r["time"]) - (t_end - 0.05)))
        v, v0 = -float(end["grain_vy"]), -float(before["grain_vy"])
        row.update(grain_m_s=v, steady_change=(v - v0) / v, liquid_at_grain_m_s=-float(end["liquid_at_grain_vy"]),
                   liquid_fraction_at_grain=float(end["grain_liquid_fraction"]),
                   error=v / schiller_naumann_speed() - 1.0)
    return row


def chart(csv_path, path):
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.5, 4.6))
    for knob, marker in (("l0", "o"), ("k", "s"), ("dt", "^")):
        pts = [r for r in rows if r["knob"] == knob and r["error"] != ""]
        ax.plot([float(r["wall_seconds"]) for r in pts], [100 * float(r["error"]) for r in pts], marker=marker,
                ls="", label={"l0": "l0 (h = 2.5 l0)", "k": "k at dt = 1 ms", "dt": "dt, dt/k = 2.5e-5 s"}[knob])
        for r in pts:
            lab = {"l0": f"{1000 * float(r['l0']):g} mm", "k": f"k={r['k']}", "dt": f"{1000 * float(r['dt']):g} ms"}[knob]
            ax.annotate(lab, (float(r["wall_seconds"]), 100 * float(r["error"])), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")
    ax.set_xscale("log")
    ax.axhline(0, lw=0.6, color="k")
    ax.set_xlabel("wall time of the run (s, one core)")
    ax.set_ylabel("grain speed against Schiller-Naumann (%)")
    ax.set_title("Settling grain (scenes/liquid/settling_grain.toml): error against cost", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def run(args):
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for knob, l0, k, dt in cases():
            rows.append(one(args.binary, knob, l0, k, dt, work))
            print(rows[-1], flush=True)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "coupled_sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS, restval="")
        w.writeheader()
        w.writerows(rows)
    chart(os.path.join(args.out, "coupled_sweep.csv"), os.path.join(args.out, "coupled_sweep.png"))


def table(args):
    with open(args.file, newline="") as f:
        rows = list(csv.DictReader(f))
    print(f"Closed form: {schiller_naumann_speed():.4f} m/s (Schiller-Naumann, Re {RHO_L * D * schiller_naumann_speed() / MU:.1f}).\n")
    print("| knob | l0 (mm) | d/l0 | k | dt (ms) | DEM step (s) | status | grain speed (m/s) | against the closed form | "
          "change over the last 0.05 s | liquid at the grain (m/s) | liquid fraction at the grain | slip against the drag "
          "law's balance there | wall time (s) | what stopped it |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        l0, k, dt = float(r["l0"]), int(r["k"]), float(r["dt"])
        ok = r["error"] != ""
        cells = [r["knob"], f"{1000 * l0:g}", f"{D / l0:.2f}", str(k), f"{1000 * dt:g}", f"{dt / k:.3g}", r["status"],
                 f"{float(r['grain_m_s']):.4f}" if ok else "", f"{100 * float(r['error']):+.1f} %" if ok else "",
                 f"{100 * float(r['steady_change']):+.2f} %" if ok else "",
                 f"{float(r['liquid_at_grain_m_s']):.4f}" if ok else "",
                 f"{float(r['liquid_fraction_at_grain']):.4f}" if ok else "",
                 f"{100 * ((float(r['grain_m_s']) - float(r['liquid_at_grain_m_s'])) / wen_yu_balance(float(r['liquid_fraction_at_grain'])) - 1):+.2f} %"
                 if ok else "",
                 f"{float(r['wall_seconds']):.1f}" if r["wall_seconds"] else "", r["message"].replace("|", "/")]
        print("| " + " | ".join(cells) + " |")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    a = sub.add_parser("run")
    a.add_argument("--binary", default=os.path.join(ROOT, "build", "grainflow"))
    a.add_argument("--out", default=os.path.join(ROOT, "studies", "seed003", "results"))
    a.set_defaults(fn=run)
    a = sub.add_parser("table")
    a.add_argument("file", nargs="?", default=os.path.join(ROOT, "studies", "seed003", "results", "coupled_sweep.csv"))
    a.set_defaults(fn=table)
    a = sub.add_parser("chart")
    a.add_argument("file", nargs="?", default=os.path.join(ROOT, "studies", "seed003", "results", "coupled_sweep.csv"))
    a.set_defaults(fn=lambda args: chart(args.file, args.file.replace(".csv", ".png")))
    args = p.parse_args()
    args.fn(args)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Minimum fluidisation and Richardson-Zaki expansion of a liquid-fluidised bed (seed 003's ladder,
rungs three and four): scenes/liquid/fluidised_bed.toml, 8000 glass beads of 2 mm in a periodic liquid
column 30 x 30 mm across, driven up through them at a sweep of mean liquid speeds.

  /usr/bin/python3 studies/seed003/fluidised_bed.py settle [--binary build/grainflow]
      pours the beads into still liquid (3 s) and writes the packed bed the scene starts from,
      scenes/data/fluidised_bed_packed.csv
  /usr/bin/python3 studies/seed003/fluidised_bed.py run [--speeds 0.003 0.006 ...] [--binary build/grainflow]
                  [--runs runs/liquid/fluidised_bed] [--set KEY=VALUE ...] [--out studies/seed003/results]
      one run per drive speed (1.5 s each, from the packed bed) into the --runs folder, every run with the
      --set overrides, then collect (into --out)
  /usr/bin/python3 studies/seed003/fluidised_bed.py collect [--runs DIR] [--out studies/seed003/results]
      studies/seed003/results/fluidised_bed.csv and studies/seed003/results/fluidised_bed.png from the runs
  /usr/bin/python3 studies/seed003/fluidised_bed.py table [studies/seed003/results/fluidised_bed.csv]
      the README's table (tools/readme/tables.py calls it)

What each run gives (means over its last 0.5 s, from series.csv; the bed's geometry from final_state.csv):
  fluidised    drag above 0.95 and the bed 3 % higher than settled: then U is compared with Richardson-Zaki
  drag law     the drag law's own expansion: the U at which Ergun (the seed's law below eps = 0.8)
               carries the weight at eps_mid
  drag         the liquid's force on the beads along the column less Archimedes' buoyancy N V rho_l g,
               over the beads' weight less buoyancy N V (rho_p - rho_l) g: 1 once the bed is fluidised
  u            the liquid's speed read at the beads (what the drag law sees: the interstitial speed)
  eps_read     the liquid fraction read at the beads (the smoothing kernel's, what the drag law sees)
  eps_mid      the liquid fraction of the bed's middle half (beads counted by centre between a quarter and
               three quarters of the bed's height), away from the kernel's reach of the floor and the top
  U            eps_mid u, the superficial speed through the bed
References: Ergun's pressure gradient over the packed bed at its U and liquid fraction; minimum
fluidisation where Ergun's gradient at the settled bed's liquid fraction carries the bed's weight;
Richardson-Zaki U = u_t eps^n with u_t from Schiller-Naumann and n from Garside & Al-Dibouni (1977),
(5.1 - n)/(n - 2.7) = 0.1 Re_t^0.9.
"""
import argparse
import csv
import math
import os
import shutil
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from coupled_sweep import schiller_naumann_speed  # noqa: E402  (the same bead and liquid)
from coupled_sweep import _outputs, last_rows  # noqa: E402  (the Python package, read lazily)

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SCENE = "scenes/liquid/fluidised_bed.toml"
PACKED = "scenes/data/fluidised_bed_packed.csv"
RUNS = "runs/liquid/fluidised_bed"
D, RHO_P, RHO_L, MU, G = 2.0e-3, 2500.0, 1000.0, 0.01, 9.81
AREA, FLOOR = 0.03 * 0.03, 0.02  # m^2 the column's cross-section, m the grains' floor
VOLUME = math.pi / 6.0 * D ** 3
SPEEDS = [0.004, 0.008, 0.012, 0.016, 0.02, 0.025, 0.03, 0.04, 0.05, 0.06]
POUR = ('fill.0={kind="random", region={shape="box", lo=[0.02,0.0,0.0], hi=[0.19,0.03,0.03]}, '
        'count={glass=8000}}')
FIELDS = ["drive", "status", "wall_seconds", "grains", "u", "eps_read", "eps_mid", "U", "height", "eps_bed", "drag",
          "drag_drift", "u_drift", "grain_speed", "ergun", "law_U", "law_error", "rz_U", "rz_error"]


def rz_exponent(re_t):
    """Garside & Al-Dibouni: (5.1 - n)/(n - 2.7) = 0.1 Re_t^0.9."""
    a = 0.1 * re_t ** 0.9
    return (5.1 + 2.7 * a) / (1.0 + a)


def ergun_gradient(u_sup, eps):
    e3 = eps ** 3
    return 150 * MU * (1 - eps) ** 2 * u_sup / (e3 * D * D) + 1.75 * RHO_L * (1 - eps) * u_sup ** 2 / (e3 * D)


def ergun_balance(eps):
    """U at which Ergun's gradient equals the bed's weight less buoyancy per volume: minimum fluidisation
    at the settled bed's eps, and the drag law's own expansion (Ergun up to eps = 0.8) above it."""
    target = (1 - eps) * (RHO_P - RHO_L) * G
    lo, hi = 0.0, 1.0
    for _ in range(200):
        u = 0.5 * (lo + hi)
        lo, hi = (u, hi) if ergun_gradient(u, eps) < target else (lo, u)
    return 0.5 * (lo + hi)


def grainflow(binary, out, sets):
    cmd = [binary, "run", SCENE, "--out", out, "--threads", "1", "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    return subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)


def settle(a):
    out = os.path.join(RUNS, "settle")
    r = grainflow(a.binary, out, ["drive.mean_velocity=0", "run.duration=3.0", POUR])
    if r.returncode != 0:
        sys.exit(f"settle failed: {r.stderr.strip()}")
    shutil.copy(os.path.join(ROOT, out, "final_state.csv"), os.path.join(ROOT, PACKED))
    print(f"packed bed written to {PACKED}")


def run(a):
    for u in a.speeds:
        out = os.path.join(a.runs, f"drive_{u:.3f}")
        r = grainflow(a.binary, out, [f"drive.mean_velocity={u}"] + a.set)
        print(f"drive {u} m/s: exit {r.returncode}", flush=True)
    collect(a)


def read_state(path):
    """The grains' x from a state file, without numpy: the ladder's table reads the packed bed's state."""
    with open(path, newline="") as fh:
        return [float(r["x"]) for r in csv.DictReader(l for l in fh if not l.startswith("#"))]


def bed(xs):
    """Height (m, floor to the 99th percentile of the centres plus a radius) and the middle half's
    liquid fraction."""
    s = sorted(xs)
    top = s[int(0.99 * (len(s) - 1))] + D / 2
    h = top - FLOOR
    lo, hi = FLOOR + 0.25 * h, FLOOR + 0.75 * h
    n = sum(1 for x in xs if lo <= x < hi)
    return h, 1 - n * VOLUME / (AREA * (hi - lo)), 1 - len(xs) * VOLUME / (AREA * h)


def one(folder, drive, u_t, n_rz):
    summary = _outputs().Run(folder).summary
    rows = last_rows(os.path.join(folder, "series.csv"))
    t_end = float(rows[-1]["time"])
    last = [r for r in rows if float(r["time"]) >= t_end - 0.5 + 1e-9]
    n = int(float(rows[-1]["grains"]))
    mean = lambda k, rs=last: statistics.fmean(float(r[k]) for r in rs)
    weight = n * VOLUME * (RHO_P - RHO_L) * G
    archimedes = n * VOLUME * RHO_L * G
    drag = lambda rs: (statistics.fmean(float(r["liquid_force_x"]) for r in rs) - archimedes) / weight
    half = len(last) // 2
    h, eps_mid, eps_bed = bed(read_state(os.path.join(folder, "final_state.csv")))
    u = mean("liquid_at_grain_vx")
    U = eps_mid * u
    fluidised = drag(last) > 0.95 and h > 1.03 * bed(read_state(os.path.join(ROOT, PACKED)))[0]
    rz = u_t * eps_mid ** n_rz
    return {"drive": drive, "status": summary["status"], "wall_seconds": round(summary["wall_seconds"], 1),
            "grains": n, "u": u, "eps_read": mean("grain_liquid_fraction"), "eps_mid": eps_mid, "U": U, "height": h, "eps_bed": eps_bed, "drag": drag(last),
            "drag_drift": drag(last[half:]) - drag(last[:half]),
            "u_drift": mean("liquid_at_grain_vx", last[half:]) / mean("liquid_at_grain_vx", last[:half]) - 1,
            "grain_speed": mean("grain_vx"),
            "ergun": ergun_gradient(U, eps_bed) * h * AREA / weight,
            "law_U": ergun_balance(eps_mid) if fluidised and eps_mid <= 0.8 else "",
            "law_error": U / ergun_balance(eps_mid) - 1 if fluidised and eps_mid <= 0.8 else "",
            "rz_U": rz if fluidised else "", "rz_error": U / rz - 1 if fluidised else ""}


def collect(a):
    u_t = schiller_naumann_speed()
    n_rz = rz_exponent(RHO_L * D * u_t / MU)
    rows = []
    for name in sorted(os.listdir(os.path.join(ROOT, a.runs))):
        if name.startswith("drive_"):
            folder = os.path.join(ROOT, a.runs, name)
            if os.path.isfile(os.path.join(folder, "final_state.csv")):  # finished
                rows.append(one(folder, float(name[6:]), u_t, n_rz))
    rows.sort(key=lambda r: r["drive"])
    with open(os.path.join(ROOT, a.out, "fluidised_bed.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, FIELDS)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    chart(os.path.join(ROOT, a.out, "fluidised_bed.csv"))


def settled_eps():
    return bed(read_state(os.path.join(ROOT, PACKED)))[2]


def chart(path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = list(csv.DictReader(open(path)))
    u_t = schiller_naumann_speed()
    n_rz = rz_exponent(RHO_L * D * u_t / MU)
    eps_mf = settled_eps()
    u_mf = ergun_balance(eps_mf)
    U = [float(r["U"]) for r in rows]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    a1.plot([1e3 * x for x in U], [float(r["drag"]) for r in rows], "o-", label="grainflow: drag / (weight - buoyancy)")
    us = [u_mf * k / 40 for k in range(0, 81)]
    a1.plot([1e3 * x for x in us], [min(ergun_gradient(x, eps_mf) / ((1 - eps_mf) * (RHO_P - RHO_L) * G), 1.0) for x in us],
            "k--", label=f"Ergun at the settled bed's eps {eps_mf:.3f}, then 1")
    a1.axvline(1e3 * u_mf, color="grey", lw=0.8)
    a1.set_xlabel("superficial speed U (mm/s)")
    a1.set_ylabel("bed pressure drop / bed weight")
    a1.legend(fontsize=8)
    fl = [r for r in rows if r["rz_U"]]
    e = [float(r["eps_mid"]) for r in fl]
    steady = [abs(float(r["u_drift"])) < 0.1 for r in fl]
    for keep, style, name in ((True, "o", "grainflow, steady over the last 0.5 s"),
                              (False, "o", "grainflow, not steady (open)")):
        pts = [(x, float(r["U"])) for x, r, s in zip(e, fl, steady) if s == keep]
        if pts:
            a2.loglog(*zip(*pts), style, mfc=None if keep else "none", color="C0", label=name)
    grid = [0.4 + 0.005 * k for k in range(0, 100)]
    a2.loglog(grid, [u_t * x ** n_rz for x in grid], "k--", label=f"Richardson-Zaki, n = {n_rz:.2f}")
    law = [x for x in grid if x <= 0.8]
    a2.loglog(law, [ergun_balance(x) for x in law], "k:", label="the drag law's balance (Ergun)")
    a2.set_xlabel("liquid fraction eps")
    a2.set_ylabel("superficial speed U (m/s)")
    a2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path.replace(".csv", ".png"), dpi=110)


def table(path):
    rows = list(csv.DictReader(open(path)))
    u_t = schiller_naumann_speed()
    re_t = RHO_L * D * u_t / MU
    n_rz = rz_exponent(re_t)
    eps_mf = settled_eps()
    print(f"Settled bed: liquid fraction {eps_mf:.3f}; Ergun's minimum fluidisation there "
          f"{1e3 * ergun_balance(eps_mf):.2f} mm/s. Terminal speed {u_t:.4f} m/s (Re_t {re_t:.1f}); "
          f"Richardson-Zaki n = {n_rz:.2f} (Garside & Al-Dibouni).\n")
    print("| drive (m/s) | status | u at beads (mm/s) | eps read at beads | bed height (mm) | eps, whole bed "
          "| eps, middle half | U = eps u (mm/s) "
          "| drag / (weight - buoyancy) | its change over the last 0.5 s | u's change over it "
          "| Ergun over the bed / weight | the drag law's balance U (mm/s) | U against it "
          "| Richardson-Zaki U (mm/s) | U against it | wall time (s) |")
    print("|---" * 17 + "|")
    for r in rows:
        rz = f"{1e3 * float(r['rz_U']):.2f}" if r["rz_U"] else ""
        law = f"{1e3 * float(r['law_U']):.2f}" if r["law_U"] else ""
        law_err = f"{100 * float(r['law_error']):+.1f} %" if r["law_error"] else ""
        err = f"{100 * float(r['rz_error']):+.1f} %" if r["rz_error"] else ""
        print(f"| {float(r['drive']):.3f} | {r['status']} | {1e3 * float(r['u']):.2f} | {float(r['eps_read']):.3f} "
              f"| {1e3 * float(r['height']):.1f} | {float(r['eps_bed']):.3f} "
              f"| {float(r['eps_mid']):.3f} | {1e3 * float(r['U']):.2f} | {float(r['drag']):.3f} "
              f"| {float(r['drag_drift']):+.3f} | {100 * float(r['u_drift']):+.1f} % | {float(r['ergun']):.3f} | {law} | {law_err} | {rz} | {err} "
              f"| {r['wall_seconds']} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    for name in ("settle", "run"):
        p = sub.add_parser(name)
        p.add_argument("--binary", default=os.path.join(ROOT, "build", "grainflow"))
        p.add_argument("--out", default="studies/seed003/results")
        if name == "run":
            p.add_argument("--speeds", type=float, nargs="+", default=SPEEDS)
            p.add_argument("--runs", default=RUNS, help="work folder of the runs (one drive_U folder per speed)")
            p.add_argument("--set", action="append", default=[], help="a scene override for every run, as grainflow's --set")
    c = sub.add_parser("collect")
    c.add_argument("--out", default="studies/seed003/results")
    c.add_argument("--runs", default=RUNS)
    t = sub.add_parser("table")
    t.add_argument("csv", nargs="?", default=os.path.join(ROOT, "studies/seed003/results/fluidised_bed.csv"))
    a = ap.parse_args()
    {"settle": settle, "run": run, "collect": collect, "table": lambda a: table(a.csv)}[a.cmd](a)


if __name__ == "__main__":
    main()

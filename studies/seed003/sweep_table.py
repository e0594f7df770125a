#!/usr/bin/python3
"""The README's tables of the liquid sweeps (studies/seed003/sweep.py): every run, and the failure boundary.

    /usr/bin/python3 studies/seed003/sweep_table.py SWEEP_CSV              every run of the file
    /usr/bin/python3 studies/seed003/sweep_table.py --boundary CSV [CSV]   per case, the largest time step that
                                                                        completed and the smallest one stopped

The cost of a run is its fluid particle-steps (steps × fluid nodes), the product of the file's
particle_steps_per_s and wall_seconds: a count, the same on any machine. The wall time is also shown; the
sweeps ran on 2 cores shared with other work.
"""
import csv
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import sweep  # noqa: E402  (the cases' scenes and durations)

# The length l0 is a fraction of, and the name of the error each case's sweep measures.
LENGTH = {"hydrostatic": ("H", 0.1), "dam_break": ("a", 0.146), "poiseuille": ("L", 0.01)}
ERROR = {
    "hydrostatic": "size of the floor pressure error against rho g H, mean from 0.5 s",
    "dam_break": "mean size of the front error against Koshizuka & Oka",
    "poiseuille": "worst centre-velocity error against the series, width L",
}
TITLE = {
    "hydrostatic_2d": "hydrostatic tank 2D", "hydrostatic_3d": "hydrostatic tank 3D", "dam_break_2d": "dam break 2D",
    "dam_break_3d": "dam break 3D", "poiseuille_2d": "Poiseuille 2D",
}


def family(case):
    return next(k for k in LENGTH if case.startswith(k))


def spacing(case, l0):
    sym, length = LENGTH[family(case)]
    return f"{sym}/{round(length / l0)}"


def g(v, digits=2):
    """`v` in exponent notation with `digits` significant digits: 1.5e-3."""
    mantissa, exponent = f"{v:.{digits - 1}e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def step(v):
    """A time step or a small number as written in the scenes (5e-4, 1.5e-3, 1.11e-4); from 0.01 up, 0.1."""
    if v >= 0.01:
        return f"{v:.3g}"
    mantissa, exponent = f"{v:.2e}".split("e")
    return f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"


def load(paths):
    rows = []
    for p in paths:
        with open(p, newline="") as f:
            rows += list(csv.DictReader(f))
    return rows


def runs(path):
    rows = load([path])
    print("| case (simulated time; error measured) | varied | l0 | dt (s) | CFL | diffusion number | status | error "
          "| fluid particle-steps | wall time (s, 2 cores shared with other work) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    shown = set()
    for r in rows:
        case = r["case"]
        head = ""
        if case not in shown:
            shown.add(case)
            head = f"{TITLE[case]} ({sweep.CASES[case][1]:g} s; {ERROR[family(case)]})"
        l0, dt = float(r["l0"]), float(r["dt"])
        done = r["status"] == "completed"
        err = f"{100 * float(r['error']):.2f} %" if done else "—"
        status = "completed" if done else f"stopped: {r['failure']}"
        work = float(r["particle_steps_per_s"]) * float(r["wall_seconds"])
        print(f"| {head} | {'l0 (dt with it)' if r['knob'] == 'resolution' else 'dt'} | {spacing(case, l0)} | {step(dt)} "
              f"| {float(r['cfl']):.2g} | {step(float(r['diffusion']))} | {status} | {err} | {g(work)} "
              f"| {float(r['wall_seconds']):.3g} |")


def laplacian_bound(dim, re=2.1):
    """Largest stable diffusion number nu dt / l0^2 of the explicit MPS Laplacian on a full lattice, lambda /
    (2 d l0^2), with Zhang's kernel and the seed's re = 2.1 l0."""
    w = lambda r: re / (0.85 * r + 0.15 * re) - 1 if r < re else 0.0  # noqa: E731
    m = int(re) + 1
    pts = [(i, j, k) for i in range(-m, m + 1) for j in range(-m, m + 1) for k in (range(-m, m + 1) if dim == 3 else [0])
           if (i, j, k) != (0, 0, 0)]
    n0 = sum(w(math.sqrt(i * i + j * j + k * k)) for i, j, k in pts)
    lam = sum(w(math.sqrt(i * i + j * j + k * k)) * (i * i + j * j + k * k) for i, j, k in pts) / n0
    return lam / (2 * dim)


def boundary(paths):
    rows = load(paths)
    print("| case | completes up to | stops at | detectors that stopped the larger steps |")
    print("|---|---|---|---|")
    for case in dict.fromkeys(r["case"] for r in rows):
        ts = sorted((r for r in rows if r["case"] == case and r["knob"] == "time_step"), key=lambda r: float(r["dt"]))
        viscous = family(case) == "poiseuille"
        key, name = ("diffusion", "diffusion number") if viscous else ("cfl", "CFL")
        ok = [r for r in ts if r["status"] == "completed"]
        bad = [r for r in ts if r["status"] != "completed"]
        last = ok[-1]
        up_to = (f"{name} {float(last[key]):.2g} (dt {step(float(last['dt']))} s; error then "
                 f"{100 * float(last['error']):.1f} %)")
        if bad:
            first = bad[0]
            stops = f"{name} {float(first[key]):.2g} (dt {step(float(first['dt']))} s)"
            by = {}
            for r in bad:
                by.setdefault(r["failure"], []).append(step(float(r["dt"])))
            detectors = "; ".join(f"{f} (dt {', '.join(d)} s)" for f, d in by.items())
            if viscous:
                detectors += (f": the viscous term's explicit instability (the MPS Laplacian's bound "
                              f"`λ/(2d l0²)` is {laplacian_bound(2 if case.endswith('2d') else 3):.2f})")
        else:
            stops, detectors = "not reached in the swept range", "—"
        print(f"| {TITLE[case]}, l0 = {spacing(case, float(last['l0']))} | {up_to} | {stops} | {detectors} |")


def main(argv):
    if argv and argv[0] == "--boundary":
        boundary(argv[1:])
    elif len(argv) == 1:
        runs(argv[0])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])

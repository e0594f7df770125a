#!/usr/bin/python3
"""Which model term sets the grains' spin in seed 003's transport pipe: the shipped pipe
(scenes/liquid/transport_pipe.toml at 2 m/s, as studies/seed003/transport_pipe.py runs it) against one change at
a time, each over the same 2 s from rest, with the same statistics from 1.0 s on (transport_pipe.py's
frames.csv rows and measure()).

  /usr/bin/python3 studies/seed003/spin_candidates.py run [--only NAME ...] [--threads 1] [--parallel 2]
      each candidate into runs/liquid/spin_candidates/<name>, then collect
  /usr/bin/python3 studies/seed003/spin_candidates.py table [studies/seed003/results/spin_candidates.json]
      the results page's table (tools/readme/tables.py calls it; needs no numpy)
  /usr/bin/python3 studies/seed003/spin_candidates.py collect
      studies/seed003/results/spin_candidates.json: per candidate its overrides, mean |omega|, var(r/R) with the
      frames' spread, the volume-fraction peak, the grains' mean axial speed, the wall time, the mean spin at
      each frame, and half the liquid's curl at the grains (half_curl: the spin at which the liquid's torque
      on a grain vanishes), read from each frame by a least-squares linear fit to the fluid nodes' velocities
      within 40 mm of the grain, weighted by the coupling's Wendland shape (as the coupling reads it)

Candidates (CANDIDATES below): the shipped scene; the liquid's torque on the grains (rotational drag, Dennis et
al.); no friction between grains and the pipe's wall (what the wall's contacts give the spin); no friction
between grains (the wall's kept at 0.2: what the grains' own collisions give it); a constant eddy viscosity
5.7e-4 m^2/s, a developed turbulent pipe's near its axis at 2 m/s (kappa u* R / 6 with u* = 0.083 m/s from the
smooth-pipe friction factor 0.0137 at Re_D = 4e5): the momentum turbulence would carry into the notch that the
grains' cloud cuts into the liquid; Prandtl's mixing length with Nikuradse's profile (liquid.turbulence), the
eddy viscosity a turbulent pipe has, small at the wall and in the flat core; Saffman's shear lift with Mei's
factor and the Magnus spin lift (coupling.shear_lift, coupling.spin_lift), and a restitution of 0.5 for every
contact instead of 0.9, run after the pipe's solver became the
multigrid kept 20 steps (the same physics to the solver's tolerance). collect keeps the rows of candidates whose
run folders are gone.
"""
import argparse
import concurrent.futures
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import transport_pipe as tp  # noqa: E402

SPEED, DURATION, FROM = 2.0, 2.0, 1.0
RUNS = os.path.join(ROOT, "runs/liquid/spin_candidates")
OUT = os.path.join(ROOT, "studies/seed003/results/spin_candidates.json")
CANDIDATES = {
    "shipped": [],
    "rotational_drag": ['coupling.rotational_drag="dennis"'],
    "wall_frictionless": ["contact.wall={friction=0.0}"],
    "grains_frictionless": ["contact.friction=0.0", "contact.wall={friction=0.2}"],
    "eddy_viscosity": ["liquid.eddy_viscosity=5.7e-4"],
    "mixing_length": ['liquid.turbulence="mixing_length"'],
    "shear_lift": ['coupling.shear_lift="saffman_mei"'],
    "spin_lift": ['coupling.spin_lift="oesterle_bui_dinh"'],
    "restitution_0.5": ["contact.restitution=0.5"],
}
# The mixing length at the seed's other transport speeds (the same 2 s from rest): its trend with the speed.
SPEEDS = {f"mixing_length_u{u}": u for u in (3, 4, 5)}
for _name in SPEEDS:
    CANDIDATES[_name] = ['liquid.turbulence="mixing_length"']


def run_one(name, binary, threads):
    folder = os.path.join(RUNS, name)
    shutil.rmtree(folder, ignore_errors=True)
    sets = tp.overrides(SPEEDS.get(name, SPEED), 0.0, DURATION) + CANDIDATES[name]
    cmd = [binary, "run", os.path.join(ROOT, tp.SCENE), "--out", folder, "--threads", str(threads)]
    for s in sets:
        cmd += ["--set", s]
    with open(os.path.join(RUNS, name + ".log"), "w") as log:
        rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT)
    tp.update_frames(folder)
    return name, rc


def frame_files(folder, part):
    return dict(tp.frames(folder, part))


def half_curl(folder):
    """Per frame from FROM on: the mean over grains of |curl u| / 2 at the grain (rad/s)."""
    import numpy as np
    from grainflow.vtp import read_vtp
    h = 0.04
    liquid, grains = frame_files(folder, "liquid"), frame_files(folder, "grains")
    out = []
    for t in sorted(liquid):
        if t < FROM - 1e-9 or t not in grains:
            continue
        liq, g = read_vtp(liquid[t]), read_vtp(grains[t])
        fluid = np.array(tp.node_kinds(liq)) == tp.FLUID
        P, U = np.array(liq["Points"])[fluid], np.array(liq["velocity"])[fluid]
        values = []
        for p in np.array(g["Points"]):
            d = P - p
            d[:, 0] -= tp.LENGTH * np.round(d[:, 0] / tp.LENGTH)
            r = np.linalg.norm(d, axis=1)
            near = r < h
            q = r[near] / h
            w = (1 - q) ** 4 * (1 + 4 * q)
            dx = d[near] - np.average(d[near], axis=0, weights=w)
            du = U[near] - np.average(U[near], axis=0, weights=w)
            D = np.linalg.solve((dx * w[:, None]).T @ dx, (dx * w[:, None]).T @ du)  # D[a, b] = du_b / dx_a
            curl = np.array([D[1, 2] - D[2, 1], D[2, 0] - D[0, 2], D[0, 1] - D[1, 0]])
            values.append(0.5 * np.linalg.norm(curl))
        out.append(float(np.mean(values)))
    return out


def collect():
    out = {"speed_m_s": SPEED, "duration_s": DURATION, "statistics_from_s": FROM, "scene": tp.SCENE,
           "seed_2_m_s": dict(zip(("r_variance", "phi_peak_r", "phi_peak_percent", "spin"), tp.SEED[2])),
           "candidates": {}}
    # A candidate whose run folder is gone keeps its row from the file (runs/ is not kept between sessions).
    kept = json.load(open(OUT))["candidates"] if os.path.exists(OUT) else {}
    for name, sets in CANDIDATES.items():
        folder = os.path.join(RUNS, name)
        m = tp.measure(folder, FROM) if os.path.isdir(folder) else None
        if m is None:
            if name in kept:
                out["candidates"][name] = kept[name]
            continue
        rows = tp.read_rows(os.path.join(folder, "frames.csv"))
        curl = half_curl(folder)
        speed = SPEEDS.get(name, SPEED)
        out["candidates"][name] = {"speed_m_s": speed, "overrides": sets, **{k: m[k] for k in (
            "status", "frames", "to_s", "spin", "r_variance", "r_variance_frame_sd", "phi_peak_r", "phi_peak",
            "grain_speed", "wall_seconds")},
            "half_curl_at_grains": sum(curl) / len(curl) if curl else None,
            "centre_liquid_over_U": m["u_profile"][0] / speed,
            "spin_per_frame": [[round(r["time"], 3), round(r["spin"], 3)] for r in rows]}
    with open(OUT, "w") as fh:
        json.dump(out, fh, indent=1)
        fh.write("\n")
    print(json.dumps(out["candidates"], indent=1))


LABELS = {
    "shipped": "the shipped scene",
    "rotational_drag": "liquid torque (rotational drag, Dennis et al.)",
    "wall_frictionless": "no grain-wall friction",
    "grains_frictionless": "no grain-grain friction (wall 0.2)",
    "eddy_viscosity": "eddy viscosity 5.7e-4 m²/s",
    "mixing_length": "mixing-length eddy viscosity (Nikuradse)",
    "shear_lift": "shear lift (Saffman-Mei)",
    "spin_lift": "spin lift (Magnus, Oesterlé-Bui Dinh)",
    "restitution_0.5": "restitution 0.5 (the scene: 0.9)",
    **{n: "mixing-length eddy viscosity (Nikuradse)" for n in SPEEDS},
}


def table(path):
    data = json.load(open(path))
    print("| run | U (m/s) | mean spin (rad/s) | half the curl at the grains (rad/s) | var(r/R) (frames' sd) | peak r/R (%) "
          "| grains' mean speed (m/s) | centre liquid / U |")
    print("|---|---|---|---|---|---|---|---|")
    for name, c in data["candidates"].items():
        print(f"| {LABELS.get(name, name)} | {c.get('speed_m_s', data['speed_m_s']):g} | {c['spin']:.2f} | {c['half_curl_at_grains']:.2f} "
              f"| {c['r_variance']:.4f} (± {c['r_variance_frame_sd']:.4f}) | {c['phi_peak_r']:.2f} ({c['phi_peak']:.1f}) "
              f"| {c['grain_speed']:.2f} | {c['centre_liquid_over_U']:.3f} |")
    for u in (2, 3, 4, 5):
        var, pr, pp, spin = tp.SEED[u]
        peak = "—" if pr is None else f"{pr:.2f} ({pp:.1f})"
        print(f"| the paper, after 100 s | {u} | {spin:.2f} | — | {var:.4f} | {peak} | — | above 1 |")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("command", choices=["run", "collect", "table"])
    p.add_argument("path", nargs="?", default=OUT)
    p.add_argument("--only", nargs="*", default=None)
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--parallel", type=int, default=2)
    p.add_argument("--binary", default=os.path.join(ROOT, "build/grainflow"))
    a = p.parse_args()
    if a.command == "table":
        table(a.path)
        return
    if a.command == "run":
        os.makedirs(RUNS, exist_ok=True)
        names = a.only or list(CANDIDATES)
        with concurrent.futures.ThreadPoolExecutor(a.parallel) as pool:
            for name, rc in pool.map(lambda n: run_one(n, a.binary, a.threads), names):
                print(f"{name}: exit {rc}", flush=True)
    collect()


if __name__ == "__main__":
    main()

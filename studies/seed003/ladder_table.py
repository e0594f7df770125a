#!/usr/bin/python3
"""Seed 003's validation ladder in one table: reference, ours, error and cost per rung, from the rungs'
result files (each written by the command the README gives beside the rung):

  studies/seed003/results/settling_grain.csv       the settling grain (tests/coupled_settling_test.cpp)
  studies/seed003/results/coupled_sweep.csv        its cost at the scene's l0 = 5 mm, k = 40, dt = 1 ms
  studies/seed003/results/ergun_bed.csv            the fixed packed bed's sweep (tests/coupled_packed_bed_test.cpp)
  studies/seed003/results/packed_bed_summary.json  the packed bed scene run once: build/grainflow run
                                       scenes/liquid/packed_bed.toml (its summary.json)
  studies/seed003/results/fluidised_bed.csv        the fluidised bed's sweep (studies/seed003/fluidised_bed.py)

    /usr/bin/python3 studies/seed003/ladder_table.py
"""
import csv
import json
import os
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fluidised_bed as bed  # noqa: E402


def rows(name):
    return list(csv.DictReader(open(os.path.join(ROOT, "studies", "seed003", "results", name))))


def span(values, fmt="{:+.1f} %"):
    lo, hi = min(values), max(values)
    return fmt.format(lo) if abs(hi - lo) < 0.05 else f"{fmt.format(lo)} to {fmt.format(hi)}"


def main():
    print("| rung | reference | reference value | ours | error | cost (one core, wall) |")
    print("|---|---|---|---|---|---|")
    s = rows("settling_grain.csv")[-1]
    cost = [r for r in rows("coupled_sweep.csv") if r["knob"] == "l0" and abs(float(r["l0"]) - 0.005) < 1e-9][0]
    err = 100 * (float(s["grain_m_s"]) / float(s["closed_form_m_s"]) - 1)
    print(f"| 1. one grain settling, Re {float(s['Re']):.1f} | Schiller-Naumann terminal speed "
          f"| {float(s['closed_form_m_s']):.4f} m/s | {float(s['grain_m_s']):.4f} m/s | {err:+.1f} % "
          f"| {float(cost['wall_seconds']):.1f} s for 0.3 s, 1 grain |")
    e = rows("ergun_bed.csv")
    pb = json.load(open(os.path.join(ROOT, "studies", "seed003", "results", "packed_bed_summary.json")))
    re = [float(r["Re_p"]) for r in e]
    print(f"| 2. fixed packed bed, Re_p {min(re):.2g} to {max(re):.2g}, column core | Ergun's pressure gradient "
          f"| {float(e[0]['dPdL_ergun_core']):.4g} to {float(e[-1]['dPdL_ergun_core']):.4g} Pa/m "
          f"| {float(e[0]['dPdL_drive']):.4g} to {float(e[-1]['dPdL_drive']):.4g} Pa/m "
          f"| {span([float(r['error_core_pct']) for r in e])} "
          f"| {pb['wall_seconds']:.1f} s for {pb['simulated_time']:.2g} s, {pb['grains']} grains, {pb['fluid_nodes']} nodes |")
    f = rows("fluidised_bed.csv")
    eps_mf = bed.settled_eps()
    u_mf = bed.ergun_balance(eps_mf)
    packed = [r for r in f if not r["rz_U"]]
    lifted = [r for r in f if r["rz_U"]]
    below, above = float(packed[-1]["U"]), float(lifted[0]["U"])
    wall = [float(r["wall_seconds"]) for r in f]
    cost = f"{min(wall):.0f} to {max(wall):.0f} s a speed for 1.5 s, {int(f[0]['grains'])} grains"
    print(f"| 3. minimum fluidisation | Ergun at the settled bed's liquid fraction {eps_mf:.3f} "
          f"| {1e3 * u_mf:.2f} mm/s | between {1e3 * below:.2f} and {1e3 * above:.2f} mm/s "
          f"| {100 * (below / u_mf - 1):+.0f} to {100 * (above / u_mf - 1):+.0f} % | {cost} |")
    steady = [r for r in lifted if abs(float(r["u_drift"])) < 0.1]
    eps = [float(r["eps_mid"]) for r in steady]
    print(f"| 4. bed expansion (hindered settling), eps {min(eps):.2f} to {max(eps):.2f}, steady runs "
          f"| Richardson-Zaki U = u_t eps^n, n = {bed.rz_exponent(1000 * bed.D * bed.schiller_naumann_speed() / bed.MU):.2f} "
          f"| {1e3 * float(steady[0]['rz_U']):.2f} to {1e3 * float(steady[-1]['rz_U']):.2f} mm/s "
          f"| {1e3 * float(steady[0]['U']):.2f} to {1e3 * float(steady[-1]['U']):.2f} mm/s "
          f"| {span([100 * float(r['rz_error']) for r in steady])} (the drag law's own balance: "
          f"{span([100 * float(r['law_error']) for r in steady])}) | as rung 3 |")


if __name__ == "__main__":
    main()

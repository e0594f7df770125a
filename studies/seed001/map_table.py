#!/usr/bin/python3
"""The kiln map's README tables from studies/seed001/results/map.json (studies/seed001/kiln_map.py report) or
studies/seed001/results/stiffness.json (studies/seed001/stiffness_study.py report, with --stiffness).

    /usr/bin/python3 studies/seed001/map_table.py studies/seed001/results/map.json
    /usr/bin/python3 studies/seed001/map_table.py --stiffness studies/seed001/results/stiffness.json
"""
import json
import sys
from pathlib import Path

SIZE_RATIOS = [1.0, 1.5, 2.0, 2.5, 3.0]
DENSITY_RATIOS = [0.5, 1.0, 1.5, 2.0, 3.0]


def map_table(m):
    cases = {(c["size_ratio"], c["density_ratio"]): c for c in m["cases"].values()}
    head = "| d_L/d_S \\ rho_L/rho_S | " + " | ".join(f"{r:g}" for r in DENSITY_RATIOS) + " |"
    rows = [head, "|---" * (len(DENSITY_RATIOS) + 1) + "|"]
    for s in SIZE_RATIOS:
        cells = []
        for r in DENSITY_RATIOS:
            c = cases.get((s, r))
            if c is None:
                cells.append("not run yet")
                continue
            depth = c.get("depth_end")
            cells.append(f"{c['lacey'][0]:.2f} / {c['radial'][0]:+.2f} / " + ("—" if depth is None else f"{depth:+.2f}"))
        rows.append(f"| {s:g} | " + " | ".join(cells) + " |")
    done = list(cases.values())
    rows.append("")
    rows.append(f"Cases finished: {m['complete']} of {m['of']}, {m['revolutions']:g} revolutions each; Lacey and radial "
                f"index the mean over the last {m['average_revolutions']:g}, the depth index of the final state "
                f"(kiln_map.py snapshot; — where not measured).")
    if done:
        grains = [c["grains"] for c in done]
        per_cell = [c["lacey_cell_grains"] for c in done]
        wall = sum(c["wall_seconds"] for c in done)
        start = [c["lacey_start"] for c in done]
        rows.append(f"Grains {min(grains):,} to {max(grains):,}; Lacey cells of {done[0]['lacey_cell'] * 1e3:g} mm holding "
                    f"{min(per_cell):.0f} to {max(per_cell):.0f} grains on average; Lacey index after settling, before "
                    f"rotation: {min(start):.2f} to {max(start):.2f}; wall time {wall / 3600:.2f} h on one core "
                    f"({sum(c['wall_seconds'] for c in done) / len(done) / 60:.1f} min per case).")
    if m.get("radial_near_zero"):
        pts = ", ".join(f"({s:g}, {r:g})" for s, r in m["radial_near_zero"])
        rows.append(f"Radial index within its fluctuation (standard deviation over the window) of 0 at "
                    f"(d_L/d_S, rho_L/rho_S): {pts}; sign changes are read only between cases outside it.")
    if m["balance_line"]:
        pts = ", ".join(f"({s:g}, {r:.2f})" for s, r in m["balance_line"])
        rows.append(f"Radial index = 0 at (d_L/d_S, rho_L/rho_S): {pts}"
                    + (f"; fitted rho_L/rho_S = (d_L/d_S)^k through (1, 1): k = {m['balance_exponent']:.2f}."
                       if m["balance_exponent"] is not None else "."))
    return "\n".join(rows) + "\n"


def departs(v):
    if "departs" not in v:
        return "—"
    return ("yes: " + ", ".join({"lacey": "Lacey", "radial": "radial"}[k] for k in v["departs_by"])) if v["departs"] else "no"


def stiffness_table(s):
    rows = ["| variant | law | E (Pa) | dt (s) | fill seed | Lacey index | radial index | largest overlap / d | wall time (min) | departs from the seeds' range |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for name, v in s["variants"].items():
        e = f"{v['youngs_modulus']:.2g}" if "youngs_modulus" in v else "—"
        if "failed" in v:
            rows.append(f"| {name} | {v['law']} | {e} | {v['dt']:.3g} | {v['seed']} | stopped: {v['failed']} | | | | |")
            continue
        rows.append(f"| {name} | {v['law']} | {e} | {v['dt']:.3g} | {v['seed']} | {v['lacey']:.3f} | {v['radial']:+.3f} | "
                    f"{v['max_overlap_ratio']:.4f} | {v['wall_seconds'] / 60:.1f} | "
                    f"{departs(v)} |")
    if s["seed_noise"]:
        rows.append("")
        n = s["seed_noise"]
        rows.append(f"E/1000 over three fill seeds: Lacey index {n['lacey']['mean']:.3f} (range {n['lacey']['range']:.3f}), "
                    f"radial index {n['radial']['mean']:+.3f} (range {n['radial']['range']:.3f}).")
    return "\n".join(rows) + "\n"


def main():
    args = sys.argv[1:]
    if args and args[0] == "--stiffness":
        print(stiffness_table(json.loads(Path(args[1]).read_text())), end="")
    else:
        print(map_table(json.loads(Path(args[0]).read_text())), end="")


if __name__ == "__main__":
    main()

"""Seed 001 (the kiln mixing map): the paper's statements beside grainflow's map, for docs/results/seed001-kiln.md.

Reads only committed files: the paper's statements and the literature rows
(docs/results/data/seed001_paper.json) and the map (studies/seed001/results/map.json, studies/seed001/kiln_map.py report).
The radial index is that of the large species (systems/analysis/mixing.hpp): + when it lies at the
periphery (a small-grain core), - when it lies in the core. "Beyond its fluctuation" means farther from
0 than its standard deviation over the averaging window, the map's own test (map.json radial_near_zero).
"""
import json
import math
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
RESULTS = ROOT / "studies" / "seed001" / "results"


def load(rel):
    return json.loads((ROOT / rel).read_text())


def cases(m):
    return {(c["size_ratio"], c["density_ratio"]): c for c in m["cases"].values()}


def sign(c):
    """+1 small-grain core, -1 large-grain core, 0 within the fluctuation."""
    mean, std = c["radial"]
    return 0 if abs(mean) <= std else (1 if mean > 0 else -1)


def balances(m):
    """Per size ratio > 1: ('at', rho*) from a sign change or a case within its fluctuation, or
    ('above', largest rho) when every case keeps a small-grain core."""
    cs = cases(m)
    crossing = {s: r for s, r in m["balance_line"]}
    out = {}
    for s in sorted({k[0] for k in cs if k[0] > 1}):
        row = sorted((r, c) for (ss, r), c in cs.items() if ss == s)
        near = [r for r, c in row if r > 1 and sign(c) == 0]
        if s in crossing:
            out[s] = ("at", crossing[s])
        elif near:
            out[s] = ("at", near[0])
        elif all(sign(c) > 0 for _, c in row):
            out[s] = ("above", row[-1][0])
    return out


def side_by_side():
    paper = load("docs/results/data/seed001_paper.json")
    m = load("studies/seed001/results/map.json")
    cs = cases(m)
    rows = ["| quantity | the paper reports | grainflow gets | agree? | why not |", "|---|---|---|---|---|"]

    size = sorted((s, c) for (s, r), c in cs.items() if r == 1 and s > 1)
    ok = all(sign(c) > 0 for _, c in size)
    lo = min(c["radial"][0] for _, c in size)
    hi = max(c["radial"][0] for _, c in size)
    rows.append(f"| size only: rho_L/rho_S = 1, d_L/d_S = {size[0][0]:g} to {size[-1][0]:g} | {paper['size_only']['shown']} | "
                f"radial index {lo:+.2f} to {hi:+.2f}: a small-grain core in every case, each beyond its fluctuation | "
                f"{'yes' if ok else 'no'} | {'' if ok else 'cause not yet measured'} |")

    dens = sorted((r, c) for (s, r), c in cs.items() if s == 1 and r != 1)
    # the heavier species in the core: the large species' radial index - when it is the denser one, + when lighter
    ok = all(sign(c) == (-1 if r > 1 else 1) for r, c in dens)
    lo = min(c["radial"][0] for _, c in dens)
    hi = max(c["radial"][0] for _, c in dens)
    heavy = max(dens)
    light = min(dens)
    rows.append(f"| density only: d_L/d_S = 1, rho_L/rho_S = {', '.join(f'{r:g}' for r, _ in dens)} | "
                f"{paper['density_only']['shown']} | radial index {lo:+.2f} to {hi:+.2f}, each within its fluctuation of 0: "
                f"no core; depth index of the final state {heavy[1]['depth_end']:+.2f} at rho_L/rho_S = {heavy[0]:g} "
                f"and {light[1]['depth_end']:+.2f} at {light[0]:g} (the denser species deeper) | {'yes' if ok else 'no'} | "
                f"{'' if ok else 'the denser species settles in layers under the surface, not in a core; why the density segregation is this weak is not yet measured'} |")

    b = balances(m)
    mixed = [(s, r) for s, r in m["radial_near_zero"] if s > 1]
    ok = bool(m["balance_line"] or mixed)
    parts = [f"the radial index changes sign at rho_L/rho_S = {r:.2f} for d_L/d_S = {s:g}" for s, r in m["balance_line"]]
    for s, r in mixed:
        c = cs[(s, r)]
        parts.append(f"at ({s:g}, {r:g}) the bed stays mixed (Lacey {c['lacey'][0]:.2f}, radial {c['radial'][0]:+.2f})")
    rows.append(f"| a pairing that stays mixed | {paper['balance']['shown']} | {'; '.join(parts)} | "
                f"{'yes' if ok else 'no'} | {'' if ok else 'no sign change inside the map'} |")

    lit = {x["id"]: x for x in paper["literature"]}
    p = lit["power_law"]
    kmin, kmax = p["k_range"]
    cells, ok = [], True
    for s, (how, r) in sorted(b.items()):
        k = math.log(r) / math.log(s)
        if how == "at":
            cells.append(f"k = {k:.2f} at d_L/d_S = {s:g}")
            ok &= kmin <= k <= kmax
        else:
            cells.append(f"k above {k:.2f} at {s:g}")
            ok &= k <= kmax
    rows.append(f"| shape of the balance line (literature, not the paper) | {p['shown']}; {p['source']} | "
                f"{'; '.join(cells)}: no single k | {'yes' if ok else 'no'} | {'' if ok else 'cause not yet measured'} |")

    p = lit["below_diagonal"]
    below = [s for s, (how, r) in b.items() if how == "at" and r < s - 1e-9]
    ok = bool(below)
    where = ", ".join(f"{s:g}" for s in sorted(b))
    rows.append(f"| best mixing against the diagonal (literature, not the paper) | {p['shown']}; {p['source']} | "
                f"the balance lies on or above the diagonal at every size ratio ({where}) | {'yes' if ok else 'no'} | "
                f"{'' if ok else 'not measured: a different set-up (their quasi-2D tumbler against a periodic slice, 5 revolutions, E/1000), and the reading of their result is second-hand'} |")

    rows.append("")
    rows.append("Rules for \"agree?\": a core agrees when the large species' radial index has the expected sign beyond its "
                "fluctuation (its standard deviation over the last 2 revolutions) in every case of the row; a mixed pairing "
                "agrees when the radial index changes sign inside the map or stays within its fluctuation of 0 at a size "
                f"ratio above 1; the balance line agrees when k = ln(rho*)/ln(d_L/d_S) lies in {kmin}–{kmax} at every "
                "size ratio (a lower bound where every density ratio keeps a small-grain core); the diagonal row agrees "
                "when the balance lies below rho_L/rho_S = d_L/d_S at some size ratio.")
    return "\n".join(rows) + "\n"


TABLES = {"seed001_side_by_side": side_by_side}

if __name__ == "__main__":
    print(side_by_side(), end="")

"""Seed 002 (composite grains of dilated polyhedra): the side-by-side table of docs/results/seed002-composites.md.

The paper's statements are in docs/results/data/seed002_paper.json (each with its place in the paper); grainflow's
side comes from the committed result files under studies/seed002/results/. The rules for "agree?" are in each row's function.
"""
import json
import pathlib
import statistics
import sys

ROOT = pathlib.Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "studies" / "seed002"))
from arch_or_heap import first_stop, grain_side_mm, shape_of, verdict  # noqa: E402

NAMES = {"hollow_block": "hollow block", "tetrapod": "tetrapod", "twisted_i": "twisted I",
         "twisted_king": "twisted king"}
LETTER_FILES = (("0.03 m (the scene)", "studies/seed002/results/packing/packing.json"),
                ("0.04 m", "studies/seed002/results/packing/stroke40_dt5/packing.json"))


def load(path):
    return json.loads((ROOT / path).read_text())


def spread(values, fmt="{:.2f}"):
    values = sorted(values)
    if len(values) == 1:
        return fmt.format(values[0])
    return f"{fmt.format(statistics.median(values))} ({fmt.format(values[0])}–{fmt.format(values[-1])})"


def pours(shape, sides):
    """The outlet runs (studies/seed002/results/outlet/outlet.json) of one grain and gate width in grain sides."""
    runs = load("studies/seed002/results/outlet/outlet.json")
    return [e for e in runs.values()
            if shape_of(e["overrides"]) == shape and round(40 / grain_side_mm(e["overrides"]), 1) == sides]


def stops(e):
    """Every stop of 0.1 s or more: the stalls, then the final stop when the flow ended."""
    times = [x["from_s"] for x in e["stalls"]]
    if verdict(e) != "still flowing":
        times.append(e["last_change_s"])
    return sorted(times)


def middle_half(values):
    """The quartiles of the pours' values (their whole range below four pours)."""
    if len(values) < 4:
        return min(values), max(values)
    q = statistics.quantiles(values, n=4, method="inclusive")
    return q[0], q[2]


def within(value, values, tolerance):
    """Whether the paper's value lies in the middle half of the pours' values, widened by its last digit."""
    lo, hi = middle_half(values)
    return lo - tolerance <= value <= hi + tolerance


def spread_middle(values):
    lo, hi = middle_half(values)
    return spread(values)[:-1] + f"; middle half {lo:.2f}–{hi:.2f})" if len(values) >= 4 else spread(values)


def yes(flag):
    return "yes" if flag else "no"


def hopper_rows(paper):
    rows = []
    prisms, cones = paper["prisms_arches"], paper["cones_arch"]
    first_runs = load("studies/seed002/results/friction/friction.json")
    # Prisms of the scene (gate 4 grain sides): the scene's own pour and the outlet study's pours at 10 mm.
    p4 = [first_runs["studies/seed002/results/hopper_prisms"]] + pours("prisms", 4.0)
    arches = sum(verdict(e) == "arch" for e in p4)
    left = [e["remaining_at_end"] for e in p4]
    rows.append(("prisms, gate 4 grain sides (the scene's 10 mm prisms): arches", prisms["value"],
                 f"{arches} of {len(p4)} pours end on an arch; {spread(left, '{:.3f}')} left at 3 s",
                 yes(arches > 0),
                 "prism size against the gate assumed (the reference's particle data not found); at 3 sides they arch"))
    # Prisms at 3 grain sides: first and second stops over the pours.
    p3 = pours("prisms", 3.0)
    firsts = [first_stop(e) for e in p3 if first_stop(e) is not None]
    seconds = [stops(e)[1] for e in p3 if len(stops(e)) > 1]
    rows.append(("prisms, gate 3 grain sides: first arch (s)", f"{prisms['first_s']:.1f}",
                 f"{spread_middle(firsts)} over {len(p3)} pours (first stop of 0.1 s or more)",
                 yes(within(prisms["first_s"], firsts, prisms["uncertainty_s"])),
                 f"arch times move by a second and more between pours; {sum(t <= 0.15 for t in firsts)} of {len(p3)} "
                 "pours stop within 0.15 s of the gate opening"))
    twice = sum(len(stops(e)) >= 2 for e in p3)
    rows.append(("prisms, gate 3 grain sides: arch gives way, a second forms (s)",
                 f"yes, second at {prisms['second_s']:.1f}",
                 f"{twice} of {len(p3)} pours stop twice, second stop {spread_middle(seconds)}; "
                 f"{sum(verdict(e) == 'arch' for e in p3)} of {len(p3)} end on an arch",
                 "in part" if twice * 2 > len(p3) and not within(prisms["second_s"], seconds, prisms["uncertainty_s"])
                 else yes(twice * 2 > len(p3)),
                 "the pattern agrees; its times vary between pours"))
    # Cones of the scene (gate 4 sides): one pour, no final frame (its pictures show the dead zones).
    c4 = first_runs["studies/seed002/results/hopper_cones"]
    rows.append(("cones, gate 4 grain sides (the scene's element): lasting arch", cones["value"],
                 f"no: the flow stops at {c4['last_change_s']:.2f} s with {c4['remaining_at_end']:.3f} left, "
                 "on the dead zones beside the gate (pictures)",
                 "no", "element's size against the gate assumed (the reference's particle data not found)"))
    c3 = pours("cones", 3.0)
    arch_runs = [e for e in c3 if verdict(e) == "arch"]
    onsets = [e["last_change_s"] for e in arch_runs]
    others = ", ".join(f"{e['remaining_at_end']:.3f}" for e in c3 if verdict(e) != "arch")
    rows.append(("cones, gate 3 grain sides: lasting arch from (s)", f"{cones['from_s']:.1f}",
                 f"{len(arch_runs)} of {len(c3)} pours end on an arch, from {spread_middle(onsets)} s; "
                 f"the {'other flows' if len(c3) - len(arch_runs) == 1 else 'others flow'} on ({others} left)",
                 "in part" if arch_runs and not within(cones["from_s"], onsets, cones["uncertainty_s"])
                 else yes(bool(arch_runs)),
                 "the elements jam at once; cause not yet measured"))
    return rows


def packing_rows(paper):
    rows = []
    groups = paper["packing_order"]["value"]
    rank = {letter: i for i, group in enumerate(groups) for letter in group}
    text = " > ".join(", ".join(g) for g in groups)
    conv = load("studies/seed002/results/packing/letter_convexity.json")["rows"]
    most_convex = {r["stroke_m"]: max((x for x in conv if x["stroke_m"] == r["stroke_m"]),
                                      key=lambda x: x["convexity"])["letter"] for r in conv}
    for label, path in LETTER_FILES:
        fr = {r["letter"]: r["packing_fraction"] for r in load(path)["shapes"]}
        pairs = [(a, b) for a in fr for b in fr if rank[a] < rank[b]]
        kept = sum(fr[a] > fr[b] for a, b in pairs)
        order = sorted(fr, key=lambda k: -fr[k])
        rows.append((f"packing order of the letters, strokes {label}",
                     f"{text} ({len(pairs)} ordered pairs)",
                     f"{' > '.join(order)}: {kept} of {len(pairs)} pairs as the paper's; O ranks "
                     f"{order.index('O') + 1} of {len(order)}",
                     yes(kept == len(pairs)),
                     f"our A is the most convex letter at every stroke tried ({', '.join(sorted({most_convex[s] for s in most_convex}))}"
                     f" at {', '.join(f'{1000 * s:g}' for s in sorted(most_convex))} mm); stroke width not given by the paper"))
    return rows


def _arch_cause(cases):
    """What the short runs that change one thing say about the arches (shapes_hopper.py CAUSES)."""
    def at4(k):
        v = cases.get(k)
        return None if v is None or "in_progress" in v or v.get("left_at_4s") is None else v["left_at_4s"]
    base, f02, f0 = at4("twisted_i"), at4("twisted_i_friction_0.2"), at4("twisted_i_friction_0")
    if None in (base, f02, f0):
        return "cause not yet measured (half the grains, assumed concrete, two shapes taken from the armour-unit family)"
    top = cases["twisted_i_friction_0.2"].get("bed_top_at_opening_m")
    deep = cases.get("twisted_i_4000", {})
    deep_text = ""
    if deep.get("bed_top_at_opening_m"):
        deep_text = (f", {deep['bed_top_at_opening_m']:.2f} m with the paper's 4000, which stop alike "
                     f"({at4('twisted_i_4000'):.3f} left at 4 s)" if at4("twisted_i_4000") is not None else
                     f", {deep['bed_top_at_opening_m']:.2f} m with the paper's 4000, not yet run to the end")
    return (f"interlocking more than friction or the bed's depth: at 4 s the twisted I blocks leave {base:.3f} at "
            f"friction 0.5, {f02:.3f} at 0.2 and {f0:.3f} without friction; their highest centre is {top:.2f} m "
            f"above the 8 m orifice when it opens (2000 grains, half the paper's){deep_text}")


def shapes_rows(paper):
    s = {k: v for k, v in load("studies/seed002/results/shapes/shapes.json")["shapes"].items() if k in NAMES}
    all_cases = load("studies/seed002/results/shapes/shapes.json")["shapes"]
    long = all_cases.get("hollow_block_long")
    rows = []
    left = {k: v["left_at_end"] for k, v in s.items()}
    drained = [k for k in s if k == min(left, key=left.get)]
    arched = [k for k in s if k not in drained]
    rows.append(("four shapes: each drains to a heap", "yes (all four)",
                 f"only the {NAMES[drained[0]]} ({left[drained[0]]:.3f} left at 12 s"
                 + (f", {long['left_at_end']:.4f} at {long['end_s']:.1f} s" if long else "") + "); "
                 + ", ".join(f"{NAMES[k]} {left[k]:.3f}" for k in arched) + " left, held by arches",
                 "no", _arch_cause(all_cases)))
    t9 = {k: v["t_0.9"] for k, v in s.items()}
    first = min(t9, key=t9.get)
    most = min(left, key=left.get)
    want = paper["four_shapes_fastest"]["value"]
    rows.append(("four shapes: fastest discharge", NAMES[want],
                 f"first to 0.9 left: {NAMES[first]} ({t9[first]:.2f} s); most emptied by 12 s: {NAMES[most]}",
                 "yes" if first == want and most == want else ("in part" if want in (first, most) else "no"),
                 "the others flow fast, then arch"))
    last = max(t9, key=t9.get)
    fullest = max(left, key=left.get)
    want = paper["four_shapes_slowest"]["value"]
    rows.append(("four shapes: slowest discharge", NAMES[want],
                 f"last to 0.9 left: {NAMES[last]} ({t9[last]:.2f} s); most left at 12 s: {NAMES[fullest]} "
                 f"({left[fullest]:.3f}; {NAMES[want]} {left[want]:.3f})",
                 "yes" if last == want and fullest == want else ("in part" if want in (last, fullest) else "no"),
                 "three shapes arch, so their rates are not defined"))
    full = [k for k, v in s.items() if v["repose_flanks"] == 4]
    rows.append(("four shapes: angle of repose, smallest and largest",
                 f"{NAMES[paper['repose_smallest']['value']]} smallest, {NAMES[paper['repose_largest']['value']]} largest",
                 "; ".join(f"{NAMES[k]} {s[k]['repose_mean_deg']:.1f}° ({s[k]['repose_flanks']} of 4 flanks)" for k in s),
                 "not comparable" if len(full) < 2 else "—",
                 "only the " + " and the ".join(NAMES[k] for k in full) + " leaves a crater with four sloped flanks; the others stop on arches"))
    return rows


def seed002_side_by_side():
    paper = load("docs/results/data/seed002_paper.json")["quantities"]
    rows = ["| quantity | the paper reports | grainflow gets | agree? | why not |", "|---|---|---|---|---|"]
    for r in hopper_rows(paper) + packing_rows(paper) + shapes_rows(paper):
        rows.append("| " + " | ".join(r) + " |")
    rows.append("")
    rows.append("Agree: a time within the middle half of grainflow's pours (their quartiles; the whole range below four "
                "pours), widened by the paper's last digit (±0.05 s); an "
                "order or a named shape the same; \"in part\" where the pattern agrees and its time does not, or one "
                "of two measures agrees. Paper: docs/results/data/seed002_paper.json.")
    return "\n".join(rows) + "\n"


TABLES = {"seed002_side_by_side": seed002_side_by_side}

if __name__ == "__main__":
    print(seed002_side_by_side(), end="")

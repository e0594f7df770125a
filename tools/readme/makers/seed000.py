"""Seed 000 (the thin drum): the paper's results beside grainflow's, for docs/results/seed000-drum.md.

Reads only committed files: the paper's values (docs/results/data/seed000_paper.json), the archived
runs (studies/seed000/results/study/<case>/series.csv, studies/seed000/study.py), the cases' table
(studies/seed000/results/seed_drum_table.json, study.py report), the arms inside the bed
(studies/seed000/results/petal_arms/<case>/petal_arms.json, studies/seed000/petal_arms.py), the pulsation
(studies/seed000/results/pulsation_surface_w0.50_from20/pulsation.json, studies/seed000/pulsation.py) and the
speed/accuracy runs (studies/seed000/results/speed_accuracy.json, studies/seed000/speed_accuracy.py).
"""
import csv
import json
import math
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
RESULTS = ROOT / "studies" / "seed000" / "results"

KINDS = {"0": "moon", "1": "petals", "-1": "undecided"}
LAST_BIN = (29.75, 30.0)  # the last quarter radian before 30 rad, as studies/seed000/pattern_calls.py bins it
PERIOD_TOLERANCE = 0.10   # one shared period: the two periods within 10 % of the shorter


def load(rel):
    return json.loads((ROOT / rel).read_text())


def series(case):
    with open(RESULTS / "study" / case / "series.csv") as f:
        return [(float(r["angle"]), r["pattern"], float(r["petals"])) for r in csv.DictReader(f)]


def calls(rows, lo, hi):
    """Rows per call (moon / petals / undecided) with lo <= angle < hi."""
    out = {"moon": 0, "petals": 0, "undecided": 0}
    for angle, pattern, _ in rows:
        if lo <= angle < hi:
            out[KINDS[pattern]] += 1
    return out


def majority(counts):
    return max(counts, key=lambda k: counts[k])


def ring_text(r):
    radii = "/".join(f"{x:g}" for x in r["ring_radii"])
    counts = "/".join(str(n) if n >= 0 else "—" for n in r["ring_lobes"])
    return f"lobes crossing {radii} R: {counts}"


def arms(case):
    rings = load(f"studies/seed000/results/petal_arms/{case}/petal_arms.json")["rings"]
    best = max(r["arms"] for r in rings)
    at = "/".join(f"{r['r_over_R']:.1f}" for r in rings if r["arms"] == best)
    return best, at


def fmt_e(x):
    m, e = f"{x:.2e}".split("e")
    return f"{m.rstrip('0').rstrip('.')}e{int(e)}"


def side_by_side():
    paper = load("docs/results/data/seed000_paper.json")
    table = {r["case"]: r for r in load("studies/seed000/results/seed_drum_table.json")}
    rows = ["| quantity | the paper reports | grainflow gets | agree? | why not |", "|---|---|---|---|---|"]

    for p in paper["patterns_at_30_rad"]:
        case, t = p["case"], table[p["case"]]
        s = series(case)
        c = calls(s, *LAST_BIN)
        n = sum(c.values())
        call = majority(c)
        ours = (f"{call} in {c[call]} of {n} rows of {LAST_BIN[0]:g}–{LAST_BIN[1]:g} rad "
                f"(at 30 rad: {t['ours']}, contrast {t['contrast']:.2f})")
        agree = call == p["kind"]
        why = ""
        if not agree:
            if p["kind"] == "moon":
                m = calls(s, 27.0, LAST_BIN[0])
                why = (f"at 30 rad a lobe of the core reaches towards the rim ({ring_text(t)}); "
                       f"a moon in {m['moon']:,} of {sum(m.values()):,} rows of 27–{LAST_BIN[0]:g} rad")
            else:
                why = f"the small-grain lobes stop short of the rim band ({ring_text(t)} at 30 rad)"
        rows.append(f"| pattern at 30 rad, {p['fill']} fill, {p['omega']:.2f} rad/s | {p['shown']} | {ours} | "
                    f"{'yes' if agree else 'no'} | {why} |")

    for p in paper["patterns_at_30_rad"]:
        if "petals" not in p:
            continue
        best, at = arms(p["case"])
        c = [n for a, k, n in series(p["case"]) if LAST_BIN[0] <= a < LAST_BIN[1] and k == "1"]
        rim = (f"; the classifier's rim band: {sum(c) / len(c):.1f} lobes on average over the rows of "
               f"{LAST_BIN[0]:g}–{LAST_BIN[1]:g} rad it calls petals" if c else "")
        agree = best == p["petals"]
        rows.append(f"| petals at 30 rad, {p['fill']} fill, {p['omega']:.2f} rad/s | {p['petals']} | "
                    f"{best} small-grain arms crossing a ring at {at} R{rim} | {'yes' if agree else 'no'} | "
                    f"{'' if agree else 'cause not yet measured'} |")

    p = paper["pulsation"]
    s = load("studies/seed000/results/pulsation_surface_w0.50_from20/pulsation.json")
    b, v = s["surface_bulge"], s["surface_speed"]
    shared = abs(b["period_s"] - v["period_s"]) <= PERIOD_TOLERANCE * min(b["period_s"], v["period_s"])
    rows.append(f"| pulsation once the petals form, 1/2 fill, {p['omega']:.2f} rad/s | {p['shown']} | "
                f"from {s['from_rad']:g} rad: the surface bulge pulses every {b['period_s']:.2f} s "
                f"(std {b['std']:.3g} mm), the surface speed every {v['period_s']:.2f} s (std {v['std']:.3g} m/s); "
                f"correlation {s['speed_bulge_correlation']:+.2f} | {'yes' if shared else 'no'} | "
                f"{'' if shared else 'the speed and the bulge do not share one period; cause not yet measured'} |")

    p = paper["time_step"]
    runs = load("studies/seed000/results/speed_accuracy.json")
    seed = next(r for r in runs if abs(r["dt"] - p["dt_s"]) < 1e-12 * p["dt_s"] + 1e-15)
    period = seed["dt"] / seed["critical_fraction"]
    double = next((r for r in runs if abs(r["dt"] - 2 * p["dt_s"]) < 1e-12 and r["status"] == "completed"), None)
    extra = (f"; {fmt_e(double['dt'])} s ({double['critical_fraction']:.3f}) keeps the segregation index to "
             f"{double['angle']:.1f} rad within {double['rms_vs_seed_dt']:.3f} (RMS)" if double else "")
    agree = seed["critical_fraction"] < p["largest_fraction_of_smallest_period"]
    rows.append(f"| time step | {fmt_e(p['dt_s'])} s, below {p['largest_fraction_of_smallest_period']:g} of the "
                f"smallest collision period | {fmt_e(seed['dt'])} s = {seed['critical_fraction']:.3f} of the smallest "
                f"period ({fmt_e(period)} s){extra} | {'yes' if agree else 'no'} | "
                f"{'' if agree else 'the step is above the paper’s limit'} |")
    rows.append("")
    rows.append(f"Rules for \"agree?\": a pattern agrees when the classifier's most frequent call over the rows of "
                f"{LAST_BIN[0]:g}–{LAST_BIN[1]:g} rad (the archived series.csv) is the paper's kind, moon or petals; "
                f"a petal count agrees when the most small-grain arms crossing one ring inside the bed "
                f"(petal_arms.py on the state at 30 rad) equal the paper's count; the pulsation agrees when the "
                f"surface bulge and the surface speed share one dominant period (within "
                f"{PERIOD_TOLERANCE:.0%} of the shorter); the time step agrees when it is below the paper's "
                f"fraction of the smallest collision period.")
    return "\n".join(rows) + "\n"


def petal_period():
    """The surface angle's pulse period as a count of petals, two pulses each, beside the arms counted inside the
    bed (studies/seed000/petal_period.py)."""
    d = load("studies/seed000/results/petal_period.json")
    paper = {p["case"]: p for p in load("docs/results/data/seed000_paper.json")["patterns_at_30_rad"]}
    rows = ["| case | the paper at 30 rad | arms inside the bed at 30 rad | surface-angle period, 20–30 rad: s (rad of "
            "rotation; prominence) | π / period (rad): petals at two pulses each | the same over 5-rad windows from "
            "5 to 30 rad |", "|---|---|---|---|---|---|"]
    for case, c in d["cases"].items():
        p = paper[case]
        w = c["windows"][0]
        shown = f"{p['petals']} petals" if "petals" in p else p["shown"]
        rest = " / ".join(f"{x['petals_two_pulses_each']:.1f}" for x in c["windows"][1:])
        rows.append(f"| {p['fill']} fill, {p['omega']:.2f} rad/s | {shown} | {c['arms_inside_the_bed']} (at "
                    f"{'/'.join(f'{r:.1f}' for r in c['arms_at_r_over_R'])} R) | {w['period_s']:.2f} s "
                    f"({w['period_rad']:.2f} rad; {w['prominence']:.0f}) | {w['petals_two_pulses_each']:.1f} | {rest} |")
    return "\n".join(rows) + ("\n\nProminence: the spectral peak's power over the median within an octave of it "
                              "(white noise of the same length reads about 11, and 17 at most over 200 draws: tests/petal_period_test.py).\n")


TABLES = {"seed000_side_by_side": side_by_side, "seed000_petal_period": petal_period}

if __name__ == "__main__":
    print(side_by_side(), end="")

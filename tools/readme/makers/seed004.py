"""Seed 004 (the continuous drum-blade mixer): the paper's values beside grainflow's.

Reads docs/results/data/seed004_paper.json (the paper's values, each with its source and reading
uncertainty, and the agreement rules), studies/seed004/results/mixer.json (studies/seed004/mixer_report.py) and
studies/seed004/results/compartments.json (studies/seed004/compartments.py).
"""
import json
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[3]


def _load(rel):
    return json.loads((ROOT / rel).read_text())


def _vc(run, distance):
    for v in run["vc"]:
        if abs(v["distance"] - distance) < 1e-9:
            return v
    raise KeyError(f"no layer at {distance} m")


def _in_range(x, spec):
    u = spec["reading_uncertainty"]
    return spec["low"] - u <= x <= spec["high"] + u


def _pct(v):
    return f"{100 * v['vc_mean']:.1f} % ({100 * v['vc_min']:.1f}–{100 * v['vc_max']:.1f})"


def seed004_side_by_side():
    paper = _load("docs/results/data/seed004_paper.json")["values"]
    assumed = _load("docs/results/data/seed004_paper.json")["assumptions"]
    mixer = _load("studies/seed004/results/mixer.json")
    comp = {r["run"]: r for r in _load("studies/seed004/results/compartments.json")["runs"]}
    designs = mixer["designs"]
    finest = next(m for m in mixer["models"] if m["model"] == "sphere DEM, factor 3")
    inlet, far = paper["vc_near_inlet_percent"], paper["vc_at_0p4_m_percent"]
    seg = _load("studies/seed004/results/vc_segregation.json")["vc"]
    geo = _load("studies/seed004/results/vc_geometry.json")["vc"]
    part = _load("studies/seed004/results/vc_partitions.json")["vc"]
    feed = _load("studies/seed004/results/vc_feed.json")["vc"]
    feed_inlet = [100 * _at(feed[k], 0.025)["vc_median"] for k in ("stream", "nozzle", "nozzle_jet")]

    def seg_pct(variant, distance):
        return f"{100 * _at(seg[variant], distance)['vc_median']:.1f} %"

    def rng(spec):
        return f"{spec['low']}–{spec['high']} % (± {spec['reading_uncertainty']} reading)"

    rows = ["| quantity | the paper reports | grainflow gets | agree? | why not |", "|---|---|---|---|---|"]
    for d in designs:
        v = _vc(d, 0.025)
        ok = _in_range(100 * v["vc_mean"], inlet)
        why = "—" if ok else (f"segregation by size and density where the feed lands (measured in design 1: with the "
                              f"key the carrier's size and density, {seg_pct('identical', 0.025)}; equal size only "
                              f"{seg_pct('same_size', 0.025)}, equal density only {seg_pct('same_density', 0.025)}; "
                              f"the seed's {seg_pct('seed', 0.025)}, vc_segregation.json); not the way the feed "
                              f"enters: as a trickle or through a nozzle's mouth on the axis {min(feed_inlet):.1f}–"
                              f"{max(feed_inlet):.1f} % against the batches' "
                              f"{100 * _at(feed['seed'], 0.025)['vc_median']:.1f} % (vc_feed.json); the random-mixture spread "
                              f"of cells of about {v['grains_per_cell']:.0f} model particles explains "
                              f"{100 * (v['vc_mean'] - v['vc_corrected_mean']):.1f} points of it")
        lengths = "/".join(f"{1000 * x:.0f}" for x in d["blade_lengths_m"])
        rows.append(f"| Vc at L = 0.025 m, design {d['design']} (blades {lengths} mm), representative volumes | "
                    f"{rng(inlet)} | {_pct(v)} | {'yes' if ok else 'no'} | {why} |")
    for d in designs:
        v = _vc(d, 0.4)
        ok = _in_range(100 * v["vc_mean"], far)
        c = comp[f"design{d['design']}"]["compartments"]
        why = "—" if ok else (f"segregation by size (measured in design 1: with the key as large as the carrier "
                              f"{seg_pct('same_size', 0.4)}, as with a key that is only a label "
                              f"{seg_pct('identical', 0.4)}, which is the cells' random-mixture spread "
                              f"({100 * _at(seg['identical'], 0.4)['random_vc_median']:.1f} %); with equal densities "
                              f"{seg_pct('same_density', 0.4)}; "
                              f"vc_segregation.json): the key particles sink to the housing side either side of "
                              f"this layer (wall-side minus free-surface key fraction {c[2]['wall_minus_top']:+.2f} "
                              f"in stage III, {c[3]['wall_minus_top']:+.2f} in the outlet compartment); not the "
                              f"bladeless outlet compartment as such: with the end ring at 0.40 m the last layer "
                              f"inside reads {100 * _at(geo['end_at_0.4'], 0.375)['vc_median']:.1f} % "
                              f"(vc_geometry.json); the partitions hold the sunken key back: without them "
                              f"{100 * _at(part['none'], 0.4)['vc_median']:.1f} % here, the key's volume fraction "
                              f"{_at(part['none'], 0.4)['key_fraction']:.2f} against "
                              f"{_at(part['seed'], 0.4)['key_fraction']:.2f}, and "
                              f"{_at(part['rings_10mm'], 0.4)['key_fraction']:.2f} / "
                              f"{_at(part['rings_30mm'], 0.4)['key_fraction']:.2f} behind partitions 10 / 30 mm "
                              f"high (ours 15 mm; the paper gives no height; vc_partitions.json)")
        rows.append(f"| Vc at L = 0.4 m (the last partition), design {d['design']} | {rng(far)} | {_pct(v)} | "
                    f"{'yes' if ok else 'no'} | {why} |")
    falls = [(d["design"], _vc(d, 0.025)["vc_mean"], _vc(d, 0.1)["vc_mean"]) for d in designs]
    ok = all(b < a for _, a, b in falls)
    rows.append("| Vc falls through stage I (L = 0.025 → 0.1 m) | yes, with steps at the stages | " +
                "; ".join(f"design {k}: {100 * a:.1f} → {100 * b:.1f} %" for k, a, b in falls) +
                f" | {'yes' if ok else 'no'} | {'—' if ok else 'cause not yet measured'} |")
    d1 = designs[0]
    n = d1["holdup_grains_mean"]
    ok = abs(n / paper["model_particles"]["value"] - 1) <= 0.05
    rows.append(f"| model particles in the mixer, design 1 (steady mean; the ring holes were chosen for this) | "
                f"{paper['model_particles']['value']} | {n:.0f} | {'yes' if ok else 'no'} | "
                f"{'—' if ok else 'cause not yet measured'} |")
    packing = assumed["bed_packing"]["value"]
    ff = d1["holdup_solid_fraction_final"] / packing
    ok = abs(ff / paper["fill_factor"]["value"] - 1) <= 0.05
    rows.append(f"| fill factor, design 1 (solid fraction of the housing {d1['holdup_solid_fraction_final']:.3f} "
                f"over an assumed packing of {packing}) | {paper['fill_factor']['value']} | {ff:.2f} | "
                f"{'yes' if ok else 'no'} | {'—' if ok else 'cause not yet measured'} |")
    for dist, spec, label in ((0.025, inlet, "Vc at L = 0.025 m"), (0.4, far, "Vc at L = 0.4 m")):
        v = _vc(finest, dist)
        ok = _in_range(100 * v["vc_mean"], spec)
        why = "—" if ok else ("cause not yet measured (the spheres' material is assumed, not the paper's; "
                              "the paper's experiment is not simulated grain for grain)")
        rows.append(f"| {label}, design 1 as sphere DEM (Hertz–Mindlin, coarse-graining factor 3, "
                    f"{finest['holdup_grains_mean']:,.0f} grains) | {rng(spec)} | {_pct(v)} | "
                    f"{'yes' if ok else 'no'} | {why} |")
    rows += _swapped_rows(inlet, far, rng)
    rows.append("")
    rows.append("grainflow's Vc: mean of the pooled layer rows in steady state (their range), from "
                "studies/seed004/results/mixer.json. agree?: a value within the paper's range widened by its reading "
                "uncertainty; a count or fraction within 5 %; a trend in every design.")
    return "\n".join(rows) + "\n"


def _swapped_rows(inlet, far, rng):
    """Design 1 with the paper's other reading of its coefficients (k_r and k_p swapped), from
    studies/seed004/results/vc_reading.json (studies/seed004/vc_variants.py): median of the pooled rows."""
    reading = _load("studies/seed004/results/vc_reading.json")
    swapped, control = reading["vc"]["swapped"], reading["vc"]["slip_0.1"]
    rows = []
    for dist, spec in ((0.025, inlet), (0.4, far)):
        v, c = _at(swapped, dist), _at(control, dist)
        ok = _in_range(100 * v["vc_median"], spec)
        why = "—" if ok else (
            f"friction 15 times the separation force mixes the bed: Vc lies "
            f"{100 * (v['vc_median'] - v['random_vc_median']):.1f} points above the cells' random-mixture spread "
            f"({100 * v['random_vc_median']:.1f} % here), and it no longer falls along the mixer "
            f"({100 * _at(swapped, 0.025)['vc_median']:.1f} % at 0.025 m, {100 * _at(swapped, 0.1)['vc_median']:.1f} % "
            f"at 0.1 m); the control, the scene's coefficients regularised alike, gives {100 * c['vc_median']:.1f} % "
            f"(vc_reading.json)")
        rows.append(f"| Vc at L = {dist} m, design 1, the coefficients' other reading (k_r 0.15, k_p 15; walls 0.1, "
                    f"10), representative volumes | {rng(spec)} | {100 * v['vc_median']:.1f} % "
                    f"({100 * v['vc_min']:.1f}–{100 * v['vc_max']:.1f}), median | {'yes' if ok else 'no'} | {why} |")
    return rows


SAMPLING_LABELS = (("pool1_cell50", "one instant, 50 mm cells"), ("pool40_cell50", "20 s pooled, 50 mm cells (the study's)"),
                   ("pool200_cell50", "100 s pooled, 50 mm cells"), ("pool40_cell25", "20 s pooled, 25 mm cells"))
SAMPLING_AT = (0.025, 0.1, 0.125, 0.25, 0.4)


def _at(layers, distance):
    for v in layers:
        if abs(v["distance"] - distance) < 1e-9:
            return v
    raise KeyError(f"no layer at {distance} m")


def seed004_vc_sampling():
    """Vc of one steady run sampled four ways (studies/seed004/vc_sampling.py): median of the rows, and
    below it the spread a random mixture of the cells' visits gives."""
    s = _load("studies/seed004/results/vc_sampling.json")
    head = "| sampling | visits a cell | " + " | ".join(f"Vc at L = {d} m" for d in SAMPLING_AT) + " |"
    rows = [head, "|---|---|" + "---|" * len(SAMPLING_AT)]
    for key, label in SAMPLING_LABELS:
        layers = s["variants"][key]
        visits = sorted(v["visits_per_cell"] for v in layers)[len(layers) // 2]
        cells = []
        for d in SAMPLING_AT:
            v = _at(layers, d)
            cells.append(f"{100 * v['vc_median']:.1f} % (random {100 * v['random_vc_median']:.1f} %)")
        rows.append(f"| {label} | {visits:.0f} | " + " | ".join(cells) + " |")
    return "\n".join(rows) + f"\n\nDesign 1, representative volumes, 100 s from its steady state; build {s['commit']}.\n"


SEGREGATION_LABELS = (("seed", "the seed's: key 0.778 of the size, 0.786 of the density"),
                      ("same_size", "key as large as the carrier"), ("same_density", "key as dense as the carrier"),
                      ("identical", "key the carrier's size and density (a label)"))
SEGREGATION_AT = (0.025, 0.1, 0.2, 0.3, 0.4, 0.475)


READING_LABELS = (("seed", "the scene's: cut-off 1e-3, friction regularised below 0.01 m/s"),
                  ("cutoff_1e-4", "tails cut at 1e-4"), ("slip_1e-3", "friction regularised below 1 mm/s"),
                  ("slip_0.1", "friction regularised below 0.1 m/s (the control for the next row)"),
                  ("swapped", "k_r and k_p swapped (grains 0.15 and 15, walls 0.1 and 10), friction regularised "
                              "below 0.1 m/s"))


def _vc_variants(experiment, labels):
    """Vc(L) of design 1 run with one thing changed (studies/seed004/vc_variants.py EXPERIMENT): median of
    the pooled rows in steady state (their range)."""
    s = _load(f"studies/seed004/results/vc_{experiment}.json")
    head = "| variant | " + " | ".join(f"Vc at L = {d} m" for d in SEGREGATION_AT) + " |"
    rows = [head, "|---|" + "---|" * len(SEGREGATION_AT)]
    for key, label in labels:
        cells = []
        for d in SEGREGATION_AT:
            v = _at(s["vc"][key], d)
            cells.append(f"{100 * v['vc_median']:.1f} % ({100 * v['vc_min']:.1f}–{100 * v['vc_max']:.1f})")
        rows.append(f"| {label} | " + " | ".join(cells) + " |")
    commits = sorted(set(s["commits"].values())) if "commits" in s else [s["commit"]]
    builds = ("build " + commits[0] if len(commits) == 1 else
              "builds " + "; ".join(f"{c} ({', '.join(n for n, k in s['commits'].items() if k == c)})"
                                    for c in commits))
    return "\n".join(rows) + (f"\n\nDesign 1, representative volumes, 300 s from empty, rows of 20 s pooled from "
                              f"{s['steady_from_s']:.0f} s; {builds}.\n")


GEOMETRY_LABELS = (("seed", "the scene's: partitions at 0.16, 0.28, 0.40 m, end ring at 0.5 m"),
                   ("end_at_0.4", "end ring at 0.40 m, no outlet compartment"),
                   ("end_at_0.4_hole_0.06", "end ring at 0.40 m with a 0.06 m hole"))
GEOMETRY_AT = (0.025, 0.1, 0.2, 0.3, 0.375, 0.4)


def _housing_table(experiment, labels, at, first, key=False):
    """Design 1 in other housings (studies/seed004/vc_variants.py EXPERIMENT): Vc median (range) per layer,
    with the random-mixture Vc or the key's volume fraction, and the steady hold-up."""
    s = _load(f"studies/seed004/results/vc_{experiment}.json")
    head = (f"| {first} | hold-up (model particles) | " + " | ".join(f"Vc at L = {d} m" for d in at) + " |")
    rows = [head, "|---|---|" + "---|" * len(at)]
    for name, label in labels:
        end = s["scenes"].get(name, {}).get("length", 0.5)
        cells = []
        for d in at:
            v = next((x for x in s["vc"][name] if abs(x["distance"] - d) < 1e-9), None)
            outside = d + 0.011 > end  # the layer (22 mm thick) reaches the end ring or past it
            tail = (f"key {v['key_fraction']:.2f}" if key else f"random {100 * v['random_vc_median']:.1f} %") if v else ""
            cells.append("outside" if outside else "—" if v is None else
                         f"{100 * v['vc_median']:.1f} % ({100 * v['vc_min']:.1f}–{100 * v['vc_max']:.1f}); {tail}")
        rows.append(f"| {label} | {s['holdup'][name]['grains']:.0f} | " + " | ".join(cells) + " |")
    commits = sorted(set(s["commits"].values()))
    what = ("key: the key's volume fraction in the layer (median)" if key else
            "random: the median Vc a random mixture of the cells' visits gives")
    return "\n".join(rows) + (f"\n\nDesign 1, representative volumes, 300 s from empty, rows of 20 s pooled from "
                              f"{s['steady_from_s']:.0f} s: median (range); {what}; build {', '.join(commits)}.\n")


def seed004_vc_geometry():
    """Design 1 with and without the bladeless outlet compartment (vc_variants.py geometry)."""
    return _housing_table("geometry", GEOMETRY_LABELS, GEOMETRY_AT, "housing")


PARTITION_LABELS = (("seed", "the scene's: 15 mm high (inner radius 0.085 m)"),
                    ("rings_10mm", "10 mm high (inner radius 0.09 m)"),
                    ("rings_30mm", "30 mm high (inner radius 0.07 m)"),
                    ("none", "no partitions"))
PARTITION_AT = (0.025, 0.1, 0.15, 0.2, 0.275, 0.3, 0.375, 0.4, 0.45)


def seed004_vc_partitions():
    """Design 1 with its partitions (0.16, 0.28, 0.40 m) lower, higher or left out (vc_variants.py
    partitions)."""
    return _housing_table("partitions", PARTITION_LABELS, PARTITION_AT, "partitions", key=True)


FEED_LABELS = (("seed", "the scene's: 25 g every 0.5 s into a box above the bed"),
               ("stream", "the same box, 2.5 g every 0.05 s"),
               ("nozzle", "2.5 g every 0.05 s into a 40 mm mouth on the axis, at rest"),
               ("nozzle_jet", "the same mouth, leaving at 0.5 m/s along the axis"))
FEED_AT = (0.025, 0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.4)


def seed004_vc_feed():
    """Design 1 fed in batches, as a trickle, or through a nozzle's mouth on the axis (vc_variants.py feed)."""
    return _housing_table("feed", FEED_LABELS, FEED_AT, "feed", key=True)


def seed004_vc_segregation():
    return _vc_variants("segregation", SEGREGATION_LABELS)


def seed004_vc_reading():
    return _vc_variants("reading", READING_LABELS)


TABLES = {"seed004_side_by_side": seed004_side_by_side, "seed004_vc_sampling": seed004_vc_sampling,
          "seed004_vc_segregation": seed004_vc_segregation, "seed004_vc_reading": seed004_vc_reading,
          "seed004_vc_geometry": seed004_vc_geometry, "seed004_vc_partitions": seed004_vc_partitions,
          "seed004_vc_feed": seed004_vc_feed}

"""The README's two generated tables: the studies at a glance and the speed against LIGGGHTS.

Both are drawn from the results pages' own generated tables (the other modules of tools/readme/makers/), so
the front page can never say more than the pages do: a study's line counts the rows of its side-by-side
table whose "agree?" cell starts with "yes"; the speed lines are the first two rows of the performance
page's summary. They read only committed files (studies/<study>/results/ and docs/results/data/), through those makers.
"""
import importlib.util
from pathlib import Path

MAKERS = Path(__file__).resolve().parent

# (study, paper, what the paper shows, side-by-side table, picture, results page)
STUDIES = [
    ("000 drum", "Zhao & Cheng 2007", "a binary mixture in a thin rotating drum forms a moon at high speed and "
     "petals at low speed", "seed000", "seed000_side_by_side",
     "studies/seed000/results/study/half_w0.25/pictures/angle_30.00.png", "docs/results/seed000-drum.md"),
    ("001 kiln", "Chen Hui et al.", "a map of mixing and segregation over size and density ratios in a "
     "rotary kiln", "seed001", "seed001_side_by_side", "studies/seed001/results/map.png", "docs/results/seed001-kiln.md"),
    ("002 composites", "Li, Liu & Ji", "concave grains as rigid composites of dilated polyhedra: packing order "
     "of letters, hopper discharge and arches", "seed002", "seed002_side_by_side",
     "studies/seed002/results/packing/packing_profiles.png", "docs/results/seed002-composites.md"),
    ("003 liquid", "Pan, Xie & Wan 2021", "MPS liquid coupled to DEM: grains carried up a vertical pipe",
     "seed003", "seed003_side_by_side", "studies/seed003/results/transport_pipe_views.png", "docs/results/seed003-liquid.md"),
    ("004 mixer", "Cherpitskiy, Korolev & Tarshis 2022", "coarse-grained DEM of a continuous drum-blade "
     "mixer: the inhomogeneity Vc along its length", "seed004", "seed004_side_by_side",
     "studies/seed004/results/vc_profile.png", "docs/results/seed004-mixer.md"),
    ("contact laws", "analytic solutions, Chung & Ooi 2011", "single contacts with known answers",
     "contact", "contact_side_by_side", None, "docs/results/contact.md"),
]


def maker(module, name):
    spec = importlib.util.spec_from_file_location(f"front_{module}", MAKERS / f"{module}.py")
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    return m.TABLES[name]


def rows_of(table):
    lines = [l for l in table.splitlines() if l.startswith("|")]
    head = [c.strip() for c in lines[0].strip("|").split("|")]
    return head, [[c.strip() for c in l.strip("|").split("|")] for l in lines[2:]]


def studies_table():
    out = ["| study | the paper shows | grainflow agrees on | picture | results |", "|---|---|---|---|---|"]
    for study, paper, shows, module, name, picture, page in STUDIES:
        head, rows = rows_of(maker(module, name)())
        col = head.index("agree?")
        yes = sum(r[col].startswith("yes") for r in rows)
        pic = f'<img src="{picture}" width="120" alt="{study}">' if picture else ""
        out.append(f"| {study} ({paper}) | {shows} | {yes} of {len(rows)} headline rows | {pic} | "
                   f"[{Path(page).name}]({page}) |")
    return "\n".join(out) + "\n"


def speed_table():
    head, rows = rows_of(maker("performance", "performance_summary")())
    out = ["| " + " | ".join(head[:3]) + " |", "|---|---|---|"]
    out += ["| " + " | ".join(r[:3]) + " |" for r in rows[:2]]
    return "\n".join(out) + "\n"


TABLES = {"readme_studies": studies_table, "readme_speed": speed_table}

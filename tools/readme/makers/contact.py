"""Generated tables of docs/results/contact.md (tools/readme/tables.py collects TABLES).

contact_side_by_side: the references' figures (docs/results/data/contact_paper.json: closed forms and
Chung & Ooi 2011) next to grainflow's, from the files the tests write (studies/contact/results/analytic.csv and
studies/contact/results/chung_ooi.csv). Before it compares, it checks that the JSON's reference values equal the
reference column the tests recorded, so the two cannot drift apart. "agree?" follows the JSON's
agree_rule: every figure of the row within the tolerance its test asserts.
"""
import csv
import json
import math
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[3]
PAPER = "docs/results/data/contact_paper.json"


def _pct(e):
    return "0 %" if e == 0 else f"{e:+.3g} %"


def _cell(text):
    return str(text).replace("|", "\\|")


def _g(v, digits):
    return "0" if v == 0 else f"{v:.{digits}g}"


def _rows(path):
    with open(ROOT / path, newline="") as f:
        return list(csv.DictReader(f))


def _select(rows, match, case_key):
    """Rows whose case contains the first text and whose quantity contains the second, in `match` order."""
    out = []
    for case, quantity in match:
        found = [r for r in rows if case in r[case_key] and quantity in r["quantity"]]
        if not found:
            raise SystemExit(f"{PAPER}: no row of '{case}' / '{quantity}' in the result file")
        out += [r for r in found if r not in out]
    return out


def _figures(row):
    """(reference, grainflow, error in %, tolerance in %) of each figure the row compares."""
    path = row["file"]
    if path.endswith("analytic.csv"):
        got = _select(_rows(path), row["match"], "case")
        figs = []
        for r in got:
            scale = {"relative %": 1.0, "relative": 100.0}.get(r["error_kind"])
            if scale is None:
                raise SystemExit(f"{path}: '{r['case']}' {r['quantity']}: expected a relative error")
            figs.append((float(r["reference"]), float(r["measured"]), scale * float(r["error"]),
                         scale * float(r["tolerance"])))
        return figs
    got = _select(_rows(path), row["match"], "test")
    tol = float(row["tolerance_percent"])
    return [(float(r["reference"]), float(r["grainflow"]), 100 * float(r["relative_error"]), tol) for r in got]


def contact_side_by_side():
    paper = json.loads((ROOT / PAPER).read_text())
    lines = ["| quantity | the paper reports | grainflow gets | agree? | why not |", "|---|---|---|---|---|"]
    for row in paper["rows"]:
        figs = _figures(row)
        values = row["values"]
        if len(values) != len(figs):
            raise SystemExit(f"{PAPER}: '{row['quantity']}' lists {len(values)} values for {len(figs)} figures")
        for v, (ref, _, _, _) in zip(values, figs):
            if not math.isclose(v, ref, rel_tol=5e-4, abs_tol=0.0):
                raise SystemExit(f"{PAPER}: '{row['quantity']}': value {v} differs from the tests' reference {ref}")
        ours = [g for _, g, _, _ in figs]
        errors = [e for _, _, e, _ in figs]
        agree = all(math.isfinite(e) and abs(e) <= t for _, _, e, t in figs)
        distinct = list(dict.fromkeys(values))
        shown = (", ".join(_g(v, 5) for v in distinct) if len(distinct) <= 5
                 else f"{_g(min(distinct), 5)} to {_g(max(distinct), 5)}")
        reports = f"{row['reports']} = {shown}" if "reports" in row else shown
        if len(figs) <= 3:
            got = ", ".join(_g(g, 5) for g in ours) + " (" + ", ".join(_pct(e) for e in errors) + ")"
        else:
            got = (f"{_g(min(ours), 5)} to {_g(max(ours), 5)}; errors {_pct(min(errors))} to {_pct(max(errors))} "
                   f"over {len(figs)} cases")
        tols = sorted({t for _, _, _, t in figs})
        verdict = ("yes" if agree else "no") + " (within " + " and ".join(f"{_g(t, 2)} %" for t in tols) + ")"
        why = "—" if agree else row.get("why_not", "cause not yet measured")
        lines.append(f"| {_cell(row['quantity'])} | {_cell(reports)} | {_cell(got)} | {verdict} | {_cell(why)} |")
    return "\n".join(lines) + "\n"


TABLES = {"contact_side_by_side": contact_side_by_side}

if __name__ == "__main__":
    print(contact_side_by_side(), end="")

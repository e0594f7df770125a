"""The performance results page's side-by-side table (docs/results/performance.md): grainflow against
LIGGGHTS 3.8 and against the project's stated aims, from the committed result files.

Reads docs/results/data/performance_reference.json (the aims), the comparison logs of
studies/performance/run_comparison.sh (studies/performance/results/comparison*.log, parsed by studies/performance/comparison_table.py),
the flow ensemble (studies/performance/results/flow_ensemble.json) and the scaling logs of studies/performance/bench_scaling.sh
(studies/performance/results/scaling*.log, parsed by studies/performance/scaling_table.py).

Rules for "agree?":
  - a speed row: "faster" when grainflow's rate is above LIGGGHTS's in every round of the log (each round runs
    both codes back to back), and whether the median per-round ratio reaches the aim of ten times per core;
  - a flow row: "yes" when, at every sample from the file's from_t on, LIGGGHTS lies within the range of
    grainflow's ensemble widened by the tolerance;
  - the scaling row: "yes" when the smallest layer's one-thread rate per grain is within the aim (20 %) of the
    largest layer's.
"""
import json
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "studies" / "performance"))
from comparison_table import parse, round_ratios  # noqa: E402
from scaling_table import LINE, SCALE, one_thread_windows  # noqa: E402

LOGS = ROOT / "studies/performance/results"
REFERENCE = ROOT / "docs/results/data/performance_reference.json"


def _log(name):
    """Rates by (code, threads, round), rebuilds by code, per-round ratios by threads."""
    runs, builds, _, _ = parse(LOGS / name)
    return runs, builds, round_ratios(runs)


def _speed_row(what, name, n, aim):
    runs, _, ratios = _log(name)
    rounds = sorted({r for c, k, r in runs if k == n and c == "liggghts"})
    lig = statistics.median(runs["liggghts", n, r] for r in rounds)
    gf = statistics.median(runs["grainflow", n, r] for r in rounds if ("grainflow", n, r) in runs)
    q = ratios[n]
    faster = sum(x > 1 for x in q)
    verdict = (f"faster in {faster} of {len(q)} rounds" if faster < len(q) else "faster in every round")
    verdict += f"; the aim ×{aim:g}: {'reached' if statistics.median(q) >= aim else 'not reached'}"
    return (f"{what} (`studies/performance/results/{name}`)", f"LIGGGHTS {lig:.3g} particle-steps/s (median of {len(rounds)})",
            f"{gf:.3g} particle-steps/s; per round **×{statistics.median(q):.2f}** (×{min(q):.2f}–{max(q):.2f})",
            verdict)


def _windows_row(n, aim):
    meds = []
    for log in sorted(LOGS.glob("comparison_flowing*.log")):
        q = round_ratios(parse(log)[0])[n]
        if q:
            meds.append(statistics.median(q))
    reached = sum(m >= aim for m in meds)
    cores = f"{n} core{'s' if n > 1 else ''}"
    return (f"flowing drum, {cores}, every committed window (`studies/performance/results/comparison_flowing*.log`, {len(meds)} logs)",
            f"the aim: ×{aim:g} LIGGGHTS per core",
            f"median per-round ratio of each window: ×{min(meds):.2f}–{max(meds):.2f} (median ×{statistics.median(meds):.2f})",
            f"faster in every window; the aim reached in {reached} of {len(meds)}")


def _flow_notes(s):
    """The ensemble's one-sided samples (angle) and the single runs' misses of the speed tolerance."""
    import csv
    ens = [r for r in csv.DictReader((LOGS / "flow_ensemble.csv").open()) if float(r["t"]) >= s["from_t"]]
    above = [(f'{float(r["t"]):.1f}', float(r["angle_liggghts_deg"]) - float(r["angle_max_deg"])) for r in ens]
    above = [(t, d) for t, d in above if d > 0.05]
    one = json.loads((LOGS / "flow_agreement.json").read_text())
    runs = [r for r in csv.DictReader((LOGS / "flow_agreement.csv").open()) if float(r["t"]) >= one["from_t"]]
    miss = [(f'{float(r["t"]):.1f}', abs(float(r["speed_diff_rel"]))) for r in runs
            if abs(float(r["speed_diff_rel"])) > one["speed_tolerance_rel"]]
    angle = NOTES["angle"].format(ts=", ".join(t for t, _ in above), lo=min(d for _, d in above),
                                  hi=max(d for _, d in above))
    speed = NOTES["speed"].format(ts=", ".join(t for t, _ in miss),
                                  miss=f"{100 * min(d for _, d in miss):.1f}–{100 * max(d for _, d in miss):.1f}")
    return angle, speed


def _flow_rows():
    s = json.loads((LOGS / "flow_ensemble.json").read_text())
    n = len(s["members"])
    return [
        (f"free-surface angle, 1.5 s of rotation from rest, every 0.1 s from {s['from_t']} s "
         "(`studies/performance/results/flow_ensemble.json`)",
         "LIGGGHTS, one run",
         f"{n} runs differing only in round-off; LIGGGHTS outside their range by at most "
         f"{s['max_angle_outside_deg']:.2f}° (their own spread up to {s['max_angle_spread_deg']:.2f}°)",
         f"{'yes' if s['max_angle_outside_deg'] <= s['angle_tolerance_deg'] else 'no'} "
         f"(tolerance {s['angle_tolerance_deg']}°)"),
        (f"mean grain speed, the same samples", "LIGGGHTS, one run",
         f"LIGGGHTS outside the {n} runs' range by at most {100 * s['max_speed_outside_rel']:.1f} % "
         f"(their own spread up to {100 * s['max_speed_spread_rel']:.1f} %)",
         f"{'yes' if s['max_speed_outside_rel'] <= s['speed_tolerance_rel'] else 'no'} "
         f"(tolerance {100 * s['speed_tolerance_rel']:.0f} %)"),
    ]


def _scaling_row(within):
    # AMD EPYC: one window, studies/performance/results/scaling.log; Intel Xeon: the medians over its windows.
    epyc = {}
    for line in (ROOT / "studies/performance/results/scaling.log").open():
        m = LINE.search(line)
        if m and int(m.group(1)) == 1:
            epyc[round(float(m.group(2)) * SCALE[m.group(3)])] = float(m.group(4)) * SCALE[m.group(5)]
    e = epyc[min(epyc)] / epyc[max(epyc)]
    rates = {}
    for w in one_thread_windows([ROOT / p for p in ("studies/performance/results/scaling_xeon.log", "studies/performance/results/scaling_knee_xeon.log",
                                                    "studies/performance/results/scaling_small_xeon.log")]):
        for g, r in w.items():
            rates.setdefault(g, []).append(r)
    x = statistics.median(rates[min(rates)]) / statistics.median(rates[max(rates)])
    ok = max(e, x) <= 1 + within
    return (f"cost per grain, settled layer of {min(epyc):,} against {max(epyc):,} grains, 1 thread "
            "(`studies/performance/results/scaling.log`; Xeon: `scaling_xeon.log`, `scaling_knee_xeon.log`, `scaling_small_xeon.log`)",
            f"the aim: equal within {100 * within:.0f} %",
            f"the smaller layer ×{e:.2f} as fast per grain (AMD EPYC); ×{x:.2f} (Intel Xeon, medians over windows)",
            "yes" if ok else "no")


NOTES = {
    "flow1": "the step waits on memory, not arithmetic (time split and profile below)",
    "flow2": "LIGGGHTS gains {lg} from its second rank, grainflow {gg}",
    "xeon1": "both codes slower on this Xeon, grainflow more: the drum's arrays do not fit its 2 MB L2",
    "xeon2": "the current build (closing kick deferred)",
    "windows1": "the ratio moves with the host's state; aims and bounds in the notes",
    "windows2": "",
    "settled1": "start of rotation, a rigid-body turn: fewer rebuilds (LIGGGHTS {lr}, grainflow {gr})",
    "settled2": "",
    "rebuilds": "grainflow keeps its list past skin/2 while no pair missing from it touches",
    "angle": "LIGGGHTS's angle above the range by more than 0.05° at t = {ts} s (by {lo:.2f}–{hi:.2f}°): within the "
             "tolerance but on one side; cause not yet measured",
    "speed": "a single run of each is {miss} % apart at t = {ts} s (`studies/performance/results/flow_agreement.csv`): "
             "round-off moves the first avalanche",
    "scaling": "the state leaves the cache; running the step over blocks of space is not built",
}


def _gain(runs, code):
    rounds = sorted({r for c, k, r in runs if c == code})
    one = statistics.median(runs[code, 1, r] for r in rounds if (code, 1, r) in runs)
    two = statistics.median(runs[code, 2, r] for r in rounds if (code, 2, r) in runs)
    return f"×{two / one:.2f}"


def summary():
    ref = json.loads(REFERENCE.read_text())
    aim = ref["aim_ratio_per_core"]["value"]
    flowing, builds, _ = _log("comparison_flowing.log")
    settled, sbuilds, _ = _log("comparison.log")
    rows = [
        _speed_row("flowing seed-000 drum, 1 core, AMD EPYC", "comparison_flowing.log", 1, aim) + (NOTES["flow1"],),
        _speed_row("flowing seed-000 drum, 2 cores, AMD EPYC", "comparison_flowing.log", 2, aim)
        + (NOTES["flow2"].format(lg=_gain(flowing, "liggghts"), gg=_gain(flowing, "grainflow")),),
        _speed_row("flowing drum, 1 core, Intel Xeon", "comparison_flowing_xeon.log", 1, aim) + (NOTES["xeon1"],),
        _speed_row("flowing drum, 2 cores, Intel Xeon", "comparison_flowing_xeon.log", 2, aim) + (NOTES["xeon2"],),
        _windows_row(1, aim) + (NOTES["windows1"],),
        _windows_row(2, aim) + (NOTES["windows2"],),
        _speed_row("settled drum, 1 core, AMD EPYC", "comparison.log", 1, aim)
        + (NOTES["settled1"].format(lr=min(sbuilds["liggghts"]), gr=min(sbuilds["grainflow"])),),
        _speed_row("settled drum, 2 cores, AMD EPYC", "comparison.log", 2, aim) + (NOTES["settled2"],),
        ("neighbour-list rebuilds in 2,000 steps of the flowing drum (`studies/performance/results/comparison_flowing.log`)",
         f"LIGGGHTS {min(builds['liggghts'])}", f"{min(builds['grainflow'])}",
         "fewer" if max(builds["grainflow"]) < min(builds["liggghts"]) else "not fewer", NOTES["rebuilds"]),
    ]
    angle, speed = _flow_rows()
    angle_note, speed_note = _flow_notes(json.loads((LOGS / "flow_ensemble.json").read_text()))
    rows += [angle + (angle_note,), speed + (speed_note,)]
    rows.append(_scaling_row(ref["aim_scaling_within"]["value"]) + (NOTES["scaling"],))
    out = ["| quantity | the reference | grainflow gets | agree? | note |", "|---|---|---|---|---|"]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(out) + "\n"


TABLES = {"performance_summary": summary}

if __name__ == "__main__":
    print(summary(), end="")

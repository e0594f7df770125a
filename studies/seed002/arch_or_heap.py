#!/usr/bin/python3
"""Whether a hopper run of seed 002 (case 1) ended on an arch or on dead zones.

Per run folder: the remaining fraction at the end and when the discharge last changed it, the
stalls of at least 0.1 s (no body left over that time), and, from the final frame
(final_frame.csv, or the last frames/frame_*.csv), how many moving bodies sit over the outlet
(|x| below half the gate's 40 mm, centre less than 30 mm above the bottom's top face at y = 0):
an arch holds bodies there while nothing leaves; a flow that stopped on dead zones leaves the
space over the outlet empty. Writes JSON with one entry per run.

    /usr/bin/python3 studies/seed002/arch_or_heap.py RUN [RUN ...] -o studies/seed002/results/friction/friction.json
    /usr/bin/python3 studies/seed002/arch_or_heap.py --table studies/seed002/results/outlet/outlet.json
    /usr/bin/python3 studies/seed002/arch_or_heap.py --ensemble studies/seed002/results/outlet/outlet.json

--table prints a Markdown table of a written JSON, a row per run: the grain's size (the prism's side, or
the cone element's triangle side, from the run's overrides), the gate's width in those sides, when half
had gone, what was left at the end and since when, the stalls, and the verdict: an arch (discharge
stopped with bodies over the outlet), stopped on dead zones (nothing over it) or still flowing.

--ensemble prints a row per grain shape and gate width over every pour of them in the JSON: how many
pours ended on an arch, each pour's count of stops of 0.1 s or more (stalls and the final stop), when
the flow first stopped so, and what was left at the end, as median and range.
"""
import argparse
import glob
import json
import math
import pathlib
import statistics
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "python"))


def _outputs():
    """grainflow.outputs, imported where run files are read: it needs numpy, the tables do not."""
    import grainflow.outputs
    return grainflow.outputs


HALF_GATE = 0.02  # m
ABOVE = 0.03      # m


def series(run):
    s = _outputs().Run(run).series
    return s["time"].tolist(), s["remaining_fraction"].tolist()


def stalls(t, f, shortest=0.1):
    out, since = [], None
    for k in range(1, len(t)):
        if f[k] == f[k - 1]:
            since = t[k - 1] if since is None else since
            continue
        if since is not None and t[k - 1] - since >= shortest:
            out.append({"from_s": round(since, 3), "lasting_s": round(t[k - 1] - since, 3)})
        since = None
    return out


def over_outlet(run):
    run = pathlib.Path(run)
    frame = run / "final_frame.csv"
    if not frame.exists():
        frames = sorted(glob.glob(str(run / "frames" / "frame_0*.csv")))
        if not frames:
            return None
        frame = pathlib.Path(frames[-1])
    d = _outputs().read_csv(frame)
    over = (d["motion"] == "moving") & (abs(d["x"]) < HALF_GATE) & (d["y"] > 0.0) & (d["y"] < ABOVE)
    return int(over.sum())


def grain_side_mm(overrides):
    """The prism's side, or the cone element's triangle side (corners on base_radius), in mm; 10 unless set."""
    for o in overrides:
        key, _, value = o.partition("=")
        if key == "shape.0.side":
            return 1e3 * float(value)
        if key == "shape.0.base_radius":
            return 1e3 * float(value) * math.sqrt(3)
    return 10.0


def verdict(e):
    stopped = e["end_s"] - e["last_change_s"] >= 0.5
    return ("arch" if e["bodies_over_outlet_at_end"] else "dead zones") if stopped else "still flowing"


def shape_of(overrides):
    return "cones" if any(o.startswith("shape.0.base_radius=") for o in overrides) else "prisms"


def first_stop(e):
    """When the flow first stopped for 0.1 s or more: the first stall, or the final stop; None if never."""
    times = [x["from_s"] for x in e["stalls"]]
    if verdict(e) != "still flowing":
        times.append(e["last_change_s"])
    return min(times) if times else None


def spread(values, fmt):
    if not values:
        return "—"
    values = sorted(values)
    med = statistics.median(values)
    return fmt.format(med) if len(values) == 1 else f"{fmt.format(med)} ({fmt.format(values[0])}–{fmt.format(values[-1])})"


def ensemble(path):
    runs = json.loads(pathlib.Path(path).read_text())
    groups = {}
    for run, e in runs.items():
        key = (shape_of(e["overrides"]), round(40 / grain_side_mm(e["overrides"]), 1))
        groups.setdefault(key, []).append(e)
    print("| grains | gate in grain sides | pours | ended on an arch | stops of 0.1 s or more per pour "
          "| first stop (s): median (range) | first stops, each pour, sorted (s) | left at the end: median (range) |")
    print("|---" * 8 + "|")
    for (shape, sides), es in sorted(groups.items()):
        stops = [first_stop(e) for e in es if first_stop(e) is not None]
        arches = sum(verdict(e) == "arch" for e in es)
        counts = ", ".join(str(len(e["stalls"]) + (verdict(e) != "still flowing")) for e in es)
        each = ", ".join(f"{t:.2f}" for t in sorted(stops)) or "—"
        if len(stops) < len(es):
            each += f"; {len(es) - len(stops)} without a stop"
        print(f"| {shape} | {sides:.1f} | {len(es)} | {arches} | {counts} | {spread(stops, '{:.2f}')} | {each} "
              f"| {spread([e['remaining_at_end'] for e in es], '{:.3f}')} |")


def table(path):
    runs = json.loads(pathlib.Path(path).read_text())
    print("| run | grain side (mm) | gate in grain sides | half gone at (s) | left at the end | unchanged since (s) "
          "| stalls of 0.1 s or more (from, lasting) | bodies over the outlet | verdict |")
    print("|---" * 9 + "|")
    for run, e in runs.items():
        side = grain_side_mm(e["overrides"])
        st = "; ".join(f"{x['from_s']:.2f} s, {x['lasting_s']:.2f} s" for x in e["stalls"]) or "none"
        half = f"{e['half_gone_s']:.2f}" if e.get("half_gone_s") is not None else "not reached"
        over = "—" if e["bodies_over_outlet_at_end"] is None else e["bodies_over_outlet_at_end"]
        print(f"| `{pathlib.Path(run).name}` | {side:.1f} | {40 / side:.1f} | {half} | {e['remaining_at_end']:.3f} "
              f"at {e['end_s']:.1f} s | {e['last_change_s']:.2f} | {st} | {over} | {verdict(e)} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="*")
    ap.add_argument("-o", "--output")
    ap.add_argument("--table", help="print the table of this JSON instead")
    ap.add_argument("--ensemble", help="print the table of pours per shape and gate width of this JSON instead")
    a = ap.parse_args()
    if a.table:
        table(a.table)
        return
    if a.ensemble:
        ensemble(a.ensemble)
        return
    result = {}
    for run in a.runs:
        t, f = series(run)
        summary = _outputs().Run(run).summary
        ended = next(ti for ti, fi in zip(t, f) if fi == f[-1])
        half = next((ti for ti, fi in zip(t, f) if fi <= 0.5), None)
        entry = {"overrides": summary.get("overrides", []), "remaining_at_end": f[-1], "end_s": t[-1],
                 "half_gone_s": half,
                 "last_change_s": round(ended, 3), "stalls": stalls(t, f), "bodies_over_outlet_at_end": over_outlet(run)}
        result[run] = entry
        print(f"{run}: {f[-1]:.3f} left at {t[-1]:.2f} s, unchanged since {ended:.2f} s; stalls {entry['stalls']}; "
              f"bodies over the outlet at the end: {entry['bodies_over_outlet_at_end']}")
    if a.output:
        pathlib.Path(a.output).write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()

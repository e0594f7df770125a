#!/usr/bin/python3
"""Whether a hopper run of seed 002 (case 1) ended on an arch or on dead zones.

Per run folder: the remaining fraction at the end and when the discharge last changed it, the
stalls of at least 0.1 s (no body left over that time), and, from the final frame
(final_frame.csv, or the last frames/frame_*.csv), how many moving bodies sit over the outlet
(|x| below half the gate's 40 mm, centre less than 30 mm above the bottom's top face at y = 0):
an arch holds bodies there while nothing leaves; a flow that stopped on dead zones leaves the
space over the outlet empty. Writes JSON with one entry per run.

    /usr/bin/python3 tools/seed002/arch_or_heap.py RUN [RUN ...] -o docs/seed002/friction/friction.json
"""
import argparse
import csv
import glob
import json
import pathlib

HALF_GATE = 0.02  # m
ABOVE = 0.03      # m


def series(run):
    rows = list(csv.DictReader(open(pathlib.Path(run) / "series.csv")))
    return [float(r["time"]) for r in rows], [float(r["remaining_fraction"]) for r in rows]


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
    rows = [r for r in csv.DictReader(open(frame)) if r["motion"] == "moving"]
    return sum(abs(float(r["x"])) < HALF_GATE and 0.0 < float(r["y"]) < ABOVE for r in rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("-o", "--output")
    a = ap.parse_args()
    result = {}
    for run in a.runs:
        t, f = series(run)
        summary = json.loads((pathlib.Path(run) / "summary.json").read_text())
        ended = next(ti for ti, fi in zip(t, f) if fi == f[-1])
        entry = {"overrides": summary.get("overrides", []), "remaining_at_end": f[-1], "end_s": t[-1],
                 "last_change_s": round(ended, 3), "stalls": stalls(t, f), "bodies_over_outlet_at_end": over_outlet(run)}
        result[run] = entry
        print(f"{run}: {f[-1]:.3f} left at {t[-1]:.2f} s, unchanged since {ended:.2f} s; stalls {entry['stalls']}; "
              f"bodies over the outlet at the end: {entry['bodies_over_outlet_at_end']}")
    if a.output:
        pathlib.Path(a.output).write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()

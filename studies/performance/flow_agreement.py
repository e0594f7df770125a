#!/usr/bin/python3
"""Does grainflow's drum flow as LIGGGHTS' does? The seed-000 drum from the shared settled state,
1.5 s of rotation at 0.5 rad/s in both codes, compared every 0.1 s.

    /usr/bin/python3 studies/performance/flow_agreement.py liggghts [--out runs/flow_ref] [--ranks 1]
    /usr/bin/python3 studies/performance/flow_agreement.py grainflow [--out runs/flow_ref] [--threads 2] [--binary build/grainflow]
    /usr/bin/python3 studies/performance/flow_agreement.py compare [--out runs/flow_ref] [--docs studies/performance/results]
    /usr/bin/python3 studies/performance/flow_agreement.py spread --out runs/flow_ref --other DIR [--docs studies/performance/results]

`liggghts` runs LIGGGHTS 3.8 (make_inputs.py, dumps every 10,000 steps) in <out>/liggghts;
`grainflow` runs scenes/drum_seed000_settled.toml in 15 pieces of 10,000 steps, each resumed from the
last one's checkpoint (bit-identical to one run) and each leaving its final_state.csv, kept as
<out>/grainflow/state_<step>.csv; a finished piece is skipped. `compare` measures both codes' states
the same way and writes <docs>/flow_agreement.csv (one row per 0.1 s) and flow_agreement.json (the
largest differences, the tolerances, pass or fail). The measures are those of the shared flowing
state's README (../shared/data): the free-surface angle from the second-highest grain top in 5 mm bins
over |x| <= 45 mm, fitted by a straight line, and the mean speed |v| of all grains. Tolerances: 0.5 deg
and 3 % of mean |v| at every sample, from the first 0.3 s on (before, the bed turns as a rigid body,
its surface is the settled one and its mean speed starts from zero, so a relative speed difference
means little).

`spread` measures how far two grainflow runs of the same physics drift apart: <out>/grainflow
against DIR (states of another build, e.g. one that sums in another order, run with `grainflow
--out DIR/.. --binary OTHER`), written to <docs>/flow_spread.csv: the flow's own sensitivity, the
floor under any comparison between codes.
"""
import argparse
import csv
import glob
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))


def _outputs():
    """grainflow.outputs, imported where run files are read: it needs numpy, the tables do not."""
    import grainflow.outputs
    return grainflow.outputs


REPO = os.path.dirname(os.path.dirname(HERE))
SCENE = "scenes/drum_seed000_settled.toml"
STEPS_PER_SAMPLE = 10000  # 0.1 s at dt = 1e-5 s
SAMPLES = 15
DT = 1.0e-5
ANGLE_TOL_DEG = 0.5
SPEED_TOL = 0.03
FROM_T = 0.3


def surface_angle_deg(rows):
    """Second-highest grain top (y + r) in 5 mm bins over |x| <= 45 mm, straight-line fit; degrees."""
    bins = {}
    for x, y, r in rows:
        if abs(x) > 0.045:
            continue
        b = math.floor((x + 0.045) / 0.005)
        top = y + r
        t = bins.setdefault(b, [-math.inf, -math.inf])
        if top > t[0]:
            t[1], t[0] = t[0], top
        elif top > t[1]:
            t[1] = top
    pts = [(-0.045 + (b + 0.5) * 0.005, t[1]) for b, t in sorted(bins.items()) if t[1] > -math.inf]
    n = len(pts)
    su = sum(p[0] for p in pts)
    sv = sum(p[1] for p in pts)
    suu = sum(p[0] * p[0] for p in pts)
    suv = sum(p[0] * p[1] for p in pts)
    return math.degrees(math.atan((n * suv - su * sv) / (n * suu - su * su)))


def measures(rows):
    """(angle in degrees, mean |v| in m/s) of rows (x, y, r, vx, vy, vz)."""
    angle = surface_angle_deg([(x, y, r) for x, y, r, *_ in rows])
    speed = sum(math.sqrt(vx * vx + vy * vy + vz * vz) for *_, vx, vy, vz in rows) / len(rows)
    return angle, speed


def read_grainflow(path):
    d = _outputs().read_csv(path)
    return [(float(x), float(y), 0.5 * float(dia), float(vx), float(vy), float(vz))
            for x, y, dia, vx, vy, vz in zip(d["x"], d["y"], d["diameter"], d["vx"], d["vy"], d["vz"])]


def read_liggghts(path):
    rows, cols = [], None
    with open(path) as f:
        for line in f:
            if line.startswith("ITEM: ATOMS"):
                cols = line.split()[2:]
                continue
            if cols and not line.startswith("ITEM"):
                v = dict(zip(cols, line.split()))
                rows.append((float(v["x"]), float(v["y"]), float(v["radius"]), float(v["vx"]), float(v["vy"]),
                             float(v["vz"])))
    return rows


def run_liggghts(out, ranks):
    work = os.path.join(out, "liggghts")
    subprocess.run([sys.executable, os.path.join(HERE, "make_inputs.py"), work, "--steps",
                    str(STEPS_PER_SAMPLE * SAMPLES), "--dump-every", str(STEPS_PER_SAMPLE)], check=True)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    with open(os.path.join(work, "out.txt"), "w") as log:
        subprocess.run(["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), "liggghts", "-in",
                        "in.drum", "-log", "log.liggghts"], cwd=work, env=env, stdout=log, stderr=log, check=True)


def run_grainflow(out, threads, binary, sets=()):
    work = os.path.join(out, "grainflow")
    os.makedirs(work, exist_ok=True)
    ckpt = os.path.join(work, "checkpoints", "checkpoint.gfc")
    for k in range(1, SAMPLES + 1):
        step = k * STEPS_PER_SAMPLE
        kept = os.path.join(work, f"state_{step:07d}.csv")
        if os.path.isfile(kept):
            continue
        cmd = [binary, "run", os.path.join(REPO, SCENE), "--out", work, "--threads", str(threads), "--quiet",
               "--steps", str(step), "--set", "output.frame_interval=0", "--set", "output.picture_angles=[]"]
        for kv in sets:
            cmd += ["--set", kv]
        if k > 1:
            cmd += ["--resume", ckpt]
        subprocess.run(cmd, check=True)
        os.replace(os.path.join(work, "final_state.csv"), kept)
        print(f"grainflow: {kept}", file=sys.stderr)


def compare(out, docs, other=None):
    rows = []
    for k in range(1, SAMPLES + 1):
        step = k * STEPS_PER_SAMPLE
        lp = (os.path.join(other, f"state_{step:07d}.csv") if other
              else os.path.join(out, "liggghts", f"dump.{step:07d}.txt"))
        gp = os.path.join(out, "grainflow", f"state_{step:07d}.csv")
        if not (os.path.isfile(lp) and os.path.isfile(gp)):
            sys.exit(f"flow_agreement: missing {lp if not os.path.isfile(lp) else gp}; run both codes first")
        la, ls = measures(read_grainflow(lp) if other else read_liggghts(lp))
        ga, gs = measures(read_grainflow(gp))
        rows.append({"t": round(step * DT, 6), "angle_liggghts_deg": la, "angle_grainflow_deg": ga,
                     "angle_diff_deg": ga - la, "speed_liggghts": ls, "speed_grainflow": gs,
                     "speed_diff_rel": (gs - ls) / ls})
    os.makedirs(docs, exist_ok=True)
    name = "flow_spread" if other else "flow_agreement"
    if other:  # the reference columns hold the other grainflow run
        rows = [{k.replace("liggghts", "other"): v for k, v in r.items()} for r in rows]
    with open(os.path.join(docs, name + ".csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    if other:
        return 0
    late = [r for r in rows if r["t"] >= FROM_T - 1e-9]
    worst_a = max(abs(r["angle_diff_deg"]) for r in late)
    worst_v = max(abs(r["speed_diff_rel"]) for r in late)
    commit = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    # The shared LIGGGHTS state at 1.5 s (another LIGGGHTS run of the same input), measured the same way:
    # how far two LIGGGHTS runs end apart.
    shared = os.path.join(REPO, "scenes", "data", "drum_flowing_t1.5s_47108.csv")
    sa, sv = measures(read_grainflow(shared))
    summary = {"commit": commit, "scene": SCENE, "samples": len(rows), "from_t": FROM_T,
               "shared_liggghts_state_1.5s": {"file": os.path.relpath(shared, REPO), "angle_deg": sa, "speed": sv},
               "max_angle_diff_deg": worst_a, "angle_tolerance_deg": ANGLE_TOL_DEG,
               "max_speed_diff_rel": worst_v, "speed_tolerance_rel": SPEED_TOL,
               "final": rows[-1], "pass": worst_a <= ANGLE_TOL_DEG and worst_v <= SPEED_TOL}
    with open(os.path.join(docs, "flow_agreement.json"), "w") as f:
        json.dump(summary, f, indent=1)
    for r in rows:
        print(f"t {r['t']:.1f} s: angle LIGGGHTS {r['angle_liggghts_deg']:6.2f} grainflow {r['angle_grainflow_deg']:6.2f}"
              f" ({r['angle_diff_deg']:+.2f} deg); mean |v| {r['speed_liggghts']:.4f} {r['speed_grainflow']:.4f}"
              f" ({100 * r['speed_diff_rel']:+.1f} %)")
    print(f"the shared LIGGGHTS state at 1.5 s: angle {sa:.2f} deg, mean |v| {sv:.4f} m/s")
    print(f"from {FROM_T} s: largest angle difference {worst_a:.2f} deg (tolerance {ANGLE_TOL_DEG}), largest mean-speed "
          f"difference {100 * worst_v:.1f} % (tolerance {100 * SPEED_TOL:.0f} %): {'pass' if summary['pass'] else 'FAIL'}")
    return 0 if summary["pass"] else 1


def ensemble(out, members, docs):
    """LIGGGHTS's run against an ensemble of grainflow runs of the same physics that differ only in
    round-off (another summation order: another build, skin or list). The flow amplifies round-off
    where the first avalanches start, so one run of each code is a sample, not the answer: the
    check is whether LIGGGHTS lies within the ensemble's range widened by the tolerances."""
    if len(members) < 2:
        sys.exit("flow_agreement: ensemble needs at least two member folders")
    rows = []
    for k in range(1, SAMPLES + 1):
        step = k * STEPS_PER_SAMPLE
        la, ls = measures(read_liggghts(os.path.join(out, "liggghts", f"dump.{step:07d}.txt")))
        ms = [measures(read_grainflow(os.path.join(m, f"state_{step:07d}.csv"))) for m in members]
        angles, speeds = [x[0] for x in ms], [x[1] for x in ms]
        # distance from LIGGGHTS to the members' range (0 inside it)
        da = max(0.0, min(angles) - la, la - max(angles))
        dv = max(0.0, min(speeds) - ls, ls - max(speeds)) / ls
        rows.append({"t": round(step * DT, 6), "angle_liggghts_deg": la, "angle_min_deg": min(angles),
                     "angle_max_deg": max(angles), "angle_outside_deg": da, "speed_liggghts": ls,
                     "speed_min": min(speeds), "speed_max": max(speeds), "speed_outside_rel": dv,
                     "angle_spread_deg": max(angles) - min(angles),
                     "speed_spread_rel": (max(speeds) - min(speeds)) / ls})
    os.makedirs(docs, exist_ok=True)
    with open(os.path.join(docs, "flow_ensemble.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    late = [r for r in rows if r["t"] >= FROM_T - 1e-9]
    worst_a = max(r["angle_outside_deg"] for r in late)
    worst_v = max(r["speed_outside_rel"] for r in late)
    commit = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    summary = {"commit": commit, "members": [os.path.relpath(m, REPO) for m in members], "from_t": FROM_T,
               "max_angle_outside_deg": worst_a, "angle_tolerance_deg": ANGLE_TOL_DEG,
               "max_speed_outside_rel": worst_v, "speed_tolerance_rel": SPEED_TOL,
               "max_angle_spread_deg": max(r["angle_spread_deg"] for r in late),
               "max_speed_spread_rel": max(r["speed_spread_rel"] for r in late),
               "pass": worst_a <= ANGLE_TOL_DEG and worst_v <= SPEED_TOL}
    with open(os.path.join(docs, "flow_ensemble.json"), "w") as f:
        json.dump(summary, f, indent=1)
    for r in rows:
        print(f"t {r['t']:.1f} s: angle LIGGGHTS {r['angle_liggghts_deg']:6.2f}, grainflow {r['angle_min_deg']:6.2f}.."
              f"{r['angle_max_deg']:6.2f}; mean |v| {r['speed_liggghts']:.4f}, {r['speed_min']:.4f}..{r['speed_max']:.4f}")
    print(f"from {FROM_T} s: LIGGGHTS outside grainflow's range by at most {worst_a:.2f} deg and {100 * worst_v:.1f} %"
          f" (tolerances {ANGLE_TOL_DEG} deg, {100 * SPEED_TOL:.0f} %): {'pass' if summary['pass'] else 'FAIL'}")
    return 0 if summary["pass"] else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("command", choices=["liggghts", "grainflow", "compare", "spread", "ensemble"])
    ap.add_argument("--other", help="spread: folder of the other grainflow run's state_<step>.csv")
    ap.add_argument("--set", dest="sets", action="append", default=[],
                    help="grainflow: a scene override for this member, e.g. run.skin=1.6e-4 (same physics, "
                         "another list and so another summation order)")
    ap.add_argument("--members", nargs="*", default=[],
                    help="ensemble: folders of grainflow runs (each with state_<step>.csv)")
    ap.add_argument("--out", default=os.path.join(REPO, "runs", "flow_ref"))
    ap.add_argument("--docs", default=os.path.join(REPO, "studies", "performance", "results"))
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--binary", default=os.path.join(REPO, "build", "grainflow"))
    a = ap.parse_args()
    if a.command == "liggghts":
        run_liggghts(a.out, a.ranks)
    elif a.command == "grainflow":
        run_grainflow(a.out, a.threads, a.binary, a.sets)
    elif a.command == "ensemble":
        sys.exit(ensemble(a.out, a.members, a.docs))
    elif a.command == "spread":
        if not a.other:
            ap.error("spread needs --other")
        compare(a.out, a.docs, a.other)
        print(open(os.path.join(a.docs, "flow_spread.csv")).read())
    else:
        sys.exit(compare(a.out, a.docs))


if __name__ == "__main__":
    main()

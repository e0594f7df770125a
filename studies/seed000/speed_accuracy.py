#!/usr/bin/python3
"""Speed against accuracy for the seed-000 drum: the half-fill case at 2 rad/s run to the same
rotation angle with the seed's time step (1e-5 s) and 2, 3 and 4 times it, and the smaller drum
(scenes/drum_quick.toml: 2,987 grains of 2 and 6 mm) at the same speed. One chart: segregation
index and pattern at the end against wall time, and the segregation index against rotation for
each run (its distance from the 1e-5 s run is the accuracy cost of the larger step).

    /usr/bin/python3 studies/seed000/speed_accuracy.py [--angle 0.5] [--threads 1] [--out runs/speed_accuracy]

Steps above dt_safety of the smallest collision period are refused by grainflow; they are forced
here with run.allow_unstable_dt so that the chart shows where the case breaks: a run that blows
up stops with exit status 3 and its summary.json says what broke. Results: <out>/speed_accuracy.png,
<out>/speed_accuracy.json.
"""
import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from grainflow.outputs import Run  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
KINDS = {-1: "undecided", 0: "moon", 1: "petals"}
VARIANTS = [
    ("dt 1e-5 (seed)", "scenes/drum_seed000_settled.toml", ["run.dt=1e-5"]),
    ("dt 2e-5", "scenes/drum_seed000_settled.toml", ["run.dt=2e-5", "run.allow_unstable_dt=true"]),
    ("dt 3e-5", "scenes/drum_seed000_settled.toml", ["run.dt=3e-5", "run.allow_unstable_dt=true"]),
    ("dt 4e-5", "scenes/drum_seed000_settled.toml", ["run.dt=4e-5", "run.allow_unstable_dt=true"]),
    ("small drum, dt 3e-5", "scenes/drum_quick.toml", []),
]


def run(label, scene, sets, angle, out, binary, threads):
    folder = out / label.replace(" ", "_").replace(",", "")
    cmd = [str(binary), "run", str(REPO / scene), "--out", str(folder), "--threads", str(threads), "--quiet",
           "--set", "wall.0.omega=2.0", "--set", "output.frame_interval=0",
           "--set", "output.series_interval=0.005", "--set", "output.checkpoint_at_end=false"]
    # The seed scenes give their length as a rotation angle, the small drum as a duration.
    length = f"run.duration={angle / 2.0}" if "drum_quick" in scene else f"run.end_angle={angle}"
    for s in sets + [length]:
        cmd += ["--set", s]
    print(" ".join(cmd), file=sys.stderr)
    p = subprocess.run(cmd, capture_output=True, text=True)
    out = Run(folder)
    summary, data = out.summary, out.series
    last = {name: values[-1] for name, values in data.items()}
    return {
        "label": label, "rc": p.returncode, "status": summary["status"], "failure": summary.get("failure", ""),
        "grains": summary["grains"], "dt": summary["dt"], "critical_fraction": summary["dt"] / summary["critical_period"],
        "wall_seconds": summary["wall_seconds"], "settle_wall_seconds": summary.get("settle", {}).get("wall_seconds", 0),
        "angle": float(last["angle"]), "segregation_index": float(last["segregation_index"]),
        "pattern": KINDS.get(int(last["pattern"]), "?"), "petals": int(last["petals"]),
        "max_overlap_ratio": float(np.max(data["max_overlap_ratio"])),
        "series": {"angle": data["angle"].tolist(), "segregation_index": data["segregation_index"].tolist()},
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--angle", type=float, default=0.5, help="rotation to reach, rad (default 0.5)")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--out", type=Path, default=REPO / "runs" / "speed_accuracy")
    ap.add_argument("--binary", type=Path, default=REPO / "build" / "grainflow")
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    res = [run(l, s, o, a.angle, a.out, a.binary, a.threads) for l, s, o in VARIANTS]
    ref = res[0]
    for r in res:
        if r["label"].startswith("dt") and r["status"] == "completed":
            n = min(len(r["series"]["angle"]), len(ref["series"]["angle"]))
            ra = np.interp(ref["series"]["angle"], r["series"]["angle"], r["series"]["segregation_index"])
            r["rms_vs_seed_dt"] = float(np.sqrt(np.mean((ra - np.array(ref["series"]["segregation_index"])) ** 2)))
            r["points_compared"] = n
    (a.out / "speed_accuracy.json").write_text(json.dumps(res, indent=1))

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4))
    for r in res:
        ok = r["status"] == "completed"
        ax1.scatter(r["wall_seconds"], r["segregation_index"], marker="o" if ok else "x", s=50,
                    color="C0" if r["label"].startswith("dt") else "C1")
        note = f"{r['label']}\n{r['pattern']}" + ("" if ok else f"\nUNSTABLE at {r['angle']:.2f} rad")
        ax1.annotate(note, (r["wall_seconds"], r["segregation_index"]), fontsize=7, xytext=(4, 4),
                     textcoords="offset points")
        ax2.plot(r["series"]["angle"], r["series"]["segregation_index"], lw=1, ls="-" if ok else ":",
                 label=f"{r['label']} ({r['wall_seconds']:.0f} s)" + ("" if ok else " unstable"))
    ax1.set_xscale("log")
    ax1.set_xlabel("wall time of the main stage (s, this machine)")
    ax1.set_ylabel(f"segregation index at {a.angle} rad")
    ax1.set_title("Cost against result, drum at 2 rad/s")
    ax2.set_xlabel("drum rotation (rad)")
    ax2.set_ylabel("segregation index")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(a.out / "speed_accuracy.png", dpi=120)
    for r in res:
        print(f"{r['label']:>22}: {r['status']:>9} dt/T={r['critical_fraction']:.3f} wall {r['wall_seconds']:.1f} s "
              f"angle {r['angle']:.3f} SI {r['segregation_index']:.4f} {r['pattern']} max overlap "
              f"{r['max_overlap_ratio']:.4f} rms {r.get('rms_vs_seed_dt', float('nan')):.4f} {r['failure'][:90]}")


if __name__ == "__main__":
    main()

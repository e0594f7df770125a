#!/usr/bin/env python3
"""Seed 002's packing case: pour each of the six letter shapes (O, T, Z, K, A, C) into a box, let
it settle, and collect the packing (solid volume) fraction per shape.

    /usr/bin/python3 studies/seed002/packing.py [--binary build/grainflow] [--jobs 2]

Runs scenes/packing_seed002_letters.toml once per letter (--set shape.0.letter=...) into
runs/seed002_packing/<letter>/, one thread each, `--jobs` at a time. Resumable: a letter whose run
completed and settled is skipped; one that completed unsettled, or was stopped, continues from its
checkpoint. Settled: the kinetic energy of the moving grains (translational + rotational) stays
below 1e-4 of sum(m g H) (every grain lifted by its own height H = 0.18 m) over the last 0.1 s of
series.csv; an unsettled run is extended by 1 s at a time, up to --max-duration.

Writes studies/seed002/results/packing/packing.json and packing.csv (per letter: the fraction in the bed's
interior, the whole bed's fraction, the interior region, bed depth, grains, simulated time, wall
time, final kinetic energy), profile_<letter>.csv (the run's packing.csv: the fraction per 5 mm
layer), packing_profiles.png (those profiles, smoothed over 0.05 m), and each run's last side view,
cropped to the bed, as <letter>.png. A letter whose run folder is missing (runs/ is not kept between
checkouts) keeps its row, picture and profile from the packing.json already under --docs. The fraction is the grainflow run's own (summary.json "packing":
voxels of 5 mm in the bed's interior, half a letter height inside the walls, above the floor and
below the free surface, and also with margins of a quarter and a whole letter height;
systems/analysis/packing.hpp). The measured order is compared with the seed's:
O highest, then T, Z, K, and A and C lowest.
"""
import argparse
import concurrent.futures
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))


def _outputs():
    """grainflow.outputs, imported where run files are read: it needs numpy, the tables do not."""
    import grainflow.outputs
    return grainflow.outputs


ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENE = os.path.join(ROOT, "scenes", "packing_seed002_letters.toml")
LETTERS = ["O", "T", "Z", "K", "A", "C"]
HEIGHT = 0.180        # m, the letters' H (the scene's shape.height)
SETTLED = 1e-4        # kinetic energy / sum(m g H)
WINDOW = 0.1          # s of series.csv that must stay below it
EXTEND = 1.0          # s added to an unsettled run
SCENE_DURATION = 2.0  # s, the scene's run.duration
# The seed's order, highest first; A and C share the last place.
SEED_ORDER = [["O"], ["T"], ["Z"], ["K"], ["A", "C"]]


# Scene overrides for every letter (--set KEY=VALUE, as grainflow's own), e.g. another friction.
OVERRIDES = []


def letter_set(letter):
    # The committed results' step, 0.129 of the rim contacts' period (the scene now takes 7.5e-5 s, within 0.1).
    sets = ["--set", 'shape.0.letter="%s"' % letter, "--set", "run.dt=1e-4"]
    for o in OVERRIDES:
        sets += ["--set", o]
    return sets


def shape_mass(binary, letter):
    """kg per grain and the grain count, from `grainflow check`."""
    out = subprocess.run([binary, "check", SCENE] + letter_set(letter), capture_output=True, text=True, check=True).stdout
    mass = float(re.search(r"shape letter: .* mass ([0-9.eE+-]+) kg", out).group(1))
    count = int(re.search(r"bodies: (\d+) moving", out).group(1))
    return mass, count


def read_series(path):
    """series.csv as a list of rows, each {column: float} (read by the Python package)."""
    return _outputs().rows_of(_outputs().read_csv(path))


def run_summary(run_dir):
    """A run folder's summary.json as a dict, or None when there is none yet."""
    try:
        return _outputs().Run(run_dir).summary
    except (OSError, ValueError):
        return None


def settled(run_dir, threshold):
    """(settled, final kinetic energy in J, simulated time in s) from series.csv."""
    series = os.path.join(run_dir, "series.csv")
    if not os.path.exists(series):
        return False, float("nan"), 0.0
    rows = read_series(series)
    if not rows:
        return False, float("nan"), 0.0
    end = rows[-1]["time"]
    window = [r for r in rows if r["time"] >= end - WINDOW - 1e-9]
    ke = [r["ke_translational"] + r["ke_rotational"] for r in window]
    return end >= WINDOW and max(ke) < threshold, ke[-1], end


def load_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def run_letter(binary, runs, letter, max_duration, log):
    run_dir = os.path.join(runs, letter)
    mass, count = shape_mass(binary, letter)
    threshold = SETTLED * count * mass * 9.81 * HEIGHT
    ledger_path = os.path.join(run_dir, "wall_seconds.json")
    while True:
        summary = run_summary(run_dir)
        done, ke, t = settled(run_dir, threshold)
        checkpoint = os.path.join(run_dir, "checkpoints", "checkpoint.gfc")
        cmd = [binary, "run", SCENE, "--out", run_dir, "--threads", "1", "--quiet"] + letter_set(letter)
        if summary and summary.get("status") == "completed" and done:
            if "by_margin" in summary.get("packing", {}):
                log("%s: settled at %.2f s (kinetic energy %.3g J < %.3g J)" % (letter, t, ke, threshold))
                return
            # Measured by an earlier build: the same state again, no step, measured by this one.
            cmd += ["--resume", checkpoint, "--steps", "0"]
            log("%s: measuring the packing of the settled state again" % letter)
        elif summary and summary.get("status") == "failed":
            log("%s: the run failed: %s" % (letter, summary.get("failure", "")))
            return
        elif summary and os.path.exists(checkpoint):
            # A completed run is extended; a stopped one continues to the scene's duration.
            duration = t + EXTEND if summary.get("status") == "completed" or t >= SCENE_DURATION - 1e-9 else SCENE_DURATION
            if duration > max_duration + 1e-9:
                log("%s: not settled by %.2f s (kinetic energy %.3g J, criterion %.3g J): left as it is" %
                    (letter, t, ke, threshold))
                return
            cmd += ["--resume", checkpoint, "--set", "run.duration=%g" % duration]
            log("%s: kinetic energy %.3g J at %.2f s (criterion %.3g J): continuing to %g s" % (letter, ke, t, threshold, duration))
        elif summary and summary.get("status") == "completed":
            log("%s: completed without its checkpoint: left as it is" % letter)
            return
        else:
            os.makedirs(run_dir, exist_ok=True)
            log("%s: pouring %d grains" % (letter, count))
        start = time.time()
        # grainflow refuses a fresh run into a folder that holds files: a fresh pour logs beside its folder,
        # and the log joins the folder afterwards.
        fresh = "--resume" not in cmd
        log_path = run_dir.rstrip(os.sep) + ".run.log" if fresh else os.path.join(run_dir, "run.log")
        if fresh and os.path.isdir(run_dir) and not os.listdir(run_dir):
            os.rmdir(run_dir)
        with open(log_path, "a") as f:
            rc = subprocess.run(cmd, stdout=f, stderr=f).returncode
        if fresh:
            os.makedirs(run_dir, exist_ok=True)
            shutil.move(log_path, os.path.join(run_dir, "run.log"))
        ledger = load_json(ledger_path) or []
        ledger.append({"command": " ".join(cmd[1:]), "wall_seconds": time.time() - start, "exit": rc})
        with open(ledger_path, "w") as f:
            json.dump(ledger, f, indent=1)
        if rc != 0:
            log("%s: grainflow exited with %d (see %s)" % (letter, rc, os.path.join(run_dir, "run.log")))
            return


def crop_picture(src, dst):
    """The side view cropped to the bed: the rows from a little above the highest grain to the floor."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import numpy as np
    img = mpimg.imread(src)
    rgb = img[..., :3]
    background = rgb[0, 0]
    rows = np.where(np.any(np.abs(rgb - background).sum(axis=2) > 0.05, axis=1))[0]
    cols = np.where(np.any(np.abs(rgb - background).sum(axis=2) > 0.05, axis=0))[0]
    if len(rows) == 0:
        shutil.copyfile(src, dst)
        return
    # The grains in flight are gone by the end; the highest drawn row is the bed's top.
    pad = max(4, (cols[-1] - cols[0]) // 40)
    top, bottom = max(0, rows[0] - pad), min(img.shape[0], rows[-1] + pad + 1)
    left, right = max(0, cols[0] - pad), min(img.shape[1], cols[-1] + pad + 1)
    mpimg.imsave(dst, img[top:bottom, left:right])


def plot_profiles(docs, rows):
    """packing_profiles.png: the fraction per 5 mm layer against the height above the floor, in the
    interior's columns and across the whole width, smoothed over 0.05 m, per letter."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(rows), figsize=(2.2 * len(rows), 4.2), sharey=True, squeeze=False)
    for ax, r in zip(axes[0], rows):
        with open(os.path.join(docs, "profile_%s.csv" % r["letter"]), newline="") as f:
            prof = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
        h = [p["height"] for p in prof]
        for key, colour, label in (("whole", "#D55E00", "whole width"), ("interior", "#0072B2", "interior columns")):
            v = [p[key] for p in prof]
            k = 5  # layers either side: 0.05 m
            smooth = [sum(v[max(0, i - k):i + k + 1]) / len(v[max(0, i - k):i + k + 1]) for i in range(len(v))]
            ax.plot(smooth, h, color=colour, lw=1.2, label=label)
        lo, hi = r["interior_lo_m"][1], r["interior_hi_m"][1]
        ax.axhspan(lo, hi, color="#999999", alpha=0.2, lw=0, label="interior region")
        ax.axvline(r["packing_fraction"], color="#0072B2", ls=":", lw=1)
        ax.set_title("%s: %.3f" % (r["letter"], r["packing_fraction"]))
        ax.set_xlim(0, 0.6)
        ax.set_xlabel("solid fraction")
    axes[0][0].set_ylabel("height above the floor (m)")
    axes[0][0].legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(os.path.join(docs, "packing_profiles.png"), dpi=110)
    plt.close(fig)


def order_check(fractions):
    """The measured order and how many of the seed's pairwise relations it keeps."""
    rank = {}
    for i, group in enumerate(SEED_ORDER):
        for letter in group:
            rank[letter] = i
    pairs, kept, broken = 0, 0, []
    for a in fractions:
        for b in fractions:
            if rank[a] < rank[b]:
                pairs += 1
                if fractions[a] > fractions[b]:
                    kept += 1
                else:
                    broken.append("%s (%.4f) <= %s (%.4f)" % (a, fractions[a], b, fractions[b]))
    measured = sorted(fractions, key=lambda k: -fractions[k])
    return {
        "seed": "O > T > Z > K > A, C",
        "measured": " > ".join(measured),
        "pairs": pairs,
        "pairs_as_seed": kept,
        "matches": pairs > 0 and kept == pairs,
        "pairs_against_seed": broken,
    }


def collect(runs, docs, binary):
    os.makedirs(docs, exist_ok=True)
    rows = []
    committed = {r["letter"]: r for r in (load_json(os.path.join(docs, "packing.json")) or {}).get("shapes", [])}
    for letter in LETTERS:
        run_dir = os.path.join(runs, letter)
        summary = run_summary(run_dir)
        if not summary or "packing" not in summary:
            # A letter collected before whose run folder this checkout does not hold (runs/ is not
            # kept): its committed row, picture and profile stay.
            if letter in committed and not os.path.isdir(run_dir):
                rows.append(committed[letter])
            continue
        p = summary["packing"]
        if not p.get("valid"):
            continue
        mass, count = shape_mass(binary, letter)
        threshold = SETTLED * count * mass * 9.81 * HEIGHT
        done, ke, t = settled(run_dir, threshold)
        ledger = load_json(os.path.join(run_dir, "wall_seconds.json")) or []
        series = read_series(os.path.join(run_dir, "series.csv"))
        by = {round(m["margin"] / p["grain_length"], 2): m for m in p.get("by_margin", [])}

        def at(k):
            m = by.get(k)
            return round(m["fraction"], 5) if m and m.get("valid") else None
        rows.append({
            "letter": letter,
            "bodies": summary["bodies"]["moving"],
            "packing_fraction": round(p["fraction"], 5),
            "fraction_margin_quarter_H": at(0.25),
            "fraction_margin_H": at(1.0),
            "whole_bed_fraction": round(p["whole_bed_fraction"], 5),
            "bed_depth_m": round(p["bed_depth"], 4),
            "interior_lo_m": [round(v, 4) for v in p["region"]["lo"]],
            "interior_hi_m": [round(v, 4) for v in p["region"]["hi"]],
            "margin_m": p["margin"],
            "voxel_m": p["voxel"],
            "simulated_s": round(t, 4),
            "steps": summary["steps"],
            "kinetic_energy_J": ke,
            "settled_criterion_J": threshold,
            "settled": done,
            "max_overlap_ratio": max(r["max_overlap_ratio"] for r in series),
            "wall_s": round(sum(e["wall_seconds"] for e in ledger), 1),
            "status": summary["status"],
        })
        pictures = os.path.join(run_dir, "pictures")
        if os.path.isdir(pictures):
            pngs = sorted(f for f in os.listdir(pictures) if f.endswith(".png"))
            if pngs:
                crop_picture(os.path.join(pictures, pngs[-1]), os.path.join(docs, "%s.png" % letter))
        shutil.copyfile(os.path.join(run_dir, "packing.csv"), os.path.join(docs, "profile_%s.csv" % letter))
    if rows:
        plot_profiles(docs, rows)
    fractions = {r["letter"]: r["packing_fraction"] for r in rows}
    doc = {
        "scene": "scenes/packing_seed002_letters.toml",
        "what": "packing (solid volume) fraction of letter-shaped composite grains poured into a 1.08 x 1.08 m box, "
                "read on 5 mm voxels in the bed's interior: half a letter height (H / 2 = 0.09 m) inside the side "
                "walls, above the floor and below the free surface (the mean top of the interior's columns); "
                "fraction_margin_quarter_H and fraction_margin_H with margins of H / 4 and H (null where the bed "
                "is shallower than two margins); whole_bed_fraction counts the full width from the floor to the "
                "free surface",
        "overrides": list(OVERRIDES),
        "settled_when": "kinetic energy below 1e-4 of sum(m g H) over the last 0.1 s",
        "wall_s": "wall seconds of a letter's grainflow runs, one thread each, with up to three letters at once on "
                  "a two-core machine shared with other work: what the runs took here, not a benchmark",
        "shapes": rows,
        "ordering": order_check(fractions) if len(fractions) > 1 else None,
        "missing": [L for L in LETTERS if L not in fractions],
    }
    with open(os.path.join(docs, "packing.json"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    keys = ["letter", "bodies", "packing_fraction", "fraction_margin_quarter_H", "fraction_margin_H", "whole_bed_fraction", "bed_depth_m", "simulated_s", "steps",
            "kinetic_energy_J", "settled_criterion_J", "settled", "max_overlap_ratio", "wall_s", "status"]
    with open(os.path.join(docs, "packing.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(keys)
        for r in rows:
            w.writerow([r[k] for k in keys])
    return doc


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "grainflow"))
    ap.add_argument("--runs", default=os.path.join(ROOT, "runs", "seed002_packing"))
    ap.add_argument("--docs", default=os.path.join(ROOT, "studies", "seed002", "results", "packing"))
    ap.add_argument("--jobs", type=int, default=2, help="letters run at once, one thread each")
    ap.add_argument("--letters", default="".join(LETTERS))
    ap.add_argument("--max-duration", type=float, default=6.0, help="s: an unsettled run stops being extended here")
    ap.add_argument("--collect-only", action="store_true")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a scene override for every letter (repeatable), e.g. contact.friction=0.1; "
                         "give such a variant its own --runs and --docs")
    a = ap.parse_args()
    OVERRIDES.extend(a.set)
    letters = [c for c in a.letters if c in LETTERS]

    def log(msg):
        print("%s %s" % (time.strftime("%H:%M:%S"), msg), flush=True)

    if not a.collect_only:
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
            for f in [pool.submit(run_letter, a.binary, a.runs, L, a.max_duration, log) for L in letters]:
                f.result()
    doc = collect(a.runs, a.docs, a.binary)
    for r in doc["shapes"]:
        print("%s: %d grains, packing fraction %.4f (whole bed %.4f), bed %.3f m deep, %.2f s simulated, %s, %.0f s wall"
              % (r["letter"], r["bodies"], r["packing_fraction"], r["whole_bed_fraction"], r["bed_depth_m"],
                 r["simulated_s"], "settled" if r["settled"] else "NOT settled", r["wall_s"]))
    if doc["ordering"]:
        o = doc["ordering"]
        print("order: %s; the seed's %s: %d of %d pairs as the seed%s" % (o["measured"], o["seed"], o["pairs_as_seed"],
              o["pairs"], "" if o["matches"] else "; against it: " + ", ".join(o["pairs_against_seed"])))
    if doc["missing"]:
        print("missing: %s" % " ".join(doc["missing"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""A cost model of grainflow_mpi at scale: time per step on P ranks for 1e8 grains (strong scaling)
and for 1e5 grains per rank (weak scaling), from counts measured here and rates committed under studies/*/results/.

    /usr/bin/python3 studies/mpi/cost_model.py measure   # runs grainflow_mpi, writes studies/mpi/results/cost_inputs.json
    /usr/bin/python3 studies/mpi/cost_model.py model     # writes studies/mpi/results/cost_model.json and studies/mpi/results/cost_model.png
    /usr/bin/python3 studies/mpi/cost_model.py table     # prints the markdown table from studies/mpi/results/cost_model.json

`measure` copies build/grainflow_mpi to a temporary folder and runs the copy (2 and 3 ranks, and 1 rank
for the rebuild count) on scenes/drum_seed000_flowing.toml and scenes/drum_quick.toml. From each run it
keeps counts (ghost rows, rebuilds, migrated rows, grains), not wall times: the machine has 2 cores
shared with other work, so its wall times say little. It reads every rank's grains from the last VTK
frame pieces, recovers the ranks' boxes from them, recounts the ghost rows of the half shell and
compares both with the surface formula ghosts = area x shell thickness x number density.
Rates (particle-steps/s on one thread) are read from the committed logs under studies/performance/results and studies/performance/results.

Per step and per rank, with n = N/P grains on a rank (one rank per core, one thread per rank):
  compute      n / R(n) + ghosts * f_bp / R(n)
  ghosts       half shell of a box of n grains, thickness h = largest diameter + skin + law reach
  exchanges    2 per step (ghost refresh: position, velocity, spin = 72 B a row; fold: force, torque =
               48 B a row) and 3 per rebuild (springs, migration, ghost rows of 212 B), rebuild every K steps
  collectives  2 allreduce of 8 B per step (stop check, rebuild decision) + 2 per rebuild (rebalance check),
               + 1 per rebuild with neighbour-only exchanges (whether anything must go past the near boxes)
  cover check  at each step where some grain is past half the skin (C per step, measured): 3 allreduce of
               8 B and one exchange of the movers (a few 40 B records) with the boxes within two reaches
Hockney model, latency alpha and bandwidth beta per link:
  allreduce (8 B)             2 log2(P) alpha
  exchange, all-to-all        MPI_Alltoall of counts + MPI_Alltoallv: 2 (P-1) alpha + V / beta (pairwise
                              exchange); MpiContext::exchange without peers (every exchange up to commit d3c42dd)
  exchange, neighbour-only    sizes then payloads to each of k = min(P-1, 26) neighbouring boxes:
                              2 k alpha + V / beta; MpiContext::exchange with peers (from commit 7a02920)
"""
import datetime
import glob
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grainflow.vtp import read_vtp  # noqa: E402
INPUTS = os.path.join(ROOT, "studies/mpi/results/cost_inputs.json")
MODEL = os.path.join(ROOT, "studies/mpi/results/cost_model.json")
FIGURE = os.path.join(ROOT, "studies/mpi/results/cost_model.png")

# (scene, ranks, steps): the flowing seed-000 drum (47,108 grains of 1 and 3 mm, from a file, no settling)
# and the quick drum (2,987 grains of 2 and 6 mm, poured and settled first).
RUNS = [
    ("scenes/drum_seed000_flowing.toml", 1, 1000),
    ("scenes/drum_seed000_flowing.toml", 2, 1000),
    ("scenes/drum_seed000_flowing.toml", 3, 1000),
    ("scenes/drum_quick.toml", 2, 1000),
    ("scenes/drum_quick.toml", 3, 1000),
]

SI = {"": 1.0, "k": 1e3, "M": 1e6, "G": 1e9, "m": 1e-3, "u": 1e-6, "n": 1e-9}


# ----------------------------------------------------------------------------------------------------
# measure


def load_average():
    with open("/proc/loadavg") as f:
        return [float(x) for x in f.read().split()[:3]]


def cpu_description():
    info = {}
    with open("/proc/cpuinfo") as f:
        for line in f:
            if ":" not in line:
                continue
            k, v = (s.strip() for s in line.split(":", 1))
            if k in ("model name", "cpu family", "model", "cache size") and k not in info:
                info[k] = v
            if k == "flags" and "flags" not in info:
                info["avx512f"] = "avx512f" in v.split()
                info["flags"] = True
    info.pop("flags", None)
    info["cores"] = os.cpu_count()
    return info


def last_frame_pieces(out, ranks):
    frames = sorted(glob.glob(os.path.join(out, "frames", "frame_*_rank0000.vtp")))
    last = frames[-1][: -len("_rank0000.vtp")]
    return [read_vtp("%s_rank%04d.vtp" % (last, r)) for r in range(ranks)], os.path.basename(last)


def infer_boxes(points):
    """Each rank's box from its grains: for every pair of ranks the axis and plane that separate their
    grains best (the cut at their common node of the bisection tree); a box is the intersection of
    its half-spaces. Grains drift up to a skin past a cut between rebuilds: the planes carry that
    error."""
    p = len(points)
    lo = [[-math.inf] * 3 for _ in range(p)]
    hi = [[math.inf] * 3 for _ in range(p)]
    cuts = []
    ext = [[(min(q[a] for q in pts), max(q[a] for q in pts)) for a in range(3)] for pts in points]
    for q in range(p):
        for r in range(q + 1, p):
            best = None
            for a in range(3):
                g_up = ext[r][a][0] - ext[q][a][1]  # r above q
                g_dn = ext[q][a][0] - ext[r][a][1]  # r below q
                for gap, r_above in ((g_up, True), (g_dn, False)):
                    if best is None or gap > best[0]:
                        best = (gap, a, r_above)
            gap, a, r_above = best
            if r_above:
                c = 0.5 * (ext[r][a][0] + ext[q][a][1])
                lo[r][a] = max(lo[r][a], c)
                hi[q][a] = min(hi[q][a], c)
            else:
                c = 0.5 * (ext[q][a][0] + ext[r][a][1])
                hi[r][a] = min(hi[r][a], c)
                lo[q][a] = max(lo[q][a], c)
            cuts.append({"lower_rank": q, "higher_rank": r, "axis": "xyz"[a], "at_m": c, "gap_m": gap})
    return lo, hi, cuts


def box_distance(lo, hi, x):
    s = 0.0
    for a in range(3):
        g = max(lo[a] - x[a], 0.0, x[a] - hi[a])
        s += g * g
    return math.sqrt(s)


def occupied_length(values, cell):
    return len({math.floor(v / cell) for v in values}) * cell


def geometry_check(points, diam, reach, axial, length, dmin):
    """Ghost rows recounted from the grains (half shell), and predicted by area x thickness x density."""
    p = len(points)
    lo, hi, cuts = infer_boxes(points)
    recount = 0
    for r in range(p):
        for q in range(r):
            recount += sum(1 for x in points[q] if box_distance(lo[r], hi[r], x) <= reach)
    allp = [x for pts in points for x in pts]
    inplane = [a for a in range(3) if a != axial]
    # Number density of the bed: grains over the interior cells of a 2-D grid across the drum axis
    # (cells of the largest diameter whose 8 neighbours hold grains too) times the drum length.
    cell = max(diam)
    grid = {}
    for x in allp:
        key = (math.floor(x[inplane[0]] / cell), math.floor(x[inplane[1]] / cell))
        grid[key] = grid.get(key, 0) + 1
    interior = [k for k in grid if all((k[0] + i, k[1] + j) in grid for i in (-1, 0, 1) for j in (-1, 0, 1))]
    density = sum(grid[k] for k in interior) / (len(interior) * cell * cell * length)
    faces = []
    predicted = 0.0
    for c in cuts:
        a = "xyz".index(c["axis"])
        q, r = c["lower_rank"], c["higher_rank"]
        if a == axial:
            continue
        other = [b for b in inplane if b != a][0]
        # the face: the part of the plane both boxes share, across the drum axis
        flo = max(lo[q][other], lo[r][other])
        fhi = min(hi[q][other], hi[r][other])
        if flo >= fhi:
            continue
        slab = [x[other] for x in allp if abs(x[a] - c["at_m"]) <= reach and flo <= x[other] < fhi]
        width = occupied_length(slab, dmin)
        area = width * length
        g = area * reach * density
        predicted += g
        faces.append({**c, "bed_width_m": width, "area_m2": area, "predicted_ghosts": g})
    return {
        "boxes": [{"rank": r, "lo": lo[r], "hi": hi[r], "grains": len(points[r])} for r in range(p)],
        "faces": faces,
        "number_density_per_m3": density,
        "interior_cells": len(interior),
        "ghosts_recounted_from_frame": recount,
        "ghosts_predicted_surface_formula": predicted,
    }


def scene_geometry(scene_path):
    doc = tomllib.load(open(scene_path, "rb"))
    diam = [s["diameter"] for s in doc["species"]]
    skin = doc["run"]["skin"]
    drum = [w for w in doc["wall"] if w["type"] == "drum"][0]
    axial = max(range(3), key=lambda a: abs(drum["axis"][a]))
    # linear_spring_dashpot reaches no farther than touching: the law's reach is 0
    return {"diameters_m": diam, "skin_m": skin, "law_reach_m": 0.0, "shell_m": max(diam) + skin,
            "drum_axis": "xyz"[axial], "drum_length_m": drum["length"], "drum_radius_m": drum["radius"]}, axial


def exchange_kind(binary):
    """Which exchanges a grainflow_mpi binary makes: the point-to-point one with peers carries its
    error text "which is not a peer"."""
    data = open(binary, "rb").read()
    if b"which is not a peer" in data:
        return "neighbour_only: ghost refresh and fold point to point with the boxes within reach (MpiContext::exchange with peers)"
    return "all_to_all: MPI_Alltoall of counts + MPI_Alltoallv among all ranks (MpiContext::exchange)"


def run_one(binary, scene, ranks, steps, work):
    out = os.path.join(work, "%s_p%d" % (os.path.splitext(os.path.basename(scene))[0], ranks))
    cmd = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks), binary, "run", scene, "--out",
           out, "--steps", str(steps), "--threads", "1"]
    load = load_average()
    log = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=300)
    if log.returncode != 0:
        raise SystemExit("failed: %s\n%s" % (" ".join(cmd), log.stderr))
    s = json.load(open(os.path.join(out, "summary.json")))
    keep = ["ranks", "grains", "grains_at_end", "steps_this_run", "neighbour_rebuilds", "settle_steps",
            "settle_neighbour_rebuilds", "neighbour_lists_kept", "rows_migrated", "rebalances", "rebalance_ratio", "ghost_rows_at_end",
            "rank0_grains_at_end", "wall_seconds", "particle_steps_per_second"]
    rec = {"command": " ".join(cmd).replace(binary, "/tmp/.../grainflow_mpi").replace(out, "OUT"),
           "load_before": load, "summary": {k: s.get(k) for k in keep}}
    rec["steps_per_rebuild"] = s["steps_this_run"] / max(s["neighbour_rebuilds"], 1)
    # every rebuild after the first list follows a cover check that failed
    rec["cover_checks_per_step"] = (s.get("neighbour_lists_kept", 0) + s["neighbour_rebuilds"]) / s["steps_this_run"]
    geo, axial = scene_geometry(os.path.join(ROOT, scene))
    rec["scene_geometry"] = geo
    if ranks > 1:
        pieces, frame = last_frame_pieces(out, ranks)
        points = [pc["Points"] for pc in pieces]
        rec["frame"] = frame
        rec["grains_per_rank_in_frame"] = [len(x) for x in points]
        chk = geometry_check(points, geo["diameters_m"], geo["shell_m"], axial, geo["drum_length_m"],
                             min(geo["diameters_m"]))
        m = s["ghost_rows_at_end"]
        chk["ghosts_measured"] = m
        chk["recount_error"] = chk["ghosts_recounted_from_frame"] / m - 1.0
        chk["surface_formula_error"] = chk["ghosts_predicted_surface_formula"] / m - 1.0
        chk["shell_m_from_measured_ghosts"] = (geo["shell_m"] * m / chk["ghosts_predicted_surface_formula"]
                                               if chk["ghosts_predicted_surface_formula"] > 0 else None)
        rec["ghost_check"] = chk
    return rec


def parse_bench_log(path):
    """{grains: {threads: particle-steps/s}} from a bench_scaling log (Google Benchmark counters)."""
    line_re = re.compile(r"threads:(\d+)/real_time_median.*grains=([0-9.]+)([kM]?) particle_steps/s=([0-9.]+)([kMG]?)/s")
    rows = {}
    for line in open(path):
        m = line_re.search(line)
        if m:
            g = round(float(m.group(2)) * SI[m.group(3)])
            rows.setdefault(g, {})[int(m.group(1))] = float(m.group(4)) * SI[m.group(5)]
    head = open(path).readline().strip()
    return rows, head


def parse_comparison_medians(path):
    med = {}
    in_med = False
    for line in open(path):
        if line.startswith("medians"):
            in_med = True
            continue
        if in_med:
            f = line.split()
            if len(f) == 5 and f[0] in ("grainflow", "liggghts"):
                med["%s_%s" % (f[0], f[1])] = {"runs": int(f[2]), "wall_s": float(f[3]),
                                               "particle_steps_per_s": float(f[4])}
            elif med and not line.strip():
                break
    rebuilds = {}
    for line in open(path):
        f = line.split()
        if len(f) == 9 and f[0] in ("grainflow", "liggghts") and f[1] in ("1", "2"):
            rebuilds.setdefault(f[0], set()).add(int(f[8]))
    steps = int(re.search(r"(\d+) steps per run", open(path).read()).group(1))
    return med, {k: sorted(v) for k, v in rebuilds.items()}, steps


def committed_inputs():
    knee, knee_head = parse_bench_log(os.path.join(ROOT, "studies/performance/results/scaling_knee.log"))
    scal, scal_head = parse_bench_log(os.path.join(ROOT, "studies/performance/results/scaling.log"))
    med, rebuilds, steps = parse_comparison_medians(os.path.join(ROOT, "studies/performance/results/comparison_flowing.log"))
    split = json.load(open(os.path.join(ROOT, "studies/performance/results/drum_time_split_flowing.json")))
    frac = {t["system"]: t["fraction"] for t in split["time_per_system"]}
    membw = json.load(open(os.path.join(ROOT, "studies/performance/results/memory_bandwidth.json")))
    return {
        "settled_layer_one_thread": {
            "file": "studies/performance/results/scaling_knee.log", "header": knee_head,
            "what": "bench end_to_end/settled_layer, 1 thread, median of 3, particle-steps/s against grains",
            "rates": {str(g): r[1] for g, r in sorted(knee.items())}},
        "settled_layer_threads": {
            "file": "studies/performance/results/scaling.log", "header": scal_head,
            "what": "the same bench at 1 and 2 threads",
            "rates": {str(g): {str(t): v for t, v in r.items()} for g, r in sorted(scal.items())}},
        "flowing_drum": {
            "file": "studies/performance/results/comparison_flowing.log",
            "what": "scenes/drum_seed000_flowing.toml, 47,108 grains, %d steps, medians of 5 runs" % steps,
            "grains": 47108, "steps": steps,
            "grainflow_1_thread_particle_steps_per_s": med["grainflow_1"]["particle_steps_per_s"],
            "grainflow_2_threads_particle_steps_per_s": med["grainflow_2"]["particle_steps_per_s"],
            "liggghts_1_rank_particle_steps_per_s": med["liggghts_1"]["particle_steps_per_s"],
            "liggghts_2_ranks_particle_steps_per_s": med["liggghts_2"]["particle_steps_per_s"],
            "grainflow_rebuilds_per_run": rebuilds.get("grainflow"),
            "liggghts_rebuilds_per_run": rebuilds.get("liggghts")},
        "flowing_drum_time_split": {
            "file": "studies/performance/results/drum_time_split_flowing.json",
            "grains": split["grains"], "steps": split["steps"], "neighbor_rebuilds": split["neighbor_rebuilds"],
            "neighbor_list_kept": split.get("neighbor_list_kept"), "contacts_at_end": split["final"]["contacts"],
            "fractions": frac},
        "memory_bandwidth": {"file": "studies/performance/results/memory_bandwidth.json",
                             "dram_GBps_read_plus_written": membw["dram_256MB_GBps"]},
        "rebuild_count_quoted_elsewhere": {
            "value": "3,879 rebuilds over 150,000 steps of the flowing seed-000 drum",
            "found_in_committed_files": False,
            "note": "not found in any committed file; the committed counts above and the runs here are used"},
    }


def measure():
    src = os.path.join(ROOT, "build/grainflow_mpi")
    work = tempfile.mkdtemp(prefix="cost_model_")
    binary = os.path.join(work, "grainflow_mpi")
    shutil.copy2(src, binary)
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    started = datetime.datetime.now(datetime.timezone.utc)
    inputs = {
        "date": started.strftime("%Y-%m-%dT%H:%M:%SZ"),
        "load_average_at_start": load_average(),
        "cpu": cpu_description(),
        "repo_head": head,
        "binary": {"copied_from": "build/grainflow_mpi",
                   "built": datetime.datetime.fromtimestamp(os.path.getmtime(src), datetime.timezone.utc)
                   .strftime("%Y-%m-%dT%H:%M:%SZ"),
                   "exchanges": exchange_kind(binary)},
        "note": ("counts (ghost rows, rebuilds, migrated rows) come from these runs; wall times and rates in "
                 "them are not used: the machine's 2 cores were shared with other work (see the load "
                 "averages). One-thread rates come from the committed files under 'committed'."),
        "runs": [],
    }
    for scene, ranks, steps in RUNS:
        print("running %s on %d ranks, %d steps" % (scene, ranks, steps), file=sys.stderr)
        inputs["runs"].append(run_one(binary, scene, ranks, steps, work))
    inputs["load_average_at_end"] = load_average()
    inputs["committed"] = committed_inputs()
    inputs["code_counts"] = code_counts()
    os.makedirs(os.path.dirname(INPUTS), exist_ok=True)
    with open(INPUTS, "w") as f:
        json.dump(inputs, f, indent=1)
        f.write("\n")
    shutil.rmtree(work, ignore_errors=True)
    print("wrote %s" % os.path.relpath(INPUTS, ROOT))


def code_counts():
    """What one step and one rebuild send, read from the code (app/mpi_main.cpp,
    systems/setup/mpi/rank_simulation.cpp, domain_ghosts.cpp, migration.cpp, row_bytes.cpp)."""
    return {
        "per_step": {
            "allreduce_8_bytes": 2,
            "allreduce_where": ["run_main_stage: mpi.max(stop requested)",
                                "RankSimulation::step_once: mpi_->max(needs rebuild)"],
            "exchanges": 2,
            "exchange_where": ["refresh_domain_ghosts: position, velocity, spin of each ghost row",
                               "fold_domain_ghost_forces: force and torque of each ghost row back to its owner"],
            "refresh_bytes_per_ghost_row": 9 * 8,
            "fold_bytes_per_ghost_row": 6 * 8,
        },
        "per_rebuild": {
            "allreduce_8_bytes": {"all_to_all": 2, "neighbour_only": 3},
            "allreduce_where": ["maybe_rebalance: mpi_->max and mpi_->sum of owned rows (rebalance on, 1.25)",
                                "relist (from commit 7a02920): mpi.max of whether a row or spring goes past the "
                                "boxes within two reaches (then that rebuild exchanges among all ranks)"],
            "exchanges": 3,
            "exchange_where": ["relist: springs to the rank that evaluates their pair next",
                               "migrate_rows: rows that left a box, whole (every column, wall springs too)",
                               "make_domain_ghosts: the ghost rows, core columns"],
            "ghost_row_bytes_core_columns": 7 * 24 + 8 + 24 + 4 + 8,
            "ghost_row_bytes_note": ("pos, vel, omega, force, torque, wall force, wall torque (7 x 3 doubles), "
                                     "radius, mass/inv_mass/inv_inertia, type (int32), id (int64)"),
            "spring_record_bytes": 2 * 8 + 6 * 8,
        },
        "per_cover_check": {
            "allreduce_8_bytes": 3,
            "allreduce_where": ["rank_list_covers: mpi.max of the largest displacement",
                                "rank_list_covers: mpi.sum of the movers' excess over an eighth of the rows",
                                "rank_list_covers: mpi.max of the verdict"],
            "exchanges": 1,
            "exchange_where": ["rank_list_covers: the movers (position, radius, id) to the boxes within two "
                               "reaches"],
            "mover_record_bytes": 5 * 8,
        },
        "exchange_implementation": {
            "up_to_commit_d3c42dd": ("MpiContext::exchange: MPI_Alltoall of one int per rank (the byte counts), "
                                     "then MPI_Alltoallv: every rank takes part in every exchange, empty "
                                     "messages included"),
            "from_commit_7a02920": ("MpiContext::exchange with peers: MPI_Isend/MPI_Irecv of the message size "
                                    "(8 B), MPI_Waitall, then of the payload, MPI_Waitall, with the ranks whose "
                                    "boxes lie within one reach (ghost rows, refresh, fold) or two reaches "
                                    "(rows and springs at a rebuild; among all ranks when the boxes were cut "
                                    "again or something goes farther)")},
    }


# ----------------------------------------------------------------------------------------------------
# model

ALPHA = 1.5e-6      # s, MPI latency per message (InfiniBand HDR class)
BETA = 12.5e9       # B/s per link (200 Gb/s HDR)
NEIGHBOURS_3D = 26
N_STRONG = 1e8
N_WEAK = 1e5
RANKS = sorted({1, 2, 4, 8, 16, 27, 32, 64, 125, 128, 216, 256, 343, 512, 729, 1000} |
               {int(round(10 ** (k / 20))) for k in range(0, 61)})


def interp_log(table, n):
    xs = sorted(table)
    if n <= xs[0]:
        return table[xs[0]]
    if n >= xs[-1]:
        return table[xs[-1]]
    for a, b in zip(xs, xs[1:]):
        if a <= n <= b:
            t = (math.log(n) - math.log(a)) / (math.log(b) - math.log(a))
            return table[a] * (1 - t) + table[b] * t


def allreduce(p):
    return 2.0 * math.log2(p) * ALPHA if p > 1 else 0.0


def exchange(p, volume, variant):
    """Time of one exchange carrying `volume` bytes out of a rank (and as many in)."""
    if p == 1:
        return 0.0
    if variant == "all_to_all":
        return 2.0 * (p - 1) * ALPHA + volume / BETA
    return 2.0 * min(p - 1, NEIGHBOURS_3D) * ALPHA + volume / BETA


def step_cost(n, p, k, inp, variant, threads_speedup=1.0):
    """Per-step seconds on the slowest (an interior) rank with n grains."""
    rate = inp["rate"](n) * threads_speedup
    rho, h = inp["density"], inp["shell"]
    # The whole domain is a cube of N grains, cut by recursive bisection into P boxes of n grains, taken
    # as cubes of side a (bisection keeps them near cubes for any P); m = P^(1/3) boxes along each axis,
    # so a fraction f = 1 - 1/m of a box's faces lies inside the domain (the rest on its boundary).
    a = (n / rho) ** (1.0 / 3.0)
    m = p ** (1.0 / 3.0)
    f = 1.0 - 1.0 / m
    # half shell of thickness h around the box (ghosts from lower-numbered ranks only), inner faces only
    ghosts = 0.5 * rho * ((a + 2 * h * f) ** 3 - a ** 3)
    compute = n / rate + ghosts * inp["f_bp"] / rate
    refresh = ghosts * inp["refresh_B"]
    fold = ghosts * inp["fold_B"]
    pack = 2.0 * (refresh + fold) / inp["mem_Bps"]  # gather and scatter: read and written once each
    per_step_comm = exchange(p, refresh, variant) + exchange(p, fold, variant) + pack
    springs = ghosts * inp["contacts_per_grain"] * inp["spring_B"]
    migrated = inp["migrated_per_rebuild_per_surface_grain"] * ghosts
    rebuild_comm = (exchange(p, springs, variant) + exchange(p, migrated * inp["full_row_B"], variant)
                    + exchange(p, ghosts * inp["ghost_row_B"], variant))
    # the cover check's exchange carries a few movers: latency only
    cover_comm = inp["cover_checks_per_step"] * exchange(p, 0.0, variant)
    ghost_comm = per_step_comm + rebuild_comm / k + cover_comm
    per_rebuild = inp["rebuild_allreduce"][variant]
    collectives = (2 * allreduce(p) + per_rebuild * allreduce(p) / k
                   + inp["cover_checks_per_step"] * inp["cover_allreduce"] * allreduce(p))
    total = compute + ghost_comm + collectives
    serial = n / rate  # the same grains on one rank: no ghosts, no messages
    return {"ranks": p, "grains_per_rank": n, "boxes_per_axis": m, "box_side_m": a, "ghosts_per_rank": ghosts,
            "ghosts_per_grain": ghosts / n, "rate_one_thread": rate,
            "compute_ms": 1e3 * compute, "ghost_comm_ms": 1e3 * ghost_comm, "collectives_ms": 1e3 * collectives,
            "total_ms": 1e3 * total, "particle_steps_per_s": n * p / total,
            "communication_share": (ghost_comm + collectives) / total,
            "parallel_efficiency": serial / total}


def model():
    inp = json.load(open(INPUTS))
    com = inp["committed"]
    knee = {int(g): r for g, r in com["settled_layer_one_thread"]["rates"].items()}
    flow = com["flowing_drum"]
    ratio = flow["grainflow_1_thread_particle_steps_per_s"] / interp_log(knee, flow["grains"])
    flowing = [r for r in inp["runs"] if "seed000_flowing" in r["command"]]
    checks = [r for r in inp["runs"] if "ghost_check" in r]
    big = [r for r in flowing if r["summary"]["ranks"] > 1]
    one = [r for r in flowing if r["summary"]["ranks"] == 1][0]
    geo = big[0]["scene_geometry"]
    density = sum(r["ghost_check"]["number_density_per_m3"] for r in big) / len(big)
    k_mpi = sum(r["summary"]["steps_this_run"] for r in big) / sum(r["summary"]["neighbour_rebuilds"] for r in big)
    cover_checks = sum(r.get("cover_checks_per_step", 0.0) for r in big) / len(big)
    migrated = sum(r["summary"]["rows_migrated"] / max(r["summary"]["neighbour_rebuilds"], 1) /
                   r["summary"]["ghost_rows_at_end"] for r in big) / len(big)
    split = com["flowing_drum_time_split"]
    cc = inp["code_counts"]
    terms = {
        "rate": lambda n: ratio * interp_log(knee, n),
        "density": density,
        "shell": geo["shell_m"],
        "f_bp": split["fractions"]["broadphase"],
        "refresh_B": cc["per_step"]["refresh_bytes_per_ghost_row"],
        "fold_B": cc["per_step"]["fold_bytes_per_ghost_row"],
        "ghost_row_B": cc["per_rebuild"]["ghost_row_bytes_core_columns"],
        "spring_B": cc["per_rebuild"]["spring_record_bytes"],
        "full_row_B": 875.0,
        "contacts_per_grain": split["contacts_at_end"] / split["grains"],
        "migrated_per_rebuild_per_surface_grain": migrated,
        "mem_Bps": 1e9 * com["memory_bandwidth"]["dram_GBps_read_plus_written"],
        "rebuild_allreduce": cc["per_rebuild"]["allreduce_8_bytes"],
        "cover_checks_per_step": cover_checks,
        "cover_allreduce": cc.get("per_cover_check", {}).get("allreduce_8_bytes", 0),
    }
    scal = com["settled_layer_threads"]["rates"]
    thread_speedup = {g: v["2"] / v["1"] for g, v in scal.items()}
    out = {
        "generated_from": "studies/mpi/results/cost_inputs.json (measured %s, repo %s)" % (inp["date"], inp["repo_head"]),
        "assumptions": {
            "machine_per_core": ("one core of this machine (%s, cpu family %s model %s, AVX-512: Zen 4), one rank "
                                 "per core, one thread per rank" % (inp["cpu"].get("model name"),
                                                                     inp["cpu"].get("cpu family"),
                                                                     inp["cpu"].get("model"))),
            "latency_s": ALPHA, "bandwidth_Bps": BETA,
            "interconnect": "InfiniBand HDR class: 1.5 us MPI latency, 12.5 GB/s (200 Gb/s) per link",
            "allreduce_8B": "2 log2(P) alpha (reduce then broadcast over a binomial tree; Rabenseifner's "
                            "reduce-scatter + allgather also costs 2 log2(P) alpha)",
            "which_code": ("all_to_all is MpiContext::exchange up to commit d3c42dd (every rank in every "
                           "exchange); neighbour_only is the modelled target, which commit 7a02920 builds: "
                           "ghost refresh and fold point to point with the boxes within reach"),
            "exchange_all_to_all": ("MPI_Alltoall of counts + MPI_Alltoallv, each a pairwise exchange of P-1 "
                                    "rounds: 2 (P-1) alpha + V/beta (Hockney model; pairwise-exchange cost as in "
                                    "Thakur, Rabenseifner and Gropp, Int. J. High Perform. Comput. Appl. 19(1), "
                                    "2005). An MPI that posts all messages at once pays a per-message overhead "
                                    "below alpha; the term is then smaller but still grows with P"),
            "exchange_neighbour_only": ("sizes, then payloads, with each of k = min(P-1, 26) neighbouring boxes: "
                                        "2 k alpha + V/beta (the messages counted one after another; posted "
                                        "at once, as the code does, they overlap and cost less)"),
            "compute": ("n / R(n) with R the one-thread particle-steps/s of bench settled_layer "
                        "(studies/performance/results/scaling_knee.log) interpolated in log(n), times %.3f, the ratio of the "
                        "flowing seed-000 drum's 1-thread median (%.4g at 47,108 grains, "
                        "studies/performance/results/comparison_flowing.log) to the settled layer's rate at 47,108 "
                        "grains; R held at its 10,011-grain value below and its 1,000,140-grain value above"
                        % (ratio, flow["grainflow_1_thread_particle_steps_per_s"])),
            "ghost_compute": ("each ghost row costs the broadphase's share of a grain's step (%.3f, "
                              "studies/performance/results/drum_time_split_flowing.json); pairs across a cut are evaluated once "
                              "and an interior rank evaluates the pairs of 3 of its 6 faces, so pair work is "
                              "not added" % terms["f_bp"]),
            "geometry": ("the domain is a cube of N grains at the number density measured in the flowing drum "
                         "(%.4g per m^3, 1 and 3 mm glass, half of the volume each); a rank's box is its share "
                         "a cube of n grains, P^(1/3) of them along each axis of the cubic domain; ghosts = half "
                         "the shell of thickness h = %.4g m (largest diameter + skin + law reach 0) around the "
                         "box, times the fraction 1 - P^(-1/3) of faces inside the domain (average rank; with "
                         "the half shell a given rank may hold up to twice that)"
                         % (density, geo["shell_m"])),
            "rebuild_interval_steps": k_mpi,
            "rebuild_interval_source": ("grainflow_mpi on 2 and 3 ranks, flowing seed-000 drum (cost_inputs.json), "
                                        "keeping lists past half the skin while they cover the contacts, as "
                                        "one-rank grainflow does (%d rebuilds in %d steps, "
                                        "studies/performance/results/drum_time_split_flowing.json)"
                                        % (split["neighbor_rebuilds"], split["steps"])),
            "cover_checks_per_step": cover_checks,
            "cover_checks_source": ("the same runs: steps where some grain was past half the skin (lists kept "
                                    "+ rebuilds) over steps"),
            "load_balance": ("equal cost per rank; the program recuts the boxes when the costliest rank's "
                             "grains cost more than 1.25 times the mean (a grain: 1 plus 0.46 a neighbour pair, "
                             "systems/decomposition/row_cost.hpp), so compute can be up to 25% above the model "
                             "between recuts"),
            "not_modelled": ["output (series rows, frames, checkpoints)", "the all-positions gather of a recut",
                             "network contention and rank placement", "threads beyond one per rank"],
            "thread_speedup_2_threads_committed": thread_speedup,
            "terms_used": {k: v for k, v in terms.items() if k != "rate"},
        },
        "curves": {},
    }
    for variant in ("all_to_all", "neighbour_only"):
        strong, weak = [], []
        for p in RANKS:
            strong.append(step_cost(N_STRONG / p, p, k_mpi, terms, variant))
            weak.append(step_cost(N_WEAK, p, k_mpi, terms, variant))
        t1 = N_STRONG / terms["rate"](N_STRONG)
        for s in strong:
            s["speedup_over_one_rank"] = t1 / (s["total_ms"] * 1e-3)
        out["curves"][variant] = {"strong_1e8": strong, "weak_1e5_per_rank": weak}
    key = {}
    for variant in ("all_to_all", "neighbour_only"):
        s = [x for x in out["curves"][variant]["strong_1e8"] if x["ranks"] == 1000][0]
        key[variant] = {k: s[k] for k in ("grains_per_rank", "ghosts_per_rank", "compute_ms", "ghost_comm_ms",
                                          "collectives_ms", "total_ms", "particle_steps_per_s",
                                          "parallel_efficiency", "speedup_over_one_rank")}
    out["prediction_1e8_grains_1000_ranks"] = key
    # 1,000 cores as 500 ranks of 2 threads: the 2-thread speed-up of studies/performance/results/scaling.log at the
    # rank's grain count (interpolated in log n, at most 2)
    s2 = {int(g): v for g, v in thread_speedup.items()}
    hybrid = {}
    for variant in ("all_to_all", "neighbour_only"):
        sp = min(2.0, interp_log(s2, N_STRONG / 500))
        h = step_cost(N_STRONG / 500, 500, k_mpi, terms, variant, threads_speedup=sp)
        h["two_thread_speedup_used"] = sp
        h["parallel_efficiency_note"] = "against one thread on the same grains: 2 is ideal here"
        hybrid[variant] = h
    out["prediction_1e8_grains_500_ranks_2_threads"] = hybrid
    # ghost formula against the measured counts
    out["ghost_formula_check"] = [
        {"run": r["command"], "measured": r["ghost_check"]["ghosts_measured"],
         "recounted_from_frame": r["ghost_check"]["ghosts_recounted_from_frame"],
         "surface_formula": r["ghost_check"]["ghosts_predicted_surface_formula"],
         "surface_formula_error": r["ghost_check"]["surface_formula_error"],
         "shell_m_code": r["scene_geometry"]["shell_m"],
         "shell_m_from_measured": r["ghost_check"]["shell_m_from_measured_ghosts"]} for r in checks]
    # at LAMMPS' chute size per rank, for the comparison
    out["at_lammps_chute_sizes"] = {
        "note": ("8,000 grains per rank on 4 ranks (LAMMPS chute, 32,000 atoms on 4 procs; its numbers are in "
                 "studies/mpi/results/lammps_granular_scaling.md): compare communication_share with LAMMPS' Comm share "
                 "and ghosts_per_grain with its Nghost/Nlocal"),
        "neighbour_only": step_cost(8000, 4, k_mpi, terms, "neighbour_only"),
        "all_to_all": step_cost(8000, 4, k_mpi, terms, "all_to_all"),
    }
    with open(MODEL, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    figure(out)
    print("wrote %s and %s" % (os.path.relpath(MODEL, ROOT), os.path.relpath(FIGURE, ROOT)))


def figure(out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(12, 8.5))
    styles = {"all_to_all": "-", "neighbour_only": "--"}
    names = {"all_to_all": "all-to-all (every rank in every exchange)", "neighbour_only": "neighbour-only (the code now)"}
    for col, (case, title) in enumerate((("strong_1e8", "strong scaling, 1e8 grains"),
                                         ("weak_1e5_per_rank", "weak scaling, 1e5 grains per rank"))):
        ax, ax2 = axes[0][col], axes[1][col]
        for variant, curves in out["curves"].items():
            c = curves[case]
            p = [x["ranks"] for x in c]
            ls = styles[variant]
            ax.plot(p, [x["total_ms"] for x in c], "k" + ls, label="total, " + names[variant])
            q = [x for x in c if x["ranks"] > 1]
            ax.plot([x["ranks"] for x in q], [x["ghost_comm_ms"] for x in q], "C1" + ls,
                    label="ghost exchanges, " + names[variant])
            if variant == "all_to_all":
                ax.plot(p, [x["compute_ms"] for x in c], "C0", label="compute")
                ax.plot([x["ranks"] for x in q], [x["collectives_ms"] for x in q], "C2", label="allreduce")
            ax2.plot(p, [x["particle_steps_per_s"] for x in c], "k" + ls, label=names[variant])
        ideal = [x for x in out["curves"]["neighbour_only"][case]]
        ax2.plot([x["ranks"] for x in ideal], [x["grains_per_rank"] * x["ranks"] * x["rate_one_thread"] /
                                               x["grains_per_rank"] for x in ideal], "C0:",
                 label="compute only (no messages)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(title)
        ax.set_xlabel("MPI ranks (one core each)")
        ax.set_ylabel("ms per step")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        ax2.set_xscale("log")
        ax2.set_yscale("log")
        ax2.set_xlabel("MPI ranks (one core each)")
        ax2.set_ylabel("particle-steps/s")
        ax2.grid(True, which="both", alpha=0.3)
        ax2.legend(fontsize=7)
    fig.suptitle("grainflow_mpi cost model: 1.5 us, 12.5 GB/s links; one Zen 4 core per rank "
                 "(studies/mpi/results/cost_model.json)", fontsize=10)
    fig.tight_layout()
    fig.savefig(FIGURE, dpi=110)


# ----------------------------------------------------------------------------------------------------
# table

TABLE_RANKS = (1, 8, 64, 125, 512, 1000)


def table():
    out = json.load(open(MODEL))
    print("| scaling | exchanges | ranks | grains per rank | compute ms | ghost exchanges ms | collectives ms "
          "| total ms per step | particle-steps/s | parallel efficiency |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for case, label in (("strong_1e8", "strong, 1e8"), ("weak_1e5_per_rank", "weak, 1e5 per rank")):
        for p in TABLE_RANKS:
            for variant, vname in (("all_to_all", "all-to-all"), ("neighbour_only", "neighbour-only")):
                x = [r for r in out["curves"][variant][case] if r["ranks"] == p][0]
                if p == 1 and variant == "neighbour_only":
                    continue
                print("| %s | %s | %d | %s | %.3g | %.3g | %.3g | %.4g | %.3g | %.2f |" % (
                    label, "none" if p == 1 else vname, p, "{:,}".format(round(x["grains_per_rank"])),
                    x["compute_ms"], x["ghost_comm_ms"], x["collectives_ms"], x["total_ms"],
                    x["particle_steps_per_s"], x["parallel_efficiency"]))


if __name__ == "__main__":
    cmds = {"measure": measure, "model": model, "table": table}
    if len(sys.argv) != 2 or sys.argv[1] not in cmds:
        raise SystemExit("usage: cost_model.py measure|model|table")
    cmds[sys.argv[1]]()

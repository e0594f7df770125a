#!/usr/bin/python3
"""Seed 003's vertical transport pipe, scaled down (scenes/liquid/transport_pipe.toml): grains carried up a
periodic pipe of water at the seed's transport speeds, and the seed's observables against its table.

  /usr/bin/python3 studies/seed003/transport_pipe.py run [--speeds 2 3 4 5] [--offaxis] [--duration 2.5]
                                                     [--budget-minutes 30] [--binary build/grainflow]
      one case per speed into runs/liquid/transport_pipe/u<U> (and with --offaxis u<U>_offaxis for each
      of those speeds: the fill's centre moved 0.01 m off the axis, the seed's check), each in resumable
      pieces of at most the budget (grainflow.resumable: a piece stops with a checkpoint and the
      next resumes from it), each to its end before the next; after each piece the new frames are reduced
      to rows of frames.csv and the case archived under studies/seed003/results/transport_pipe/<case>; then collect
      --tag T names the cases u<U>_T; --courant C steps the liquid at dt = C l0 / U (the drive's relaxation
      scaled to keep its 0.2 s time constant); --frame-interval S; --prune deletes each liquid frame once it is
      reduced, all but the newest (a 100 s case writes about 3 MB a frame); --set KEY=VALUE passes an override on;
      a finished *_long case's archived series.csv keeps a row every 0.5 s
  /usr/bin/python3 studies/seed003/transport_pipe.py collect [--from 1.0]
      (a case named *_long starts its statistics at the earliest of 1, 2, 5, 10, 20 s after which the grains'
      mean speed, var(r/R) and the liquid's centre speed are flat within their noise: over twenty blocks to the
      end, the later half's mean within two standard errors of the earlier half's and the first block's within
      two of the others'; its JSON keeps the test, the block means' errors and the
      grains' axial concentration correlation over the periodic length: is 0.4 m long enough)
      studies/seed003/results/transport_pipe.json and studies/seed003/results/transport_pipe.png (profiles) from the cases'
      frames.csv, studies/seed003/results/transport_pipe_views.png (pictures) from the last frames where a run
      folder has them
  /usr/bin/python3 studies/seed003/transport_pipe.py table [studies/seed003/results/transport_pipe.json]
      the README's table (tools/readme/tables.py calls it; needs no numpy)

Each frame (every 0.05 s) is reduced to one row of frames.csv: per ring of r/R 0.1 wide the fluid nodes'
count and mean axial velocity and the grains' count; the grains' mean r/R, mean (r/R)^2, mean |omega| and
mean axial velocity. Observables, over the rows from --from s to the end of each case:
  u_profile     the fluid nodes' mean axial velocity over U in rings of r/R 0.1 wide
  phi_profile   the grains' volume fraction in the same rings (each grain's volume at its centre's ring)
  phi_peak      the ring of the largest volume fraction (its middle r/R) and that fraction
  r_variance    the variance of the grains' r/R over all frames' grains (a disc filled evenly: 1/18 =
                0.0556; the seed's values 0.029 to 0.040 are below it: the grains gather towards the axis),
                with the standard deviation of the frames' own variances beside it
  spin          the grains' mean |omega| (rad/s)
  grain_speed   the grains' mean axial velocity (m/s)
The seed's figures (spec/003, after 100 s of its 4 m pipe) are in SEED below.
"""
import argparse
import json
import math
import os

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
from grainflow.vtp import read_vtp  # noqa: E402

SCENE = "scenes/liquid/transport_pipe.toml"
RUNS = "runs/liquid/transport_pipe"
ARCHIVE = "studies/seed003/results/transport_pipe"
DOCS = "studies/seed003/results/transport_pipe.json"
R, LENGTH, RG = 0.1, 0.4, 0.01  # m: pipe radius, periodic length, grain radius
RINGS = 10
SEED = {  # speed: (radial variance, peak r/R, peak fraction %, mean spin rad/s)
    2: (2.875e-2, 0.16, 13.8, 2.86),
    3: (3.39e-2, 0.18, 13.5, 3.11),
    4: (3.94e-2, 0.26, 12.3, 3.84),
    5: (3.96e-2, None, None, 3.85),
}


def resumable():
    """grainflow.resumable, imported where runs are read (it needs numpy; the table does not)."""
    import grainflow.resumable as r
    return r


def cases(a):
    tag = f"_{a.tag}" if getattr(a, "tag", None) else ""
    out = [(f"u{u:g}{tag}", u, 0.0) for u in a.speeds]
    if a.offaxis:
        out += [(f"u{u:g}_offaxis{tag}", u, 0.01) for u in a.speeds]
    return out


def overrides(u, shift, duration):
    sets = [f"drive.mean_velocity={u}", f"run.velocity_scale={1.2 * u}",
            f"run.duration={duration}", "output.checkpoint_interval=0.5"]
    if shift:
        sets.append(f'fill.0.region={{shape="cylinder", center=[0.2,{shift},0.0], axis=[1.0,0.0,0.0], '
                    f'radius=0.08, length=0.4}}')
    return sets


def step_overrides(u, courant, l0=0.01, tau=0.2):
    """The liquid's step at U dt / l0 = courant, and the drive's relaxation that keeps the mean speed's time
    constant at tau seconds (the relaxation acts once a step)."""
    dt = courant * l0 / u
    return [f"run.dt={dt:.6g}", f"drive.relaxation={dt / tau:.6g}"]


LONG_SERIES_EVERY = 0.5  # s between the rows a finished long case keeps in its archived series.csv


def thin_series(path):
    """A finished long case's archived series.csv cut to a row every LONG_SERIES_EVERY seconds and its last row
    (its statistics come from frames.csv; the series is kept to show the run's course)."""
    with open(path) as fh:
        lines = fh.read().splitlines()
    head, rows = lines[0], lines[1:]
    kept, next_t = [], 0.0
    for k, line in enumerate(rows):
        t = float(line.split(",", 1)[0])
        if t >= next_t - 1e-9 or k == len(rows) - 1:
            kept.append(line)
            next_t = t + LONG_SERIES_EVERY
    with open(path, "w") as fh:
        fh.write("\n".join([head] + kept) + "\n")


def prune_liquid_frames(run_dir):
    """Deletes the liquid frames already reduced to frames.csv, all but the newest (a long run's pictures need
    only its last); the grains' frames are small and kept."""
    have = {round(r["time"], 9) for r in read_rows(os.path.join(run_dir, "frames.csv"))}
    listed = frames(run_dir, "liquid")
    for t, path in listed[:-1]:
        if round(t, 9) in have and os.path.exists(path):
            os.remove(path)


def run(a):
    r = resumable()
    pathlib = __import__("pathlib")
    for name, u, shift in cases(a):
        folder, dest = pathlib.Path(ROOT) / RUNS / name, pathlib.Path(ROOT) / ARCHIVE / name
        r.restore(folder, dest)
        done = lambda s: float(s[-1]["time"]) >= a.duration - 1e-9  # noqa: E731
        while True:
            sets = overrides(u, shift, a.duration)
            if a.courant:
                sets += step_overrides(u, a.courant)
            if a.frame_interval:
                sets.append(f"output.frame_interval={a.frame_interval}")
            sets += a.set or []
            piece = r.run_piece(name, a.binary, pathlib.Path(ROOT) / SCENE, folder, sets,
                                a.threads, a.budget_minutes * 60, done)
            update_frames(str(folder))
            if a.prune:
                prune_liquid_frames(str(folder))
            s = r.load_series(folder)
            finished = s is not None and done(s)
            r.archive(folder, dest, finished, extra=("frames.csv", "final_state.csv"))
            if finished and name.endswith("_long"):
                thin_series(dest / "series.csv")
            if piece is None or piece["status"] != "interrupted":
                break
    collect(a)


def frames(run_dir, part):
    import re
    path = os.path.join(run_dir, part, "frames.pvd")
    if not os.path.exists(path):
        return []
    text = open(path).read()
    return [(float(t), os.path.join(run_dir, part, f))
            for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)]


FLUID = 0  # a liquid frame's `species` is the node's kind: 0 fluid, 1 wall, 2 dummy


def node_kinds(liq):
    """Each node's kind in a liquid frame read by read_vtp."""
    return liq["species"]


def ring(r):
    return min(RINGS - 1, int(r / R * RINGS))


COLUMNS = (["time"] + [f"fluid_{k}" for k in range(RINGS)] + [f"u_{k}" for k in range(RINGS)] +
           [f"grains_{k}" for k in range(RINGS)] + ["grains", "r_mean", "r2_mean", "spin", "grain_vx"])


def reduce_frame(t, liquid_file, grain_file):
    """One row of frames.csv from a frame of both parts."""
    count, u_sum, grains = [0] * RINGS, [0.0] * RINGS, [0] * RINGS
    liq = read_vtp(liquid_file)
    for (_, y, z), (u, _, _), kind in zip(liq["Points"], liq["velocity"], node_kinds(liq)):
        if kind == FLUID:
            k = ring(math.hypot(y, z))
            count[k] += 1
            u_sum[k] += u
    g = read_vtp(grain_file)
    rr, spin, vx = [], 0.0, 0.0
    for (_, y, z), (u, _, _), w in zip(g["Points"], g["velocity"], g["angular_velocity"]):
        r = math.hypot(y, z)
        rr.append(r / R)
        grains[ring(r)] += 1
        spin += math.sqrt(sum(c * c for c in w))
        vx += u
    n = len(rr)
    return ([t] + count + [s / c if c else 0.0 for s, c in zip(u_sum, count)] + grains +
            [n, sum(rr) / n, sum(v * v for v in rr) / n, spin / n, vx / n])


def update_frames(run_dir):
    """Appends to run_dir/frames.csv the rows of the frames it does not hold yet."""
    path = os.path.join(run_dir, "frames.csv")
    rows = read_rows(path)
    have = {round(r["time"], 9) for r in rows}
    new = [(t, lf, gf) for (t, lf), (_, gf) in zip(frames(run_dir, "liquid"), frames(run_dir, "grains"))
           if round(t, 9) not in have and os.path.exists(lf) and os.path.exists(gf)]
    if not new:
        return
    exists = os.path.exists(path)
    with open(path, "a") as fh:
        if not exists:
            fh.write(",".join(COLUMNS) + "\n")
        for t, lf, gf in new:
            fh.write(",".join(repr(float(v)) for v in reduce_frame(t, lf, gf)) + "\n")


def read_rows(path):
    if not os.path.exists(path):
        return []
    with open(path) as fh:
        lines = [l.strip() for l in fh if l.strip()]
    head = lines[0].split(",")
    return [dict(zip(head, map(float, l.split(",")))) for l in lines[1:]]


def measure(run_dir, t_from, t_to=math.inf):
    """The observables of one case, averaged over its frames.csv rows from t_from to t_to."""
    rows = [r for r in read_rows(os.path.join(run_dir, "frames.csv")) if t_from - 1e-9 <= r["time"] <= t_to + 1e-9]
    summary_path = os.path.join(run_dir, "summary.json")
    if not os.path.exists(summary_path):
        return None
    summary = json.load(open(summary_path))
    if not rows:  # stopped before the statistics begin: what stopped it
        if summary.get("status") != "failed":
            return None
        return {"status": "failed", "to_s": summary.get("simulated_time"), "failure": summary.get("failure", "")}
    used = len(rows)
    rings = [(k + 0.5) / RINGS for k in range(RINGS)]
    area = [math.pi * R * R * ((k + 1) ** 2 - k ** 2) / RINGS ** 2 for k in range(RINGS)]
    fluid = [sum(r[f"fluid_{k}"] for r in rows) for k in range(RINGS)]
    u = [sum(r[f"fluid_{k}"] * r[f"u_{k}"] for r in rows) / fluid[k] if fluid[k] else None for k in range(RINGS)]
    volume = 4.0 / 3.0 * math.pi * RG ** 3
    phi = [100.0 * volume * sum(r[f"grains_{k}"] for r in rows) / (used * area[k] * LENGTH) for k in range(RINGS)]
    mean = sum(r["r_mean"] for r in rows) / used
    mean2 = sum(r["r2_mean"] for r in rows) / used
    per_frame = [r["r2_mean"] - r["r_mean"] ** 2 for r in rows]  # each frame's own variance of r/R
    spread = (sum((v - sum(per_frame) / used) ** 2 for v in per_frame) / max(1, used - 1)) ** 0.5
    peak = max(range(RINGS), key=lambda k: phi[k])
    pieces = resumable().pieces(__import__("pathlib").Path(run_dir))
    wall = sum(p["wall_seconds"] or 0 for p in pieces) if pieces else summary.get("wall_seconds")
    return {
        "frames": used, "from_s": t_from, "to_s": rows[-1]["time"], "status": summary.get("status"),
        "wall_seconds": wall, "rings": rings, "u_profile": u, "phi_profile": phi, "phi_peak_r": rings[peak],
        "phi_peak": phi[peak], "r_variance": mean2 - mean * mean, "r_variance_frame_sd": spread, "spin": sum(r["spin"] for r in rows) / used,
        "grain_speed": sum(r["grain_vx"] for r in rows) / used,
    }


LONG_STARTS = (1.0, 2.0, 5.0, 10.0, 20.0)  # s: the candidate starts of a long case's statistics, earliest first
BLOCKS = 20  # a long case's statistics window in this many blocks of equal frame counts


def frame_variance(r):
    return r["r2_mean"] - r["r_mean"] ** 2


def block_means(rows, value):
    n = len(rows) // BLOCKS
    return [sum(value(r) for r in rows[k * n:(k + 1) * n]) / n for k in range(BLOCKS)]


def block_variance(blocks):
    """The sample variance of the block means."""
    m = sum(blocks) / len(blocks)
    return sum((b - m) ** 2 for b in blocks) / (len(blocks) - 1)


def half_drift(blocks):
    """The later half's mean less the earlier half's, and the standard error of that difference from the
    blocks' own spread (blocks taken as independent)."""
    h = len(blocks) // 2
    var = block_variance(blocks)
    return sum(blocks[h:]) / (len(blocks) - h) - sum(blocks[:h]) / h, (var / h + var / (len(blocks) - h)) ** 0.5


def first_block_step(blocks):
    """The first block's mean less the others', and the standard error of that difference from the blocks'
    spread: a transient at the window's start that the halves' comparison would average away."""
    rest = blocks[1:]
    var = block_variance(blocks)
    return blocks[0] - sum(rest) / len(rest), (var + var / len(rest)) ** 0.5


STEADY = (("grain_speed", lambda r: r["grain_vx"]), ("r_variance", frame_variance),
          ("centre_speed", lambda r: r["u_0"]))


def steadiness(run_dir):
    """A long case's statistics start: the earliest of LONG_STARTS from which the grains' mean axial speed, the
    frames' variance of r/R and the liquid's centre speed (the slowest to develop) are flat within their noise:
    over BLOCKS blocks of the window to the end, the later half's mean lies within two standard errors of the
    earlier half's, and the first block's within two standard errors of the others'. Returns the start (None
    when no candidate passes) and each candidate's test."""
    rows = read_rows(os.path.join(run_dir, "frames.csv"))
    tests = []
    for t0 in LONG_STARTS:
        window = [r for r in rows if r["time"] >= t0 - 1e-9]
        if len(window) < 4 * BLOCKS:
            break
        test = {"from_s": t0}
        for name, value in STEADY:
            blocks = block_means(window, value)
            drift, se = half_drift(blocks)
            step, se_step = first_block_step(blocks)
            test[name] = {"drift": drift, "se": se, "first_block_step": step, "se_step": se_step,
                          "flat": abs(drift) < 2.0 * se and abs(step) < 2.0 * se_step}
        tests.append(test)
        if all(test[name]["flat"] for name, _ in STEADY):
            return t0, tests
    return None, tests


def block_errors(run_dir, t0):
    """Standard errors of the window's means from BLOCKS block means (the frames are correlated in time)."""
    rows = [r for r in read_rows(os.path.join(run_dir, "frames.csv")) if r["time"] >= t0 - 1e-9]
    out = {}
    for name, value in (("r_variance", frame_variance), ("spin", lambda r: r["spin"]),
                        ("grain_speed", lambda r: r["grain_vx"]), ("centre_speed", lambda r: r["u_0"])):
        b = block_means(rows, value)
        out[name] = (block_variance(b) / len(b)) ** 0.5
    return out


AXIAL_BINS = 20  # bins of the periodic length (20 mm, one grain diameter) for the axial correlation


def axial_correlation(run_dir, t_from):
    """The grains' axial concentration correlation over the periodic length, averaged over the grain frames
    from t_from on: per frame the grains counted in AXIAL_BINS bins along x, the fluctuations' periodic
    autocorrelation C(lag) = sum_k d_k d_(k+lag) / sum_k d_k^2. A pipe long enough for its grains has C near
    the uncorrelated value -1/(bins - 1) well before half the period. Returns the lags (m), C, the frames used
    and the shortest lag where C falls below 1/e (None if it never does). A run that went on in another
    checkout has lost the frames of its earlier pieces: only the frames still on disk count, and the
    result says from when."""
    sums, used, first = [0.0] * AXIAL_BINS, 0, None
    for t, path in frames(run_dir, "grains"):
        if t < t_from - 1e-9 or not os.path.exists(path):
            continue
        first = t if first is None else first
        counts = [0] * AXIAL_BINS
        for x, _, _ in read_vtp(path)["Points"]:
            counts[min(AXIAL_BINS - 1, max(0, int(x % LENGTH / LENGTH * AXIAL_BINS)))] += 1
        mean = sum(counts) / AXIAL_BINS
        d = [c - mean for c in counts]
        var = sum(v * v for v in d)
        if var <= 0:
            continue
        for lag in range(AXIAL_BINS):
            sums[lag] += sum(d[k] * d[(k + lag) % AXIAL_BINS] for k in range(AXIAL_BINS)) / var
        used += 1
    if not used:
        return None
    c = [v / used for v in sums[:AXIAL_BINS // 2 + 1]]
    lags = [k * LENGTH / AXIAL_BINS for k in range(len(c))]
    below = next((lag for lag, v in zip(lags, c) if v < math.exp(-1.0)), None)
    return {"lags_m": lags, "correlation": c, "frames": used, "frames_from_s": first, "decorrelated_by_m": below,
            "uncorrelated": -1.0 / (AXIAL_BINS - 1)}


def pictures(run_dirs, path):
    """Per speed, the last frame: a side view (a slab |z| < 10 mm: liquid nodes by axial speed, grains in
    it as circles) and a cross-section (every grain projected along the axis, liquid nodes of one layer)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle
    fig, axes = plt.subplots(2, len(run_dirs), figsize=(3.2 * len(run_dirs), 7.4), squeeze=False,
                             gridspec_kw={"height_ratios": [2.0, 1.0]})
    for col, (name, d) in enumerate(run_dirs):
        t, lf = frames(d, "liquid")[-1]
        _, gf = frames(d, "grains")[-1]
        liq, g = read_vtp(lf), read_vtp(gf)
        pts = [(p, v[0]) for p, v, k in zip(liq["Points"], liq["velocity"], node_kinds(liq)) if k == FLUID]
        side, top = axes[0][col], axes[1][col]
        slab = [(p[1], p[0], u) for p, u in pts if abs(p[2]) < 0.005]
        sc = side.scatter([s[0] for s in slab], [s[1] for s in slab], c=[s[2] for s in slab], s=9, cmap="viridis",
                          marker="s", linewidths=0)
        layer = [(p[1], p[2], u) for p, u in pts if abs(p[0] - 0.205) < 0.005]
        top.scatter([s[0] for s in layer], [s[1] for s in layer], c=[s[2] for s in layer], s=14, cmap="viridis",
                    marker="s", linewidths=0, vmin=sc.get_clim()[0], vmax=sc.get_clim()[1])
        for (x, y, z) in g["Points"]:
            if abs(z) < RG:
                side.add_patch(Circle((y, x), math.sqrt(RG * RG - z * z), fc="none", ec="red", lw=0.8))
            top.add_patch(Circle((y, z), RG, fc="none", ec="red", lw=0.6))
        for ax in (side, top):
            ax.set_aspect("equal")
            ax.set_xlim(-R, R)
            ax.set_xticks([-0.1, 0, 0.1])
        side.set_ylim(0, LENGTH)
        side.set_title(f"{name}, t = {t:.2f} s", fontsize=9)
        top.set_ylim(-R, R)
        fig.colorbar(sc, ax=side, shrink=0.6, label="axial liquid speed (m/s)")
    axes[0][0].set_ylabel("x along the pipe (m)")
    axes[1][0].set_ylabel("z (m)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def chart(result, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    for name, m in result["runs"].items():
        if "u_profile" not in m:
            continue
        u = m["speed"]
        a.plot(m["rings"], [v / u if v is not None else None for v in m["u_profile"]], "o-", ms=3, label=name)
        b.plot(m["rings"], m["phi_profile"], "o-", ms=3, label=name)
    for speed, (_, r, p, _) in SEED.items():
        if r is not None:
            b.plot([r], [p], "k*", ms=9)
    b.plot([], [], "k*", label="seed's peaks")
    a.set_xlabel("r/R")
    a.set_ylabel("axial liquid velocity / U")
    b.set_xlabel("r/R")
    b.set_ylabel("grain volume fraction (%)")
    a.legend(fontsize=8)
    b.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def collect(a):
    r = resumable()
    pathlib = __import__("pathlib")
    result = {"scene": SCENE, "from_s": a.from_s, "runs": {}}
    pictured = []
    names = set()
    for base in (RUNS, ARCHIVE):
        if os.path.isdir(os.path.join(ROOT, base)):
            names |= {n for n in os.listdir(os.path.join(ROOT, base)) if n.startswith("u")}
    for name in sorted(names, key=lambda n: (len(n), n)):
        folder, dest = pathlib.Path(ROOT) / RUNS / name, pathlib.Path(ROOT) / ARCHIVE / name
        r.restore(folder, dest)
        update_frames(str(folder))
        t0, tests = (steadiness(str(folder)) if name.endswith("_long") else (a.from_s, None))
        m = measure(str(folder), t0 if t0 is not None else LONG_STARTS[-1])
        if m is None:
            continue
        if tests is not None:
            m["steadiness"] = {"start": t0, "tests": tests}
            m["block_se"] = block_errors(str(folder), m["from_s"])
            m["axial_correlation"] = axial_correlation(str(folder), m["from_s"])
        m["speed"] = float(name[1:].split("_")[0])
        result["runs"][name] = m
        if frames(str(folder), "liquid"):
            pictured.append((name, str(folder)))
    with open(os.path.join(ROOT, DOCS), "w") as fh:
        json.dump(result, fh, indent=1)
    chart(result, os.path.join(ROOT, DOCS.replace(".json", ".png")))
    # The 2-s cases' pictures and the long cases' apart: a folder holds frames only while its run is on disk.
    short = [(n, d) for n, d in pictured if not n.endswith("_long")]
    long_ = [(n, d) for n, d in pictured if n.endswith("_long")]
    if short:
        pictures(short, os.path.join(ROOT, DOCS.replace(".json", "_views.png")))
    # The long cases' last frames side by side when all are on disk; else each one's apart, so that a
    # checkout holding one long run does not draw over the picture of the others.
    if long_ and len(long_) == sum(1 for n in result["runs"] if n.endswith("_long")):
        pictures(long_, os.path.join(ROOT, DOCS.replace(".json", "_long_views.png")))
    else:
        for name, folder in long_:
            pictures([(name, folder)], os.path.join(ROOT, DOCS.replace(".json", f"_{name}_views.png")))
    print(f"wrote {DOCS} ({len(result['runs'])} cases; pictures of {len(pictured)})")


def fmt(v, spec):
    return "—" if v is None else format(v, spec)


def table(a):
    d = json.load(open(a.path))
    print("| run | U (m/s) | statistics over (s) | var(r/R) ours (frames' sd) / seed | peak r/R ours / seed | peak fraction (%) "
          "ours / seed | mean spin (rad/s) ours / seed | grains' mean speed (m/s) | centre liquid / U | wall time (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, m in d["runs"].items():
        if "r_variance" not in m:
            print(f"| {name} | {m['speed']:g} | failed at t = {m['to_s']:.3f} s: {m['failure'].split(':')[0]} "
                  "| | | | | | | |")
            continue
        var, pr, pp, spin = SEED.get(int(m["speed"]), (None,) * 4)

        def se(key, spec, m=m):  # a long case's standard error of the mean from its block means
            return f"; mean ± {format(m['block_se'][key], spec)}" if "block_se" in m else ""
        centre = m["u_profile"][0] / m["speed"] if m["u_profile"][0] is not None else None
        print(f"| {name} | {m['speed']:g} | {m['from_s']:g}–{m['to_s']:.2f} ({m['frames']} frames) | "
              f"{m['r_variance']:.4f} (± {m['r_variance_frame_sd']:.4f}{se('r_variance', '.4f')}) / {fmt(var, '.4f')} | "
              f"{m['phi_peak_r']:.2f} / {fmt(pr, '.2f')} | "
              f"{m['phi_peak']:.1f} / {fmt(pp, '.1f')} | {m['spin']:.2f}{se('spin', '.2f')} / {fmt(spin, '.2f')} | "
              f"{m['grain_speed']:.2f}{se('grain_speed', '.3f')} | {fmt(centre, '.3f')} | {m['wall_seconds']:.0f} |")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--speeds", type=float, nargs="*", default=[2.0, 3.0, 4.0, 5.0])
    r.add_argument("--offaxis", action="store_true")
    r.add_argument("--duration", type=float, default=2.5)
    r.add_argument("--threads", type=int, default=1)
    r.add_argument("--budget-minutes", type=float, default=30.0)
    r.add_argument("--binary", default="build/grainflow")
    r.add_argument("--from", dest="from_s", type=float, default=1.0)
    r.add_argument("--tag", help="appended to each case's name (u2_TAG)")
    r.add_argument("--courant", type=float, help="the liquid's step from U dt / l0 (the scene's dt without it)")
    r.add_argument("--frame-interval", type=float, help="s between frames (the scene's without it)")
    r.add_argument("--prune", action="store_true", help="delete the liquid frames once reduced, all but the newest")
    r.add_argument("--set", action="append", help="another override, as grainflow's --set")
    c = sub.add_parser("collect")
    c.add_argument("--from", dest="from_s", type=float, default=1.0)
    t = sub.add_parser("table")
    t.add_argument("path", nargs="?", default=os.path.join(ROOT, DOCS))
    a = p.parse_args()
    {"run": run, "collect": collect, "table": table}[a.cmd](a)


if __name__ == "__main__":
    main()

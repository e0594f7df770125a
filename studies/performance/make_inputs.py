#!/usr/bin/python3
"""Write the LIGGGHTS 3.8 inputs for the standard benchmark state (seed-000 drum, settled).

    /usr/bin/python3 studies/performance/make_inputs.py OUTDIR [--steps N] [--rolling epsd|epsd3|epsd2|cdt]
                                                   [--csv PATH] [--segments N]

writes into OUTDIR
    drum.data  LIGGGHTS data file (atom_style granular: id type diameter density x y z), from
               scenes/data/drum_settled_47108.csv or --csv; atom types 1 (1 mm) and 2 (3 mm) as in the
               CSV, type 3 is the drum wall (no atoms). A state with velocities (columns vx,vy,vz and
               optionally wx,wy,wz, as grainflow's final_state.csv and the flowing-drum states) gets
               a Velocities section, so LIGGGHTS starts from the same motion.
    drum.stl   ASCII STL of the drum: inner cylinder surface and both flat end discs, one closed mesh
    in.drum    the input script (template TEMPLATE below), running N steps (default 2000)

Contact parameters are those of scenes/drum_seed000_settled.toml (linear spring-dashpot, kn = 1000 N/m,
kt = 600 N/m, en = et = er = 0.3, friction 0.3, rolling friction 5e-5 m, kr = 1e-5 N m/rad,
dt = 1e-5 s, skin 1.5e-4 m); how each one maps onto LIGGGHTS is documented at its use below.
Python 3 standard library only.
"""

import argparse
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))


def _outputs():
    """grainflow.outputs, imported where run files are read: it needs numpy, the tables do not."""
    import grainflow.outputs
    return grainflow.outputs


REPO = os.path.dirname(os.path.dirname(HERE))
DEFAULT_CSV = os.path.join(REPO, "scenes", "data", "drum_settled_47108.csv")

# --- scene (scenes/drum_seed000_settled.toml) ---------------------------------------------------
DENSITY = 2500.0          # kg/m^3, both species
KN = 1000.0               # N/m
KT = 600.0                # N/m
KR = 1.0e-5               # N m/rad, rolling stiffness
EN = ET = ER = 0.3        # restitution: normal, tangential, rolling
FRICTION = 0.3
ROLLING_FRICTION = 5.0e-5  # m: rolling torque cap = ROLLING_FRICTION * |F_n|
DT = 1.0e-5               # s
SKIN = 1.5e-4             # m
GRAVITY = 9.81            # m/s^2 along -y
DRUM_RADIUS = 0.075       # m, axis z through the origin
DRUM_HALF_LENGTH = 0.004  # m, end walls at z = +-0.004
OMEGA = 0.5               # rad/s about +z
WALL_TYPE = 3             # LIGGGHTS atom type given to the mesh

# --- drum mesh ------------------------------------------------------------------------------------
# The cylinder is a prism of SEGMENTS flat facets whose edges lie on the circle R = 0.075 m. The
# largest gap between facet and circle (the sag, at the facet middle) is R (1 - cos(pi/SEGMENTS)):
# for 720 segments 0.71 um, i.e. 0.14 % of the small-grain radius (0.5 mm) and well below the
# grain-wall overlaps of the settled state (up to ~15 um), so the facets are not felt as corners.
# (360 segments would give 2.9 um, 0.57 %.) Each end disc shares the cylinder's rim vertices and is
# coarsened inwards by rings, so that no triangle has an angle below a few degrees (LIGGGHTS warns
# below 0.5 deg) and the flat discs, which a quarter of the grains touch, are few large facets.
DEFAULT_SEGMENTS = 720


def damping(m_eff, k, e):
    """Dashpot coefficient (kg/s) of a linear spring k (N/m or N m/rad) on mass (or inertia) m_eff
    that gives the restitution e:  eta = 2 sqrt(m_eff k) ln(1/e) / sqrt(pi^2 + ln^2(1/e)).
    Same formula as grainflow's damping_coefficient (systems/contact/contact_params.cpp)."""
    l = math.log(1.0 / e)
    return 2.0 * math.sqrt(m_eff * k) * l / math.sqrt(math.pi ** 2 + l * l)


def damping_ratio(e):
    """eta / (2 sqrt(m k)) for restitution e."""
    l = math.log(1.0 / e)
    return l / math.sqrt(math.pi ** 2 + l * l)


def read_state(path):
    """Rows (id, type, diameter, x, y, z) and, when the file has them, velocities per row
    (vx, vy, vz, wx, wy, wz; spins 0 when only velocities are given), else None."""
    rows, vel = [], []
    d = _outputs().read_csv(path)
    has_v = {"vx", "vy", "vz"} <= set(d)
    has_w = {"wx", "wy", "wz"} <= set(d)
    for k in range(len(d["id"])):
        rows.append((int(d["id"][k]), int(d["type"][k]), float(d["diameter"][k]),
                     float(d["x"][k]), float(d["y"][k]), float(d["z"][k])))
        if has_v:
            w = tuple(float(d[c][k]) for c in ("wx", "wy", "wz")) if has_w else (0.0, 0.0, 0.0)
            vel.append(tuple(float(d[c][k]) for c in ("vx", "vy", "vz")) + w)
    # LIGGGHTS atom ids start at 1; grainflow's final_state.csv numbers grains from 0: shift them.
    shift = 1 - min(r[0] for r in rows) if rows and min(r[0] for r in rows) < 1 else 0
    rows = [(i + shift, *rest) for i, *rest in rows]
    diam = {}
    for _, t, d, _, _, _ in rows:
        if diam.setdefault(t, d) != d:
            sys.exit(f"make_inputs: type {t} has more than one diameter in {path}")
    if sorted(diam) != [1, 2]:
        sys.exit(f"make_inputs: expected atom types 1 and 2 in {path}, found {sorted(diam)}")
    return rows, (vel if vel else None), diam


def type_pair_tables(diam):
    """Per-type-pair matrices (3 x 3, row-major, types 1, 2 and the wall 3) of every property."""
    radius = {t: 0.5 * d for t, d in diam.items()}
    mass = {t: DENSITY * math.pi / 6.0 * d ** 3 for t, d in diam.items()}

    def m_eff(a, b):
        if a == WALL_TYPE and b == WALL_TYPE:
            return mass[1]  # wall-wall: never used, any valid value
        if a == WALL_TYPE or b == WALL_TYPE:
            return mass[b if a == WALL_TYPE else a]  # the wall does not move in response: own mass
        return mass[a] * mass[b] / (mass[a] + mass[b])

    def r_eff(a, b):
        if a == WALL_TYPE and b == WALL_TYPE:
            return radius[1]
        if a == WALL_TYPE or b == WALL_TYPE:
            return radius[b if a == WALL_TYPE else a]
        return radius[a] * radius[b] / (radius[a] + radius[b])

    types = [1, 2, WALL_TYPE]
    tab = {k: [] for k in ("kn", "kt", "gamman_abs", "gammat_abs", "friction", "rolling_mu", "rolling_visc")}
    for a in types:
        for b in types:
            m = m_eff(a, b)
            tab["kn"].append(KN)
            tab["kt"].append(KT)
            # Normal dashpot for e_n = 0.3 with this pair's effective mass (absolute_damping on: kg/s).
            tab["gamman_abs"].append(damping(m, KN, EN))
            # Tangential dashpot as grainflow's: e_t = 0.3 on the tangential spring kt with 2/7 m_eff.
            tab["gammat_abs"].append(damping(2.0 / 7.0 * m, KT, ET))
            tab["friction"].append(FRICTION)
            # LIGGGHTS caps the rolling torque at rmu * r_eff * |F_n| (r_eff = ri rj/(ri+rj), the
            # grain's radius against a wall); grainflow at f_r |F_n| with f_r a length, so
            # rmu = f_r / r_eff per pair gives the same cap.
            tab["rolling_mu"].append(ROLLING_FRICTION / r_eff(a, b))
            # epsd and epsd3 damp with coeffRollVisc * 2 sqrt(I_r k_r), I_r = 1.4 (m r^2)_eff (inertia about
            # the contact point); grainflow with damping(I_eff, kr, er), I_eff = 0.4 (m r^2)_eff. The
            # same dashpot needs coeffRollVisc = ratio(er) * sqrt(0.4 / 1.4), for every pair.
            tab["rolling_visc"].append(damping_ratio(ER) * math.sqrt(0.4 / 1.4))
    return tab, mass


def write_data(path, rows, vel):
    lo_xy = -(DRUM_RADIUS + 0.002)
    hi_xy = DRUM_RADIUS + 0.002
    lo_z, hi_z = -(DRUM_HALF_LENGTH + 0.001), DRUM_HALF_LENGTH + 0.001
    with open(path, "w") as f:
        f.write("LIGGGHTS data file: seed-000 settled drum (studies/performance/make_inputs.py)\n\n")
        f.write(f"{len(rows)} atoms\n{WALL_TYPE} atom types\n\n")
        f.write(f"{lo_xy:.6f} {hi_xy:.6f} xlo xhi\n{lo_xy:.6f} {hi_xy:.6f} ylo yhi\n")
        f.write(f"{lo_z:.6f} {hi_z:.6f} zlo zhi\n\n")
        f.write("Atoms\n\n")
        for i, t, d, x, y, z in rows:
            f.write(f"{i} {t} {d:.9g} {DENSITY:g} {x:.10g} {y:.10g} {z:.10g}\n")
        if vel:
            # atom_style granular: id vx vy vz omegax omegay omegaz
            f.write("\nVelocities\n\n")
            for (i, *_), v in zip(rows, vel):
                f.write(f"{i} " + " ".join(f"{c:.10g}" for c in v) + "\n")


def ring(radius, n, z, phase=0.0):
    if n == 0:
        return [(0.0, 0.0, z)]
    return [(radius * math.cos(phase + 2 * math.pi * k / n), radius * math.sin(phase + 2 * math.pi * k / n), z)
            for k in range(n)]


def strip(outer, inner):
    """Triangles between two closed rings of points (counter-clockwise), by walking both in angle."""
    tris = []
    if len(inner) == 1:  # fan to the centre
        c = inner[0]
        for k in range(len(outer)):
            tris.append((outer[k], outer[(k + 1) % len(outer)], c))
        return tris
    no, ni = len(outer), len(inner)
    i = j = 0
    while i < no or j < ni:
        # advance on the ring whose next step ends at the smaller angle
        a_o = 2 * math.pi * (i + 1) / no
        a_i = 2 * math.pi * (j + 1) / ni
        if j >= ni or (i < no and a_o <= a_i):
            tris.append((outer[i % no], outer[(i + 1) % no], inner[j % ni]))
            i += 1
        else:
            tris.append((outer[i % no], inner[(j + 1) % ni], inner[j % ni]))
            j += 1
    return tris


def drum_triangles(segments):
    R, h = DRUM_RADIUS, DRUM_HALF_LENGTH
    tris = []
    bottom, top = ring(R, segments, -h), ring(R, segments, h)
    for k in range(segments):
        a, b = bottom[k], bottom[(k + 1) % segments]
        c, d = top[k], top[(k + 1) % segments]
        tris += [(a, d, b), (a, c, d)]  # normals point into the drum
    # disc rings: rim (shared with the cylinder), then coarser rings inwards, then the centre
    rings = [(R, segments), (R - 0.003, max(segments // 4, 48)), (R - 0.010, 48), (R - 0.030, 16), (0.0, 0)]
    for z in (-h, h):
        pts = [ring(r, n, z) for r, n in rings]
        disc = [t for o, i in zip(pts, pts[1:]) for t in strip(o, i)]  # normals +z
        tris += disc if z < 0 else [(p, r, q) for p, q, r in disc]  # into the drum
    return tris


def min_angle_deg(t):
    best = 180.0
    for k in range(3):
        p, q, r = t[k], t[(k + 1) % 3], t[(k + 2) % 3]
        u = [q[m] - p[m] for m in range(3)]
        v = [r[m] - p[m] for m in range(3)]
        c = sum(u[m] * v[m] for m in range(3)) / math.sqrt(sum(x * x for x in u) * sum(x * x for x in v))
        best = min(best, math.degrees(math.acos(max(-1.0, min(1.0, c)))))
    return best


def write_stl(path, tris):
    with open(path, "w") as f:
        f.write("solid drum\n")
        for p, q, r in tris:
            u = [q[m] - p[m] for m in range(3)]
            v = [r[m] - p[m] for m in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            ln = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write(f"  facet normal {n[0] / ln:.6e} {n[1] / ln:.6e} {n[2] / ln:.6e}\n    outer loop\n")
            for x, y, z in (p, q, r):
                f.write(f"      vertex {x:.10e} {y:.10e} {z:.10e}\n")
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid drum\n")


TEMPLATE = """\
# LIGGGHTS 3.8: seed-000 drum from the settled benchmark state (written by studies/performance/make_inputs.py)
# 47,108 glass spheres (45,426 x 1 mm type 1, 1,682 x 3 mm type 2), drum R = 0.075 m, z = +-0.004 m,
# rotating at +0.5 rad/s about +z, gravity -9.81 along y. Same contact parameters as grainflow's
# scenes/drum_seed000_settled.toml; derived values are computed in make_inputs.py.

units           si
atom_style      granular
atom_modify     map array
boundary        f f f
newton          off
communicate     single vel yes
# Split along x only: the bed fills the lower half, so a y split would leave one rank idle.
processors      * 1 1

read_data       drum.data

neighbor        {skin:g} bin
neigh_modify    delay 0

# Per-type-pair properties; types 1, 2 = grains, {wall} = drum wall.
# kn, kt: N/m. gamman_abs, gammat_abs: kg/s (absolute_damping on), for restitution 0.3 with each
# pair's effective mass (wall: the grain's own mass):
#   eta = 2 sqrt(m_eff k) ln(1/e) / sqrt(pi^2 + ln^2(1/e)),  tangential with 2/7 m_eff and kt.
fix m_kn    all property/global kn peratomtypepair 3 {kn}
fix m_kt    all property/global kt peratomtypepair 3 {kt}
fix m_gn    all property/global gamman_abs peratomtypepair 3 {gamman_abs}
fix m_gt    all property/global gammat_abs peratomtypepair 3 {gammat_abs}
fix m_mu    all property/global coefficientFriction peratomtypepair 3 {friction}
# Rolling: cap rmu * r_eff * |F_n| = 5e-5 m * |F_n| (rmu = 5e-5 m / r_eff per pair).
fix m_rmu   all property/global coefficientRollingFriction peratomtypepair 3 {rolling_mu}
{rolling_extra}
pair_style      gran model hooke/stiffness tangential history rolling_friction {rolling} absolute_damping on
pair_coeff      * *

timestep        {dt:g}

fix drum_mesh   all mesh/surface file drum.stl type {wall}
fix drum_wall   all wall/gran model hooke/stiffness tangential history rolling_friction {rolling} &
                mesh n_meshes 1 meshes drum_mesh absolute_damping on
# period = 2 pi / 0.5 rad/s
fix drum_spin   all move/mesh mesh drum_mesh rotate origin 0. 0. 0. axis 0. 0. 1. period {period:.9f}

fix integrate   all nve/sphere
fix grav        all gravity {g:g} vector 0.0 -1.0 0.0

compute ke_t    all ke
compute ke_r    all erotate/sphere
thermo_style    custom step atoms c_ke_t c_ke_r
thermo_modify   lost error norm no
thermo          1000
{dump}
run             {steps}
"""

ROLLING_EXTRA = {
    # epsd (default): elastic-plastic spring-dashpot, the arithmetic of grainflow's rolling law
    # (spring on the accumulated relative rotation, dashpot, both capped at rmu r_eff |F_n|, no
    # dashpot at the cap) with k_r fixed at 2.25 kn (rmu r_eff)^2 = 2.25 * 1000 * (5e-5)^2
    # = 5.625e-6 N m/rad, i.e. 0.5625 x grainflow's 1e-5. Compiled in the optimised (whitelisted)
    # form in Debian's LIGGGHTS 3.8.
    "epsd": ("# epsd: k_r = 2.25 kn (rmu r_eff)^2 = 5.625e-6 N m/rad (grainflow: 1e-5), capped as above.\n"
             "# Rolling dashpot coeffRollVisc * 2 sqrt(1.4 (m r^2)_eff k_r): damping ratio of er = 0.3.\n"
             "fix m_rv    all property/global coefficientRollingViscousDamping peratomtypepair 3 {rolling_visc}\n"),
    # epsd3: the same with k_r = rollingStiffness * kn * (rmu r_eff)^2 = rollingStiffness * kn * (5e-5 m)^2,
    # so rollingStiffness = 4 gives grainflow's 1e-5 N m/rad for every pair: grainflow's law exactly
    # (but for the torsion part, see README). Debian's build has no optimised (whitelisted) kernel
    # for hooke/stiffness + history + epsd3 and warns that it runs up to 20 % slower.
    "epsd3": ("# Rolling stiffness k_r = c * kn * (rmu r_eff)^2 = c * 1000 * (5e-5)^2 = 1e-5 N m/rad for c = {c:g}.\n"
              "fix m_rk    all property/global rollingStiffness scalar {c:.9g}\n"
              "# Rolling dashpot coeffRollVisc * 2 sqrt(1.4 (m r^2)_eff k_r) = grainflow's er = 0.3 dashpot.\n"
              "fix m_rv    all property/global coefficientRollingViscousDamping peratomtypepair 3 {rolling_visc}\n"),
    # epsd2: k_r = kt r_eff^2 (3.75e-5 to 1.35e-3 N m/rad here), no dashpot; only the cap is matched.
    "epsd2": "# epsd2: k_r = kt * r_eff^2 (not grainflow's 1e-5 N m/rad), no rolling dashpot.\n",
    # cdt: constant torque rmu r_eff |F_n| against the relative spin; no spring, no dashpot.
    "cdt": "# cdt: constant torque at the cap against the relative spin; no spring, no dashpot.\n",
}


def fmt(values):
    return " ".join(f"{v:.9g}" for v in values)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("outdir", help="folder to write drum.data, drum.stl and in.drum into")
    ap.add_argument("--steps", type=int, default=2000, help="steps to run (default 2000)")
    ap.add_argument("--rolling", choices=sorted(ROLLING_EXTRA), default="epsd",
                    help="LIGGGHTS rolling-friction model (default epsd; epsd3 is grainflow's law "
                         "exactly but runs unoptimised in Debian's build)")
    ap.add_argument("--csv", default=DEFAULT_CSV,
                    help="state (id,type,diameter,x,y,z[,vx,vy,vz[,wx,wy,wz]]); default the settled drum")
    ap.add_argument("--dump-every", type=int, default=0,
                    help="write dump.STEP.txt (id type radius x y z vx vy vz) every N steps (default: none)")
    ap.add_argument("--skin", type=float, default=SKIN, help=f"Verlet skin in m (default {SKIN:g}, the scenes')")
    ap.add_argument("--segments", type=int, default=DEFAULT_SEGMENTS, help="facets around the cylinder")
    args = ap.parse_args()
    if args.steps < 0:
        ap.error("--steps must be >= 0")
    if not args.skin > 0:
        ap.error("--skin must be > 0")
    if args.segments < 64:
        ap.error("--segments must be >= 64")

    rows, vel, diam = read_state(args.csv)
    tab, _ = type_pair_tables(diam)
    os.makedirs(args.outdir, exist_ok=True)
    write_data(os.path.join(args.outdir, "drum.data"), rows, vel)
    tris = drum_triangles(args.segments)
    write_stl(os.path.join(args.outdir, "drum.stl"), tris)

    c_rk = KR / (KN * ROLLING_FRICTION ** 2)
    extra = ROLLING_EXTRA[args.rolling].format(c=c_rk, rolling_visc=fmt(tab["rolling_visc"]))
    script = TEMPLATE.format(
        skin=args.skin, wall=WALL_TYPE, kn=fmt(tab["kn"]), kt=fmt(tab["kt"]), gamman_abs=fmt(tab["gamman_abs"]),
        gammat_abs=fmt(tab["gammat_abs"]), friction=fmt(tab["friction"]), rolling_mu=fmt(tab["rolling_mu"]),
        rolling_extra=extra, rolling=args.rolling, dt=DT, period=2.0 * math.pi / OMEGA, g=GRAVITY,
        steps=args.steps,
        dump=(f"dump            states all custom {args.dump_every} dump.*.txt id type radius x y z vx vy vz\n"
              f"dump_modify     states sort id pad 7\n" if args.dump_every > 0 else ""))
    with open(os.path.join(args.outdir, "in.drum"), "w") as f:
        f.write(script)
    sag = DRUM_RADIUS * (1.0 - math.cos(math.pi / args.segments))
    print(f"make_inputs: {len(rows)} atoms, {len(tris)} facets (sag {sag * 1e6:.2f} um, "
          f"smallest angle {min(min_angle_deg(t) for t in tris):.2f} deg), {args.steps} steps, "
          f"{'with' if vel else 'no'} velocities, rolling {args.rolling} -> {args.outdir}", file=sys.stderr)


if __name__ == "__main__":
    main()

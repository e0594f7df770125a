#!/usr/bin/env python3
"""Writes the seed-004 drum-blade mixer scenes (scenes/mixer_seed004_design{1,2,3}.toml).

The seed gives the blades (60 mm wide, 60 or 20 mm long, inclined 60 and 30 degrees to the cross
section, alternately bent), three stages, the components' ratios (key/carrier density 0.786, size
0.778, key volume fraction 0.33), the fill factor 0.21 and N = 480 model particles. It does not give
the housing, the speed, the feed rate or where the stages and partitions sit; what is taken here:

  housing   radius 0.1 m, length 0.5 m (Vc is reported to L = 0.4 m), axis x, gravity -y; the
            analytic rotating cylinder, the rings and blades meshes turning with it
  speed     3.13 rad/s (30 rpm): Froude number w^2 R / g = 0.10, the rolling regime of a drum mixer
  stages    I, II, III centred at x = 0.10, 0.22, 0.34 m; four blades each, 90 degrees apart, fixed
            to the housing and reaching 60 mm in from it; blades alternately inclined -60 and +30
            degrees to the cross section (the seed's alpha1 and alpha2, "bent in opposite directions"; the
            signs that carry the bed towards the outlet, see ALPHA)
  partitions annular, inner radius 0.085 m, at x = 0.16, 0.28, 0.40 m; end ring at x = 0.5 m with
            a 0.08 m hole (the outlet); the inlet end is a closed disc (the nozzle is not modelled:
            the feed places grains just inside it). The holes set the hold-up: chosen so that design
            1 holds the seed's N = 480 (480-506 particles from 100 to 160 s in a trial); holes of
            0.07 and 0.065 m held 887-1,014, those of 0.05 and 0.045 m over 900 after 95 s with none
            out yet
  particles carrier (millet) 22.0 mm, 1400 kg/m^3; key (rapeseed) 17.1 mm (0.778), 1100 kg/m^3
            (0.786); about 480 of them make a fill factor of 0.21 at a solid fraction of 0.59
  feed      0.05 kg/s, key mass fraction 0.279 (its volume fraction 0.33), every 0.5 s into
            x = 0.012 .. 0.045 m above the bed: a mean residence time near 50 s at that hold-up

Sphere DEM of the same mixer (--dem F): the representative volumes' diameters divided by F (F^3 times
as many grains), rotating, with the Hertz-Mindlin law: the coarse-graining rule of keeping the
material (density, Young's modulus, restitution, friction) and scaling only the size (Bierwisch et
al. 2009, J. Mech. Phys. Solids 57, 10; Radl et al. 2011), so F = 1 is the representative volumes'
size with sphere physics and larger F approach the real grains (millet 2.3 mm is F of about 10).
Material assumed (the seed gives none): E = 1e7 Pa (reduced, as the kiln's; 2e6 Pa let a blade press
two 17 mm spheres 10 % into each other after 55 s), nu = 0.3, restitution 0.5, friction 0.4, rolling
friction 0.05, for both seeds; dt 0.3 of the Rayleigh time, as the kiln's; run.max_overlap 0.15.

Usage: mixer_scene.py [--out scenes]                 (writes the three designs)
       mixer_scene.py --dem F [--design 1] [--out scenes]   (writes mixer_seed004_dem_fF_designD.toml)
"""
import argparse
import re
import math
import pathlib

RADIUS, LENGTH, OMEGA = 0.1, 0.5, 3.13
STAGES = [0.10, 0.22, 0.34]
PARTITIONS = [0.16, 0.28, 0.40]
PARTITION_HOLE, OUTLET_HOLE = 0.085, 0.08
# Blades alternately at -60 and +30 degrees to the cross section (the seed's alpha1, alpha2, bent in
# opposite directions); with the housing turning at +omega about +x this pair carries the bed towards
# the outlet: in 80 s trials from empty, the first grain left at 49 s, and at 79 s with the signs
# swapped (which carry it back towards the inlet).
BLADE_WIDTH, ALPHA = 0.060, (-60.0, 30.0)
# Blade length (m) per stage, the seed's three designs.
DESIGNS = {1: (0.060, 0.060, 0.060), 2: (0.060, 0.060, 0.020), 3: (0.060, 0.020, 0.020)}
CARRIER = ("carrier", 0.022, 1400.0)
KEY = ("key", 0.022 * 0.778, 1400.0 * 0.786)
KEY_VOLUME_FRACTION = 0.33
RATE, FEED_EVERY = 0.05, 0.5


def vec(v):
    return "[" + ", ".join(f"{x:.6g}" for x in v) + "]"


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def housing():
    """The housing is the analytic rotating cylinder (unbounded along x; the inlet disc and the end
    ring close it, and a grain past the ring is counted out). As a mesh it was most of the step: the
    representative-volume law reaches 9.5 mm past touching, so a particle on the mantle lies within
    reach of 7 facets' planes. 25 s of design 1 from empty, two alternated rounds: 6.53 and 4.50 s of
    wall time with a 48-facet mesh housing, 2.56 and 2.49 s with the analytic cylinder (and 17.0 s with
    96 facets in 10 rings, against 7.9 s with 48 in one)."""
    return "\n".join(["[[wall]]", 'type = "cylinder"', 'name = "housing"', f"center = [{LENGTH / 2}, 0.0, 0.0]",
                      "axis = [1.0, 0.0, 0.0]", f"radius = {RADIUS}", f"omega = {OMEGA}", ""])


def mesh(name, lines):
    return "\n".join(["[[wall]]", 'type = "mesh"', f'name = "{name}"'] + lines +
                     [f"omega = {OMEGA}", "rotation_axis = [1.0, 0.0, 0.0]", "rotation_point = [0.0, 0.0, 0.0]", ""])


def blade(stage, k, x, length):
    """Blade k of a stage: a plate spanning the radial direction e_r (its width) and, in the plane
    tilted by alpha from the cross section, t = cos(alpha) e_theta + sin(alpha) e_x (its length)."""
    theta = math.pi / 2 * k + math.pi / 4
    e_r = (0.0, math.cos(theta), math.sin(theta))
    e_t = (0.0, -math.sin(theta), math.cos(theta))
    a = math.radians(ALPHA[k % 2])
    t = tuple(math.cos(a) * e_t[i] + math.sin(a) * (1.0, 0.0, 0.0)[i] for i in range(3))
    r_mid = RADIUS - 0.5 * BLADE_WIDTH
    centre = (x, r_mid * e_r[1], r_mid * e_r[2])
    return mesh(f"blade-{stage}{k}", ['primitive = "plate"', f"center = {vec(centre)}", f"normal = {vec(cross(e_r, t))}",
                                      f"axis = {vec(t)}", f"half_widths = [{0.5 * length:.6g}, {0.5 * BLADE_WIDTH - 0.001:.6g}]"])


def ring(name, x, inner):
    return mesh(name, ['primitive = "annulus"', f"center = [{x}, 0.0, 0.0]", "axis = [1.0, 0.0, 0.0]",
                       f"inner_radius = {inner}", f"outer_radius = {RADIUS}", "segments = 64"])


def physics(dem):
    """The [run], [[species]] and [contact] tables: representative volumes, or spheres 1/dem the size."""
    if dem is None:
        return f"""[run]
dt = 4.0e-4            # s (check prints the law's time-step terms)
duration = 300.0       # s: steady from about 150 s (hold-up), pooled rows every 20 s after
skin = 2.0e-3          # m
gravity = [0.0, -9.81, 0.0]
max_overlap = 0.4      # of the smaller diameter: the law is soft, a particle under N weights overlaps k_d R* ln N
seed = {{seed}}

[[species]]
name = "{CARRIER[0]}"       # millet's representative volume
diameter = {CARRIER[1]:.6g}
density = {CARRIER[2]:.6g}
rotates = false

[[species]]
name = "{KEY[0]}"           # rapeseed's: 0.778 of the carrier's size, 0.786 of its density
diameter = {KEY[1]:.6g}
density = {KEY[2]:.6g}
rotates = false

[contact]
model = "representative_volume"
kd = 0.25              # the seed's particle coefficients
kr = 15.0
kp = 0.15
cutoff = 1.0e-3
slip_speed = 0.01      # m/s: friction regularisation

[contact.wall]
kd = 0.2               # the seed's wall coefficients
kr = 10.0
kp = 0.1
"""
    d_c, d_k = CARRIER[1] / dem, KEY[1] / dem
    # The Rayleigh time of the small grains scales with the diameter; dt 0.3 of it (2.46e-4 s at 8.55 mm).
    dt = 7.3e-5 * d_k / 0.00855
    return f"""[run]
dt = {dt:.3g}            # s (check prints the law's time-step terms)
duration = 300.0       # s: as the representative volumes
dt_safety = 0.3        # of the smallest time-step term, the Rayleigh time of a small grain
max_overlap = 0.15     # of the smaller diameter: a blade pressing a grain into the bed
skin = {0.15 * d_k:.3g}        # m
gravity = [0.0, -9.81, 0.0]
seed = {{seed}}

[[species]]
name = "{CARRIER[0]}"       # millet, coarse-grained: the representative volume's size / {dem:g}
diameter = {d_c:.6g}
density = {CARRIER[2]:.6g}
youngs_modulus = 1.0e7
poisson_ratio = 0.3

[[species]]
name = "{KEY[0]}"           # rapeseed: 0.778 of the carrier's size, 0.786 of its density
diameter = {d_k:.6g}
density = {KEY[2]:.6g}
youngs_modulus = 1.0e7
poisson_ratio = 0.3

[contact]
model = "hertz_mindlin"
restitution = 0.5
friction = 0.4
rolling_friction = 0.05
impact_speed = 1.0     # m/s: a grain thrown by a blade
"""


STEADY_STATE = "data/mixer_design1_steady.csv"  # design 1 at its hold-up, turned back to angle 0
STEADY_DURATION = 100.0  # s from the steady state: five pooled rows of layers.csv


def scene(design, dem=None, steady=False, length=LENGTH, partitions=PARTITIONS, outlet_hole=OUTLET_HOLE,
          partition_hole=PARTITION_HOLE):
    """The scene's text; length (the end ring's x), partitions, their hole and the end ring's hole are the
    housing's, for variants."""
    lengths = DESIGNS[design]
    vk = KEY_VOLUME_FRACTION
    key_mass = vk * KEY[2] / (vk * KEY[2] + (1 - vk) * CARRIER[2])
    what = ("the seed's representative-volume law and coefficients" if dem is None else
            f"sphere DEM (Hertz-Mindlin) of grains 1/{dem:g} the representative volumes' size")
    out = [f"""# Seed 004's continuous drum-blade mixer, blade design {design} (blade lengths {', '.join(f'{l*1000:.0f}' for l in lengths)} mm
# at stages I, II, III), with {what}. Written by
# scenes/generators/mixer_scene.py, which states what the seed does not give (housing, speed, feed, where
# the stages sit). {{start}}
# layers.csv holds Vc of transverse layers at L = 0.025 .. 0.475 m, pooled over 20 s of samples.
# Units: SI (m, kg, s, N, rad).

""".replace("{start}", STARTS[steady]) + physics(dem).replace("{seed}", str(design)), housing(),
           ring("inlet-wall", 0.0, 0.0)]
    for i, x in enumerate(partitions):
        out.append(ring(f"partition-{i + 1}", x, partition_hole))
    out.append(ring("end-ring", length, outlet_hole))
    for s, (x, l) in enumerate(zip(STAGES, lengths)):
        for k in range(4):
            out.append(blade("I" * (s + 1) if s < 3 else str(s), k, x, l))
    if steady:
        out.append(f"""[[fill]]
kind = "file"
path = "{STEADY_STATE}"
types = {{ 1 = "carrier", 2 = "key" }}   # the file's types, as final_state.csv numbers them (species + 1)
""")
    out.append(f"""[[feed]]
mass_rate = {RATE}       # kg/s
fractions = {{ key = {key_mass:.6f}, carrier = {1 - key_mass:.6f} }}   # by mass: key volume fraction {vk}
interval = {FEED_EVERY}
region = {{ shape = "box", lo = [0.012, -0.01, -0.045], hi = [0.045, 0.06, 0.045] }}

[[outlet]]
interval = 0.1
region = {{ shape = "box", lo = [{length + 0.015}, -1.0, -1.0], hi = [2.0, 1.0, 1.0] }}

[analysis]
species = "key"

[analysis.layers]
inlet = [0.0, 0.0, 0.0]
axis = [1.0, 0.0, 0.0]
distances = {vec([0.025 * k for k in range(1, 20)])}
cell = 0.05            # m: square sample cells of the cross-section
min_grains = 10        # grain visits per cell over the pool
interval = 0.5         # s between samples
pool = 40              # samples pooled per row (20 s)

[output]
series_interval = 1.0
frame_interval = 10.0
checkpoint_interval = 20.0
""")
    text = "\n".join(out)
    if steady:
        text = re.sub(r"duration = [0-9.]+ +# s: [^\n]*", f"duration = {STEADY_DURATION}       # s from the steady state", text)
    return text


STARTS = {False: "Starts empty; the feed fills it and the end ring's hole lets the mixture out.",
          True: "Starts from its steady hold-up (" + STEADY_STATE + "), so layers.csv\n# reads from the first pooled row; the "
                "feed goes on and the end ring's hole lets the mixture out."}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(pathlib.Path(__file__).resolve().parents[2] / "scenes"))
    ap.add_argument("--dem", type=float, help="sphere DEM, diameters divided by this factor")
    ap.add_argument("--design", type=int, default=1, choices=sorted(DESIGNS))
    ap.add_argument("--steady", action="store_true", help="design 1 from its steady state instead of empty")
    args = ap.parse_args()
    if args.steady:
        p = pathlib.Path(args.out) / "mixer_seed004_design1_steady.toml"
        p.write_text(scene(1, steady=True))
        print("wrote", p)
        return
    if args.dem:
        p = pathlib.Path(args.out) / f"mixer_seed004_dem_f{args.dem:g}_design{args.design}.toml"
        p.write_text(scene(args.design, args.dem))
        print("wrote", p)
        return
    for d in DESIGNS:
        p = pathlib.Path(args.out) / f"mixer_seed004_design{d}.toml"
        p.write_text(scene(d))
        print("wrote", p)


if __name__ == "__main__":
    main()

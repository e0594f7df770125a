#include "systems/mps/liquid_fields.hpp"

#include "engine/output_times.hpp"

namespace gf {

namespace {

constexpr Range kUnitOpenClosed{0, 1, true, false};  // (0, 1]
constexpr Range kLimit{0, 2, true, false};           // (0, 2]

constexpr std::string_view kBool = "true, false";

const Field kLiquid[] = {
    {"dim", "", {2, 3, false, false}, "(integers); 3 in a coupled scene", kNoDefault, "", "space dimension"},
    {"l0", "m", range::length, "and smaller than the geometry's narrowest extent", kNoDefault, "", "initial particle spacing"},
    {"re", "l0", {1.5, 5, false, false}, "", 2.1, "", "kernel radius"},
    {"density", "kg/m³", range::density, "", kNoDefault, "", "liquid density ρ"},
    {"viscosity", "m²/s", range::kinematic_viscosity, "", kNoDefault, "", "kinematic viscosity ν"},
    {"turbulence", "", kAnyNumber, "`\"none\"`, `\"mixing_length\"` (a `pipe` only)", kNoDefault, "`\"none\"`",
     "eddy viscosity per node: Prandtl's mixing length with Nikuradse's profile, in the momentum diffusion only"},
    {"eddy_viscosity", "m²/s", {0, 1, false, false}, "", 0.0, "",
     "constant eddy viscosity ν_t, added to ν in the liquid's momentum diffusion only (a coupled drag law keeps ν)"},
    {"gamma", "", kFraction, "", 0.001, "", "weight γ of the number-density term in the pressure source"},
    {"surface_threshold", "", kUnitOpenClosed, "", 0.97, "", "β: a node with `n* < β n0` is a surface node"},
    {"free_surface", "", kAnyNumber, kBool, kNoDefault, "true", "false: a closed liquid, no surface nodes"},
    {"gradient", "", kAnyNumber, "`\"sum\"`, `\"min\"`", kNoDefault, "`\"sum\"`",
     "pressure-gradient form: symmetric `(p_j + p_i)` or Koshizuka's `(p_j − p_min)`"},
    {"clip_negative", "", kAnyNumber, kBool, kNoDefault, "true", "set negative pressures to 0 after the solve"},
    {"compressibility", "1/Pa", range::compressibility, "", 0.0, "", "Ikeda's α; > 0 makes a closed liquid's matrix definite"},
    {"collision_distance", "l0", kFraction, "", 0.8, "", "distance below which the collision model acts"},
    {"collision_restitution", "", kFraction, "", 0.2, "", "restitution of the collision model"},
    {"skin", "l0", {0, 2, false, false}, "", 0.5, "", "Verlet skin of the neighbour list (search radius `re + skin`)"},
    {"solver.", "", kAnyNumber, "", kNoDefault, "", "", &kLiquidSolverFields},
};

const Field kSolver[] = {
    {"kind", "", kAnyNumber, "`\"parallel_cg\"`, `\"eigen_cg\"`", kNoDefault, "`\"parallel_cg\"`", "pressure solver"},
    {"preconditioner", "", kAnyNumber,
     "`\"jacobi\"`, `\"multigrid\"` (`parallel_cg` only), `\"incomplete_cholesky\"` (`eigen_cg` only)", kNoDefault,
     "`\"jacobi\"`", "preconditioner"},
    {"tolerance", "", {0, 0.1, true, false}, "", 1e-8, "1e-8", "relative residual ‖b − Ap‖/‖b‖ to reach"},
    {"max_iterations", "", {1, 1e6, false, false}, "(integers)", 2000, "",
     "iterations before the run stops with the solver's message"},
    {"multigrid_reuse", "", {1, 1e6, false, false}, "(integers)", 1, "",
     "steps one multigrid hierarchy serves before it is rebuilt from the nodes' positions (`multigrid` only)"},
};

const Field kRun[] = {
    {"dt", "s", range::time_step, "and within the CFL and diffusion limits", kNoDefault, "",
     "the liquid's step (the outer step of a coupled scene)"},
    {"duration", "s", range::time_span, "and at most 1e15 steps", kNoDefault, "", "simulated time"},
    {"gravity", "m/s²", kAnyNumber, "3 numbers, magnitude ≤ 1e6; z = 0 in 2D", kNoDefault,
     "[0, 0, 0]; required in a coupled scene", "gravity"},
    {"body_force", "m/s²", kAnyNumber, "3 numbers, magnitude ≤ 1e6; z = 0 in 2D", kNoDefault, "[0, 0, 0]",
     "extra acceleration of the liquid; with `[drive]`, the start of the control"},
    {"velocity_scale", "m/s", range::speed, "", kNoDefault,
     "free fall over the liquid's height, `sqrt(2 g H)` with g the size of `gravity`; required without gravity",
     "speed for the load-time CFL check"},
    {"cfl_limit", "", kLimit, "", 0.5, "", "largest CFL number, at load and during the run"},
    {"diffusion_limit", "", kLimit, "", 0.2, "", "largest `ν dt/l0²` at load"},
    {"density_limit", "", {1, 10, true, false}, "", 1.5, "", "largest `n*/n0` before the run stops"},
    {"allow_unstable_dt", "", kAnyNumber, kBool, kNoDefault, "false",
     "run despite the load-time checks (and, coupled, a too-small `substeps`)"},
    {"domain_margin", "m", range::length_or_zero, "", kNoDefault, "10 l0", "how far a fluid node may leave the geometry's bounds"},
};

const Field kGeometry[] = {
    {"type", "", kAnyNumber, "`\"tank\"`, `\"box\"`, `\"channel\"`, `\"pipe\"`", kNoDefault, "",
     "the walls (see Geometries)"},
    {"layers", "", {1, 20, false, false}, "(integers), and at least `re/l0` rounded up", kNoDefault,
     "the larger of 3 and `re/l0` rounded up", "wall plus dummy layers"},
    {"lo", "m", kAnyNumber, "3 numbers; z = 0 in 2D", kNoDefault, "required (not `pipe`)", "low corner of the inner faces"},
    {"hi", "m", kAnyNumber,
     "each component above `lo`'s; z = 0 in 2D; channel: x length a whole number of `l0`, at least 3 search radii",
     kNoDefault, "required (not `pipe`)", "high corner of the inner faces"},
    {"center", "m", kAnyNumber, "3 numbers", kNoDefault, "required (`pipe`)",
     "the pipe's axis runs along x through (·, y, z) and starts at x"},
    {"radius", "m", range::length, "and at least 2 l0", kNoDefault, "required (`pipe`)", "inner radius"},
    {"length", "m", range::length, "and a whole number of `l0`, at least 3 search radii", kNoDefault, "required (`pipe`)",
     "periodic length along x"},
};

const Field kFluidBlock[] = {
    {"lo", "m", kAnyNumber, "3 numbers", kNoDefault, "",
     "low corner of a block to fill; lattice nodes in `[lo, hi)` inside the geometry become liquid"},
    {"hi", "m", kAnyNumber, "each component above `lo`'s (in the scene's dimensions)", kNoDefault, "",
     "high corner of the block"},
    {"velocity", "m/s", kAnyNumber, "3 numbers", kNoDefault, "[0, 0, 0]", "the block's starting velocity"},
};

const Field kDrive[] = {
    {"mean_velocity", "m/s", {-1e3, 1e3, false, false}, "and only with a periodic geometry", kNoDefault, "",
     "target mean velocity of the fluid nodes along the periodic axis"},
    {"relaxation", "", kUnitOpenClosed, "", 1.0, "", "share r of the gap closed per step; the time constant is `dt/r`"},
};

const Field kOutput[] = {
    {"", "", kAnyNumber, "", kNoDefault, "", "", &kOutputTimesFields},
};

}  // namespace

const FieldTable kLiquidFields{"[liquid]", "liquid.md", kLiquid};
const FieldTable kLiquidSolverFields{"solver", "", kSolver};
const FieldTable kLiquidRunFields{"[run]", "liquid.md", kRun};
const FieldTable kLiquidGeometryFields{"[geometry]", "liquid.md", kGeometry};
const FieldTable kFluidBlockFields{"[[fluid]]", "liquid.md", kFluidBlock};
const FieldTable kDriveFields{"[drive]", "liquid.md", kDrive};
const FieldTable kLiquidOutputFields{"[output]", "liquid.md", kOutput};

std::vector<const FieldTable*> liquid_field_tables() {
  return {&kLiquidFields, &kLiquidRunFields, &kLiquidGeometryFields, &kFluidBlockFields, &kDriveFields,
          &kLiquidOutputFields};
}

}  // namespace gf

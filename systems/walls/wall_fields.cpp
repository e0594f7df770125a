#include "systems/walls/wall_fields.hpp"

namespace gf {

namespace {

constexpr Range kLength{1e-9, 1e3, false, false};  // m: a kilometre-wide wall is a typo

const Field kWall[] = {
    {"type", "", kAnyNumber, "`\"plane\"`, `\"box\"`, `\"cylinder\"`, `\"drum\"`, `\"mesh\"`", kNoDefault, "",
     "the kind of wall"},
    {"name", "", kAnyNumber, "text", kNoDefault, "the type", "the wall's name in messages and outputs"},
    {"point", "m", kAnyNumber, "three numbers", kNoDefault, "required (plane)", "a point on the plane"},
    {"normal", "", kAnyNumber, "non-zero vector", kNoDefault, "required (plane; mesh plate)",
     "plane: the normal into the domain. Mesh plate: the plate's normal"},
    {"lo", "m", kAnyNumber, "three numbers", kNoDefault, "required (box)", "the box's lower corner"},
    {"hi", "m", kAnyNumber, "three numbers, each above `lo`'s", kNoDefault, "required (box)", "the box's upper corner"},
    {"center", "m", kAnyNumber, "three numbers", kNoDefault, "required (cylinder, drum, mesh primitives)",
     "a point on the axis (the middle of a drum; the centre of a mesh primitive)"},
    {"axis", "", kAnyNumber, "non-zero vector", kNoDefault, "required (cylinder, drum, mesh primitives)",
     "the axis direction; for a mesh plate, a direction in the plate's plane"},
    {"radius", "m", kLength, "", kNoDefault, "required (cylinder, drum, mesh cylinder)",
     "the radius (of the inner surface, for cylinder and drum)"},
    {"length", "m", kLength, "", kNoDefault, "required (drum, mesh cylinder)", "the length along the axis"},
    {"omega", "rad/s", kAnyNumber, "any finite number", 0.0, "",
     "rotation rate (plane, cylinder, drum, mesh) about the rotation axis (a cylinder's or drum's own axis); a "
     "cylinder, drum or mesh surface may move at most 0.1 of the smallest diameter per step"},
    {"velocity", "m/s", {0, 1e5, false, false}, "three numbers, length at most 1e5", kNoDefault, "`[0, 0, 0]`",
     "a constant translational velocity of the wall (any type), added to its rotation and vibration"},
    {"vibration_amplitude", "m", {0, 1e3, false, false}, "three numbers, length at most 1000", kNoDefault, "`[0, 0, 0]`",
     "the vector amplitude A of a sinusoidal vibration: the wall is displaced by A (sin(2π f t + φ) − sin φ)"},
    {"vibration_frequency", "Hz", {0, 1e6, false, false}, "", 0.0, "", "the vibration's frequency f"},
    {"vibration_phase", "rad", {-1e3, 1e3, false, false}, "", 0.0, "", "the vibration's phase φ at t = 0"},
    {"velocity_file", "", kAnyNumber, "path of a CSV file of rows `time, vx, vy, vz` (s, m/s) from time 0",
     kNoDefault, "none",
     "a prescribed translational velocity, linear between rows and held at the last row's after it; relative to "
     "the scene file"},
    {"rotation_point", "m", kAnyNumber, "three numbers", kNoDefault, "the plane's `point`; a mesh primitive's `center`",
     "plane and mesh: a point on the rotation axis; required for a turning mesh file"},
    {"rotation_axis", "", kAnyNumber, "non-zero vector", kNoDefault,
     "the plane's `normal`; a mesh primitive's axis (a plate's normal)",
     "plane and mesh: the rotation axis; required for a turning mesh file"},
    {"file", "", kAnyNumber, "path of an STL file (binary or ASCII)", kNoDefault, "required (mesh), or `primitive`",
     "mesh: the surface, relative to the scene file; give exactly one of `file` and `primitive`"},
    {"scale", "", kLength, "", 1.0, "", "mesh file: factor applied to the file's coordinates (0.001 for a file in mm)"},
    {"translate", "m", kAnyNumber, "three numbers", kNoDefault, "`[0, 0, 0]`", "mesh file: added after scaling"},
    {"primitive", "", kAnyNumber, "`\"plate\"`, `\"annulus\"`, `\"cylinder\"`", kNoDefault, "required (mesh), or `file`",
     "mesh: a surface built without a file"},
    {"half_widths", "m", kAnyNumber, "two numbers, each in (0, 1000]", kNoDefault, "required (mesh plate)",
     "the plate's half-widths along `axis` and along `normal` × `axis`"},
    {"cells", "", kAnyNumber, "two whole numbers ≥ 1, product ≤ 1e7", kNoDefault, "`[1, 1]`",
     "mesh plate: cells along the two directions, two triangles per cell"},
    {"outer_radius", "m", kLength, "", kNoDefault, "required (mesh annulus)", "the annulus's outer radius"},
    {"inner_radius", "m", range::length_or_zero, "and below `outer_radius`", 0.0, "",
     "mesh annulus: the inner radius (0 for a disc)"},
    {"segments", "", {3, 1e5, false, false}, "(integers)", 64, "", "mesh annulus and cylinder: segments around the axis"},
    {"rings", "", {1, 1e5, false, false}, "(integers)", 1, "", "mesh cylinder: rings along the axis"},
};

}  // namespace

const FieldTable kWallFields{"[[wall]]", "scene-files.md", kWall};

}  // namespace gf

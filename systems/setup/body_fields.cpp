#include "systems/setup/body_fields.hpp"

#include "engine/output_times.hpp"
#include "systems/bodies/mass_properties.hpp"
#include "systems/setup/scene_fields.hpp"

namespace gf {

namespace {

constexpr Range kHeight{-1e6, 1e6, false, false};  // m along -gravity
constexpr Range kTime{0, 1e12, false, false};       // s

// An up_down_cone's facets: two rings of corners per frustum within a part's vertex limit.
constexpr double kMaxFacets = 64;
static_assert(kMaxFacets == kMaxCoreVertices / 2);

const Field kShape[] = {
    {"name", "", kAnyNumber, "unique among `[[shape]]` and `[[species]]` names", kNoDefault, "",
     "the name `[[bodies]]` tables refer to"},
    {"kind", "", kAnyNumber,
     "`\"box\"`, `\"triangular_prism\"`, `\"up_down_cone\"`, `\"letter\"`, `\"file\"`, `\"sphere\"`, `\"spheres\"`, "
     "`\"ellipsoid\"`",
     kNoDefault, "", "how the shape is built; the keys below belong to one kind each"},
    {"radius", "m", {0, 100, false, false}, "and > 0 for `sphere` and `spheres` and under `hertz_mindlin`", kNoDefault,
     "", "the dilation radius r shared by every part (edge rounding; a sphere's or clump sphere's radius)"},
    {"density", "kg/m³", range::density, "", kNoDefault, "", "the material's density"},
    {"grid", "m", range::length,
     "and at most 2^22 voxels over the bounding box, at least 8 inside the shape; refused for `sphere` and for "
     "`ellipsoid` with `radius` 0 (exact)",
     kNoDefault, "a tenth of the shape's smallest bounding-box edge", "voxel edge of the mass-property grid"},
    {"size", "m", kAnyNumber,
     "[x, y, z], each > 0 and wide enough that the core keeps an inside after the inset by `radius`", kNoDefault,
     "required (`box`)", "a box's outer edges along x, y, z, centred on the origin"},
    {"side", "m", range::length, "", kNoDefault, "required (`triangular_prism`)",
     "the outer edge of the equilateral triangle (centroid on the z axis, one corner on +y)"},
    {"length", "m", range::length, "", kNoDefault, "required (`triangular_prism`)", "the prism's outer length along z"},
    {"base_radius", "m", range::length, "", kNoDefault, "required (`up_down_cone`)",
     "circle through the wide end's corners of each frustum"},
    {"neck_radius", "m", range::length_or_zero, "and < `base_radius`; > 0 when joined at the narrow ends", kNoDefault,
     "required (`up_down_cone`)", "circle through the narrow end's corners (0: a pyramid)"},
    {"height", "m", range::length, "and for a letter > 3 `stroke`", kNoDefault,
     "required (`up_down_cone`); 0.180 (`letter`)",
     "`up_down_cone`: axial length of each of the two frusta; `letter`: the letter's height H"},
    {"facets", "", {3, kMaxFacets, false, false}, "(integers)", 12, "", "side faces of each frustum (`up_down_cone`)"},
    {"join", "", kAnyNumber, "`\"narrow_ends\"`, `\"wide_ends\"`", kNoDefault, "`\"narrow_ends\"`",
     "`up_down_cone`: an hourglass (concave, the seed's element) or a double frustum (convex, still two parts)"},
    {"letter", "", kAnyNumber, "`\"O\"`, `\"T\"`, `\"Z\"`, `\"K\"`, `\"A\"`, `\"C\"`", kNoDefault, "required (`letter`)",
     "which of the seed's letters, built from boxes and slanted boxes"},
    {"width", "m", range::length, "and > 2 `stroke`", 0.100, "", "the letter's width L"},
    {"depth", "m", range::length, "", 0.030, "", "the letter's depth W (through the letter)"},
    {"stroke", "m", range::length, "", 0.030, "", "the width of every stroke, measured across it"},
    {"path", "", kAnyNumber, "an `.obj` or `.stl` file, relative to the scene", kNoDefault, "required (`file`)",
     "convex parts: one per OBJ `o`/`g` group; each connected component of each STL solid (ASCII or binary)"},
    {"centres", "m", kAnyNumber, "[[x, y, z], ...], 1 to 64", kNoDefault, "required (`spheres`)",
     "the centres of a clump of spheres of `radius`, overlapping or not"},
    {"semi_axes", "m", kAnyNumber, "[a, b, c], each > `radius`", kNoDefault, "required (`ellipsoid`)",
     "the grain's semi-axes along x, y, z: its core is the ellipsoid of semi-axes a − r, b − r, c − r, a smooth core "
     "(no vertices), so the grain's extent along each axis is the one given"},
    {"youngs_modulus", "Pa", range::modulus, "and the same in every `[[shape]]` and `[[species]]`", kNoDefault,
     "required under `hertz_mindlin`", "the bodies' one material"},
    {"poisson_ratio", "", {-0.99, 0.5, false, false}, "and the same in every table", kNoDefault,
     "required under `hertz_mindlin`", "the bodies' one material"},
};

constexpr std::string_view kPlacedBy = "required: one of `positions`, `count`, `file`";

const Field kBodies[] = {
    {"shape", "", kAnyNumber, "a `[[shape]]` name", kNoDefault, "", "the bodies' shape"},
    {"positions", "m", kAnyNumber, "[[x, y, z], ...]", kNoDefault, kPlacedBy, "centres of mass, one body each"},
    {"count", "", {1, 1e5, false, false}, "(integers)", kNoDefault, kPlacedBy,
     "bodies placed in `region`, which `count` requires"},
    {"region.", "", kAnyNumber, "", kNoDefault, "", "", &kRegionFields},
    {"arrangement", "", kAnyNumber, "`\"random\"`, `\"lattice\"`", kNoDefault, "`\"random\"`",
     "random: bounding spheres kept apart, clear of bodies placed before; lattice: a cubic lattice of bounding "
     "spheres (spacing 2.02 bounding radii) filled from the bottom of a box region, for dense pours"},
    {"seed", "", kAnyNumber, "integer ≥ 0", kNoDefault, "`run.seed` + the table's index",
     "the random placement's and orientations' seed; another seed is another pour"},
    {"orientation", "", kAnyNumber, "`\"identity\"`, `\"random\"`", kNoDefault, "`\"identity\"`",
     "the bodies' initial orientation"},
    {"velocity", "m/s", kAnyNumber, "[x, y, z]; zero when `fixed`", kNoDefault, "[0, 0, 0]", "initial velocity"},
    {"fixed", "", kAnyNumber, "true, false", kNoDefault, "false",
     "the bodies never move: floors, hopper bottoms, gates built of shapes; moving bodies meet them with the "
     "`[contact.wall]` parameters"},
    {"remove_at", "s", kTime, "", kNoDefault, "never",
     "time of the main stage (after `[settle]`) at which the bodies are removed and their springs dropped: a gate "
     "that opens"},
    {"group", "", {0, 1e6, false, false}, "(integers)", kNoDefault, "the table's index",
     "a column of the frames; the colour of pictures by group"},
    {"file", "", kAnyNumber, "a body frame CSV a run wrote, relative to the scene", kNoDefault, kPlacedBy,
     "restart: the frame's moving bodies of this shape with their pose, velocity and spin; `positions`, `count`, "
     "`orientation`, `velocity` and `fixed` are refused beside it"},
};

const Field kBodyOutput[] = {
    {"", "", kAnyNumber, "", kNoDefault, "", "", &kOutputTimesFields},  // frames: frames/frame_NNNNNN.csv
    {"picture_interval", "s", kTime, "and either 0, or ≥ `run.dt` and ≥ 1e-4", 0.0, "0 (none)",
     "a side view every interval, `pictures/time_SSSS.SSSS.png`"},
    {"picture_size", "px", {16, 8192, false, false}, "(integers)", 800, "", "the picture's longer side"},
    {"picture_colour", "", kAnyNumber, "`\"group\"`, `\"layer\"`, `\"shape\"`", kNoDefault, "`\"group\"`",
     "colour by group, by five layers of equal counts by height at the start of the main stage (blue and "
     "vermillion, as the seed's hopper), or by shape; the legend below the picture names the colours"},
    {"picture_view", "", kAnyNumber, "`\"z\"`, `\"x\"`", kNoDefault, "`\"z\"`",
     "look along -z (x to the right) or along +x (z to the right)"},
    {"frame_force", "", kAnyNumber, "false", kNoDefault, "false", "body frames hold no forces; true is refused"},
    {"frame_velocity", "", kAnyNumber, "true", kNoDefault, "true",
     "body frames always hold velocities; false is refused"},
    {"frame_angular_velocity", "", kAnyNumber, "true", kNoDefault, "true",
     "body frames always hold angular velocities; false is refused"},
    {"picture_angles", "", kAnyNumber, "—", kNoDefault, "—", "refused in a body scene; use `picture_interval`"},
    {"picture_speed_max", "", kAnyNumber, "—", kNoDefault, "—", "refused in a body scene; use `picture_colour`"},
};

const Field kBodyAnalysis[] = {
    {"outlet_height", "m", kHeight, "", kNoDefault, "none",
     "a height along -gravity; adds `remaining_fraction` to `series.csv`: moving bodies whose centre lies above it, "
     "over those moving at the start of the main stage"},
    {"species", "", kAnyNumber, "—", kNoDefault, "—",
     "refused in a body scene (the mixing measures compare grain species)"},
    {"mixing_cell", "", kAnyNumber, "—", kNoDefault, "—", "refused in a body scene"},
    {"mixing_min_grains", "", kAnyNumber, "—", kNoDefault, "—", "refused in a body scene"},
};

const Field kReposeRegion[] = {
    {"lo", "m", kAnyNumber, "[x, y, z], below `region.hi` on every axis", kNoDefault, "none (all bodies)",
     "a box of bodies to read the heap from (a band through the middle)"},
    {"hi", "m", kAnyNumber, "[x, y, z]", kNoDefault, "none", "the box's high corner"},
};

const Field kRepose[] = {
    {"name", "", kAnyNumber, "unique among the heaps", kNoDefault, "", "the key in `summary.json` `repose`"},
    {"geometry", "", kAnyNumber, "`\"heap\"`, `\"ridge\"`, `\"crater\"`", kNoDefault, "",
     "one flank radially about an axis, or two flanks across a ridge or a crater (what a flat-bottomed hopper "
     "leaves about its outlet)"},
    {"centre", "m", kAnyNumber, "[x, y, z]", kNoDefault, "required (`heap`); refused otherwise",
     "a point on the heap's vertical axis"},
    {"across", "", kAnyNumber, "a direction, not vertical", kNoDefault, "required (`ridge`, `crater`); refused for `heap`",
     "the horizontal direction across the ridge or crater"},
    {"column", "m", range::length, "", kNoDefault, "", "the width of a column of horizontal distance"},
    {"rank", "", {1, 1000, false, false}, "(integers)", 3, "", "which highest grain top of a column is its surface"},
    {"lower", "", {0, 1, false, false}, "and below `upper`", 0.15, "",
     "the fitted part of a flank starts here (fraction of its height range)"},
    {"upper", "", {0, 1, false, false}, "", 0.85, "", "and ends here"},
    {"region.", "", kAnyNumber, "", kNoDefault, "", "", &kReposeRegionFields},
};

const Field kSink[] = {
    {"height", "m", kHeight, "and below `analysis.outlet_height`", kNoDefault, "",
     "a height along -gravity: a moving body whose centre falls below it is removed, so a hopper's discharge needs "
     "no floor"},
};

}  // namespace

const FieldTable kShapeFields{"[[shape]]", "composite-grains.md", kShape};
const FieldTable kBodiesFields{"[[bodies]]", "composite-grains.md", kBodies};
const FieldTable kBodyOutputFields{"[output]", "composite-grains.md", kBodyOutput};
const FieldTable kBodyAnalysisFields{"[analysis]", "composite-grains.md", kBodyAnalysis};
const FieldTable kReposeFields{"[[analysis.repose]]", "composite-grains.md", kRepose};
const FieldTable kReposeRegionFields{"region", "", kReposeRegion};
const FieldTable kSinkFields{"[sink]", "composite-grains.md", kSink};

std::vector<const FieldTable*> body_field_tables() {
  return {&kShapeFields,        &kBodiesFields, &kBodyOutputFields, &kBodyAnalysisFields,
          &kReposeFields, &kSinkFields};
}

}  // namespace gf

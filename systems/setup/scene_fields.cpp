#include "systems/setup/scene_fields.hpp"

#include <limits>

#include "engine/output_times.hpp"
#include "systems/contact/laws.hpp"
#include "systems/walls/wall_fields.hpp"

namespace gf {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

const Field kRegion[] = {
    {"shape", "", kAnyNumber, "`\"box\"` or `\"cylinder\"`", kNoDefault, "", "the region's shape"},
    {"lo", "m", kAnyNumber, "three numbers, each below `hi`'s", kNoDefault, "required for a box", "the box's lower corner"},
    {"hi", "m", kAnyNumber, "three numbers, each above `lo`'s", kNoDefault, "required for a box", "the box's upper corner"},
    {"center", "m", kAnyNumber, "three numbers", kNoDefault, "required for a cylinder", "the cylinder's centre"},
    {"axis", "", kAnyNumber, "non-zero vector", kNoDefault, "required for a cylinder", "the cylinder's axis direction"},
    {"radius", "m", range::length, "", kNoDefault, "required for a cylinder", "the cylinder's radius"},
    {"length", "m", range::length, "", kNoDefault, "required for a cylinder", "the cylinder's length, half to each side of the centre"},
    {"max_height", "m", kAnyNumber, "any number; cylinders only", kInf, "no limit",
     "keeps the part whose height above the centre (against gravity) is at most this (0: the lower half)"},
};

const Field kDiameter[] = {
    {"distribution", "", kAnyNumber, "`\"discrete\"`, `\"normal\"`, `\"lognormal\"`, `\"file\"`", kNoDefault, "",
     "how each grain's diameter is drawn (see *Size distributions* below)"},
    {"mean", "m", range::diameter, "", kNoDefault, "required for normal and lognormal",
     "the mean diameter (of the law before its cut-offs)"},
    {"sd", "m", {0, 100, true, false}, "", kNoDefault, "required for normal and lognormal",
     "the diameter's standard deviation (of the law before its cut-offs)"},
    {"min", "m", range::diameter, "", kNoDefault, "three standard deviations below",
     "the smallest diameter drawn: mean − 3 sd, or exp(μ − 3σ) for lognormal"},
    {"max", "m", range::diameter, "", kNoDefault, "three standard deviations above",
     "the largest diameter drawn: mean + 3 sd, or exp(μ + 3σ) for lognormal"},
    {"diameters", "m", range::diameter, "(a list)", kNoDefault, "required for discrete", "the sizes of a discrete distribution"},
    {"fractions", "", {0, 1e12, false, false}, "(a list as long as `diameters`)", kNoDefault, "required for discrete",
     "each size's share, by number or by mass; any scale (percent is fine)"},
    {"by", "", kAnyNumber, "`\"number\"`, `\"mass\"`", kNoDefault, "`\"number\"`",
     "what the fractions count (discrete and file)"},
    {"file", "", kAnyNumber, "a path, relative to the scene file", kNoDefault, "required for file",
     "a table of `diameter, fraction` rows (m, share), a header line of names allowed"},
};

const Field kFill[] = {
    {"kind", "", kAnyNumber, "`\"random\"`, `\"file\"`", kNoDefault, "", "random placement in a region, or a state file"},
    {"region.", "", kAnyNumber, "", kNoDefault, "", "", &kRegionFields},
    {"count.<species>", "", {0, 1e8, false, false}, "(integers)", kNoDefault, "required, or `volume_fraction`",
     "grains of that species; give exactly one of `count` and `volume_fraction`"},
    {"volume_fraction.<species>", "", {0, 0.74, true, false}, "", kNoDefault, "required, or `count`",
     "solid volume fraction of that species in the region"},
    {"seed", "", kAnyNumber, "integer ≥ 0", kNoDefault, "`run.seed` + the fill's index", "random seed of the placement"},
    {"path", "", kAnyNumber, "path of a CSV file", kNoDefault, "required (file)",
     "the state file, relative to the scene file"},
    {"types.<type>", "", kAnyNumber, "a species name", kNoDefault, "required (file), at least one",
     "maps the file's integer `type` column to a species, e.g. `types = { 1 = \"small\", 2 = \"large\" }`"},
};

const Field kFeed[] = {
    {"mass_rate", "kg/s", {0, 1e6, true, false}, "", kNoDefault, "",
     "mass fed per second, all species together; one event may place at most 1,000,000 grains (mass_rate × interval / "
     "grain mass)"},
    {"fractions.<species>", "", {0, 1, false, false}, "and summing to 1 (within 1e-6)", kNoDefault, "",
     "inline table of species name = mass fraction, e.g. `{ sand = 0.7, salt = 0.3 }`; at least one species"},
    {"region.", "", kAnyNumber, "", kNoDefault, "", "", &kRegionFields},
    {"velocity", "m/s", kAnyNumber, "three numbers", kNoDefault, "[0, 0, 0]", "velocity of a new grain"},
    {"start", "s", range::time_span, "", 0.0, "", "time of the first feed event"},
    {"stop", "s", range::time_step, "and > `start`", kInf, "no end", "no events after this time"},
    {"interval", "s", range::time_step, "and ≥ `run.dt`", 0.01, "", "time between feed events"},
    {"seed", "", kAnyNumber, "0 to 2^63 − 1", kNoDefault, "`run.seed` + 1000 + the feed's index",
     "seed of the placement generator"},
};

const Field kOutlet[] = {
    {"region.", "", kAnyNumber, "", kNoDefault, "", "", &kRegionFields},
    {"interval", "s", range::time_step, "and ≥ `run.dt`", 0.01, "", "time between checks"},
};

const Field kLayers[] = {
    {"inlet", "m", kAnyNumber, "three numbers", kNoDefault, "", "the point from which distances are measured"},
    {"axis", "", kAnyNumber, "non-zero vector", kNoDefault, "", "direction from the inlet along the mixer"},
    {"distances", "m", kAnyNumber, "1 to 10,000 numbers", kNoDefault, "", "distances L of the layers from the inlet"},
    {"thickness", "m", range::length, "", kNoDefault, "the largest species diameter",
     "thickness of a layer (the seed's choice is the default)"},
    {"cell", "m", range::length, "", kNoDefault, "", "edge of the square sample cells in a layer"},
    {"min_grains", "", {1, 1e6, false, false}, "(integers)", 5, "",
     "cells with fewer grains (visits, over the pool) are left out"},
    {"interval", "s", range::time_step, "and ≥ `run.dt`", kNoDefault, "", "time between samples"},
    {"pool", "", {1, 1e6, false, false}, "(integers)", 1, "", "samples pooled per row of `layers.csv`"},
};

const Field kRun[] = {
    {"dt", "s", range::time_step, "", kNoDefault, "",
     "the time step. It must not exceed `dt_safety` of the contact law's smallest time-step term (printed by "
     "`grainflow check`) unless `allow_unstable_dt`"},
    {"duration", "s", range::time_span, "and at most 1e15 steps", kNoDefault, "required, or `end_angle`",
     "length of the main stage; give exactly one of `duration` and `end_angle`"},
    {"end_angle", "rad", range::angle_span, "and at most 1e15 steps", kNoDefault, "required, or `duration`",
     "length of the main stage as the rotation angle of the first rotating wall (needs a wall with `omega` ≠ 0)"},
    {"skin", "m", range::length, "", kNoDefault, "", "Verlet skin: the neighbour list holds pairs closer than r_i + r_j + skin"},
    {"gravity", "m/s²", kAnyNumber, "three numbers, magnitude ≤ 1e6", kNoDefault, "`[0, -9.81, 0]`", "gravity"},
    {"dt_safety", "", {0, 1, true, false}, "", 0.1, "", "`dt` may be at most this fraction of the smallest time-step term"},
    {"allow_unstable_dt", "", kAnyNumber, "true, false", kNoDefault, "false", "run even when `dt` exceeds the limit"},
    {"max_overlap", "", {0, 1, true, false}, "", 0.1, "",
     "largest overlap, as a fraction of the smaller diameter; beyond it the run stops (checked in every step, see "
     "[the step](model.md#stability-checks))"},
    {"seed", "", kAnyNumber, "integer 0 to 2^63 − 1", 1, "",
     "base seed of random fills (each fill adds its index) and feeds"},
};

const Field kSpecies[] = {
    {"name", "", kAnyNumber, "unique text", kNoDefault, "", "the name fills, pairs and `[analysis]` refer to"},
    {"diameter", "m", range::diameter, "a number, or a table of the keys below", kNoDefault, "",
     "grain diameter, or a size distribution each grain draws its own from"},
    {"diameter.", "", kAnyNumber, "", kNoDefault, "", "", &kDiameterFields},
    {"density", "kg/m³", range::density, "", kNoDefault, "",
     "solid density; mass and moment of inertia (2/5 m r²) follow"},
    {"rotates", "", kAnyNumber, "true, false", kNoDefault, "true",
     "false: the grains only translate and their torques are not integrated; when no species rotates the grains "
     "have no spin columns at all. The representative-volume law needs false in every species"},
    {"", "", kAnyNumber, "", kNoDefault, "", "", &kHertzMaterialFields},
};

const Field kContact[] = {
    {"model", "", kAnyNumber, "a law's name: `\"linear_spring_dashpot\"`, `\"hertz_mindlin\"`, `\"representative_volume\"`",
     kNoDefault, "", "the contact law; the law's own keys follow in its table below"},
};

const Field kContactPair[] = {
    {"species_a", "", kAnyNumber, "a species name", kNoDefault, "", "one species of the pair"},
    {"species_b", "", kAnyNumber, "a species name", kNoDefault, "", "the other (may be the same)"},
};

const Field kPeriodic[] = {
    {"x", "m", kAnyNumber, "`[min, max]`, max > min, length > 2 (largest diameter + skin) + skin", kNoDefault,
     "not periodic", "the periodic extent along x"},
    {"y", "m", kAnyNumber, "as `x`", kNoDefault, "not periodic", "the periodic extent along y"},
    {"z", "m", kAnyNumber, "as `x`", kNoDefault, "not periodic", "the periodic extent along z"},
};

const Field kOutput[] = {
    {"", "", kAnyNumber, "", kNoDefault, "", "", &kOutputTimesFields},
    {"frame_velocity", "", kAnyNumber, "true, false", kNoDefault, "true", "frames hold `velocity` and `speed`"},
    {"frame_angular_velocity", "", kAnyNumber, "true, false", kNoDefault, "true", "frames hold `angular_velocity`"},
    {"frame_force", "", kAnyNumber, "true, false", kNoDefault, "false", "frames hold `force`"},
    {"picture_angles", "rad", kAnyNumber, "list of numbers ≥ 0, at least 0.01 apart", kNoDefault, "none",
     "draw a picture when the first rotating wall reaches each angle, e.g. `[2, 10, 18, 30]`"},
    {"picture_interval", "rad", range::angle_span, "0, or ≥ 0.01", 0.0, "", "draw a picture every interval of rotation; 0: none"},
    {"picture_colour", "", kAnyNumber, "`\"species\"`, `\"speed\"`", kNoDefault, "`\"species\"`",
     "colour grains by species or by speed"},
    {"picture_size", "px", {16, 8192, false, false}, "(integers)", 800, "", "picture width and height"},
    {"picture_speed_max", "m/s", range::speed, "", 0.5, "", "the speed at the top of the speed colours"},
};

const Field kAnalysis[] = {
    {"species", "", kAnyNumber, "a species name", kNoDefault, "the larger (the first on equal diameters)",
     "the species whose fraction the segregation, Lacey and radial indices and the pattern classifier follow"},
    {"mixing_cell", "m", range::length, "and at least one diameter of `species`", kNoDefault,
     "three diameters of `species`", "the edge of Lacey's cubic cells"},
    {"mixing_min_grains", "", {2, 1e6, false, false}, "(integers)", 10, "",
     "cells with fewer grains are left out of Lacey's index"},
    {"layers", "", kAnyNumber, "a table", kNoDefault, "none",
     "transverse layers of a continuous mixer: see [continuous mixers](mixers.md)"},
};

const Field kSettle[] = {
    {"time", "s", range::time_span, "and at most 1e15 steps", kNoDefault, "", "simulated time of settling"},
};

}  // namespace

const FieldTable kRegionFields{"region", "", kRegion};
const FieldTable kDiameterFields{"diameter", "", kDiameter};
const FieldTable kFillFields{"[[fill]]", "scene-files.md", kFill};
const FieldTable kFeedFields{"[[feed]]", "mixers.md", kFeed};
const FieldTable kOutletFields{"[[outlet]]", "mixers.md", kOutlet};
const FieldTable kSettleFields{"[settle]", "scene-files.md", kSettle};
const FieldTable kRunFields{"[run]", "scene-files.md", kRun};
const FieldTable kSpeciesFields{"[[species]]", "scene-files.md", kSpecies};
const FieldTable kContactFields{"[contact]", "scene-files.md", kContact};
const FieldTable kContactPairFields{"[[contact.pair]]", "scene-files.md", kContactPair};
const FieldTable kPeriodicFields{"[periodic]", "scene-files.md", kPeriodic};
const FieldTable kOutputFields{"[output]", "scene-files.md", kOutput};
const FieldTable kAnalysisFields{"[analysis]", "scene-files.md", kAnalysis};
const FieldTable kLayersFields{"[analysis.layers]", "mixers.md", kLayers};

std::vector<const FieldTable*> scene_field_tables() {
  std::vector<const FieldTable*> all{&kRunFields, &kSpeciesFields, &kContactFields};
  for (const FieldTable* t : law_field_tables()) all.push_back(t);
  for (const FieldTable* t : {&kContactPairFields, &kWallFields, &kFillFields, &kPeriodicFields, &kSettleFields,
                              &kOutputFields, &kAnalysisFields, &kFeedFields, &kOutletFields, &kLayersFields})
    all.push_back(t);
  return all;
}

}  // namespace gf

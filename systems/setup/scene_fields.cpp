#include "systems/setup/scene_fields.hpp"

#include <limits>

namespace gf {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr Range kPositive{0, kInf, true, true};
constexpr Range kNonNegative{0, kInf, false, true};

const Field kRegion[] = {
    {"shape", "", kAnyNumber, "`\"box\"` or `\"cylinder\"`", kNoDefault, "", "the region's shape"},
    {"lo", "m", kAnyNumber, "three numbers, each below `hi`'s", kNoDefault, "required for a box", "the box's lower corner"},
    {"hi", "m", kAnyNumber, "three numbers, each above `lo`'s", kNoDefault, "required for a box", "the box's upper corner"},
    {"center", "m", kAnyNumber, "three numbers", kNoDefault, "required for a cylinder", "the cylinder's centre"},
    {"axis", "", kAnyNumber, "non-zero vector", kNoDefault, "[0, 0, 1]", "the cylinder's axis direction"},
    {"radius", "m", kPositive, "", kNoDefault, "required for a cylinder", "the cylinder's radius"},
    {"length", "m", kPositive, "", kNoDefault, "required for a cylinder", "the cylinder's length, half to each side of the centre"},
    {"max_height", "m", kAnyNumber, "any number; cylinders only", kInf, "no limit",
     "keeps the part whose height above the centre (against gravity) is at most this (0: the lower half)"},
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
    {"start", "s", kNonNegative, "", 0.0, "", "time of the first feed event"},
    {"stop", "s", kPositive, "and > `start`", kInf, "no end", "no events after this time"},
    {"interval", "s", kPositive, "and ≥ `run.dt`", 0.01, "", "time between feed events"},
    {"seed", "", kAnyNumber, "0 to 2^63 − 1", kNoDefault, "`run.seed` + 1000 + the feed's index",
     "seed of the placement generator"},
};

const Field kOutlet[] = {
    {"region.", "", kAnyNumber, "", kNoDefault, "", "", &kRegionFields},
    {"interval", "s", kPositive, "and ≥ `run.dt`", 0.01, "", "time between checks"},
};

const Field kLayers[] = {
    {"inlet", "m", kAnyNumber, "three numbers", kNoDefault, "", "the point from which distances are measured"},
    {"axis", "", kAnyNumber, "non-zero vector", kNoDefault, "[1, 0, 0]", "direction from the inlet along the mixer"},
    {"distances", "m", kAnyNumber, "1 to 10,000 numbers", kNoDefault, "", "distances L of the layers from the inlet"},
    {"thickness", "m", {0, 1e3, true, false}, "", kNoDefault, "the largest species diameter",
     "thickness of a layer (the seed's choice is the default)"},
    {"cell", "m", {0, 1e3, true, false}, "", kNoDefault, "", "edge of the square sample cells in a layer"},
    {"min_grains", "", {1, 1e6, false, false}, "(integers)", 5, "",
     "cells with fewer grains (visits, over the pool) are left out"},
    {"interval", "s", kPositive, "and ≥ `run.dt`", kNoDefault, "", "time between samples"},
    {"pool", "", {1, 1e6, false, false}, "(integers)", 1, "", "samples pooled per row of `layers.csv`"},
};

const Field kSettle[] = {
    {"time", "s", kNonNegative, "and at most 1e15 steps", kNoDefault, "", "simulated time of settling"},
};

}  // namespace

const FieldTable kRegionFields{"region", "", kRegion};
const FieldTable kFillFields{"[[fill]]", "scene-files.md", kFill};
const FieldTable kFeedFields{"[[feed]]", "mixers.md", kFeed};
const FieldTable kOutletFields{"[[outlet]]", "mixers.md", kOutlet};
const FieldTable kSettleFields{"[settle]", "scene-files.md", kSettle};
const FieldTable kLayersFields{"[analysis.layers]", "mixers.md", kLayers};

std::vector<const FieldTable*> scene_field_tables() {
  return {&kFillFields, &kSettleFields, &kFeedFields, &kOutletFields, &kLayersFields};
}

}  // namespace gf

#include "systems/coupling/coupling_fields.hpp"

namespace gf {

namespace {

// The drag laws' names as drag_laws() lists them, the first the default (tests/coupled_step_test.cpp).
const Field kCoupling[] = {
    {"smoothing_radius", "m", range::length, "and at least `l0`", kNoDefault, "",
     "radius h over which a grain's volume and force are shared with the nodes"},
    {"substeps", "", {0, 1e6, false, false}, "(integers; 0: computed), and at least 1 with `fixed_grains`", 0,
     "computed (1 with `fixed_grains`)", "DEM steps k per liquid step"},
    {"drag", "", kAnyNumber, "`\"ergun_wen_yu\"`, `\"blend\"`", kNoDefault, "`\"ergun_wen_yu\"`", "drag law"},
    {"rotational_drag", "", kAnyNumber, "`\"none\"`, `\"dennis\"`", kNoDefault, "`\"none\"`",
     "the liquid's torque on a spinning grain (none in the seed)"},
    {"shear_lift", "", kAnyNumber, "`\"none\"`, `\"saffman_mei\"`", kNoDefault, "`\"none\"`",
     "Saffman's shear lift with Mei's correction (none in the seed)"},
    {"spin_lift", "", kAnyNumber, "`\"none\"`, `\"oesterle_bui_dinh\"`", kNoDefault, "`\"none\"`",
     "the Magnus lift of a spinning grain, Oesterlé and Bui Dinh's coefficient (none in the seed)"},
    {"min_liquid_fraction", "", {0, 1, true, false}, "", 0.2, "", "floor of the nodes' liquid fraction"},
    {"share_with", "", kAnyNumber, "`\"all_nodes\"`, `\"fluid_nodes\"`", kNoDefault, "`\"all_nodes\"`",
     "which nodes share a grain"},
    {"fixed_grains", "", kAnyNumber, "true, false", kNoDefault, "false", "hold the grains where the fills put them"},
    {"modified_pressure", "", kAnyNumber, "true, false; a `box` filled by one `[[fluid]]` block", kNoDefault, "false",
     "solve for the pressure less its hydrostatic part"},
    {"averaged", "", kAnyNumber, "true, false", kNoDefault, "false", "locally averaged liquid (seed 003's model B)"},
};

}  // namespace

const FieldTable kCouplingFields{"[coupling]", "liquid.md", kCoupling};

}  // namespace gf

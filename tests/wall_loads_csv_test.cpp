// The loads the walls receive (systems/walls/walls.hpp) and walls.csv (systems/output/wall_loads_csv.hpp):
//  - a settled bed: the walls together carry its weight less its collective motion (momentum balance:
//    the mean force on the walls is M g + dp/dt, y up), the floor nearly all of it, and a layer at rest
//    exactly its weight;
//  - a turning drum: the balance of angular momentum about the axis, sum over the steps of (the walls'
//    moment on the grains + the weight's moment) dt = L(end) - L(start), holds to rounding of the
//    integrator, and at steady rotation the torque on the drum equals the bed's moment of weight about
//    the axis (the shift of the bed's angular momentum over the window is a fraction of a percent of
//    it; the test bounds the difference by that shift plus 1 %). Its drive's power is omega times it;
//  - the vectorised and scalar drivers give the same loads;
//  - walls.csv: a column group per wall, a row per series row, the drum's power positive; in a liquid, the
//    floor under grains at rest carries their weight less Archimedes' buoyancy.
#include "systems/setup/dem_simulation.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "systems/contact/laws.hpp"
#include "systems/output/wall_loads_csv.hpp"
#include "systems/walls/wall_contact.hpp"
#include "tests/test_support.hpp"

using gf::DemSimulation;
using gf::Grains;
using gf::Vec3d;

namespace {

// The sums of the walls' loads (force, moment, power on the grains) over the steps from `before`.
struct Window {
  std::vector<gf::WallLoad> sum;
  std::int64_t steps = 0;
};
Window since(const gf::WallLoads& now, const gf::WallLoads& before) {
  Window w;
  w.steps = now.steps - before.steps;
  for (std::size_t k = 0; k < now.sum.size(); ++k) {
    gf::WallLoad l;
    l.force = now.sum[k].force - before.sum[k].force;
    l.moment = now.sum[k].moment - before.sum[k].moment;
    l.power = now.sum[k].power - before.sum[k].power;
    w.sum.push_back(l);
  }
  return w;
}

double total_mass(const Grains& g) {
  double m = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i) m += g.mass.m[i];
  return m;
}

// Angular momentum about the z axis through the origin: orbital plus spin (I = 0.4 m r^2).
double angular_momentum_z(const Grains& g) {
  double l = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i)
    l += g.mass.m[i] * (g.pos.x[i] * g.vel.y[i] - g.pos.y[i] * g.vel.x[i]) +
         0.4 * g.mass.m[i] * g.radius.r[i] * g.radius.r[i] * g.omega.z[i];
  return l;
}

// Vertical momentum of the grains, kg m/s.
double momentum_y(const Grains& g) {
  double p = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i) p += g.mass.m[i] * g.vel.y[i];
  return p;
}

// The mean vertical force on the walls over `steps` steps from the state after settling, with the
// floor's share and the grains' momentum change over the window (M g - F = dp/dt).
struct BedLoads {
  double walls = 0, floor = 0, weight = 0, dp_dt = 0;
};
BedLoads bed_loads(int small, int large, int steps) {
  DemSimulation sim = DemSimulation::from_text(gf::test::binary_box_scene(small, large) + "[settle]\ntime = 0.25\n");
  sim.settle();
  const gf::WallLoads before = sim.world().resources.get<gf::Walls>().loads;
  const double p0 = momentum_y(sim.grains());
  sim.advance(steps);
  const gf::Walls& walls = sim.world().resources.get<gf::Walls>();
  const Window w = since(walls.loads, before);
  REQUIRE(w.steps == steps);
  REQUIRE(walls.list[2].name == "box-y");
  BedLoads b;
  for (const gf::WallLoad& l : w.sum) b.walls -= l.force.y / steps;  // on the walls: downward, negative
  b.floor = -w.sum[2].force.y / steps;
  b.weight = total_mass(sim.grains()) * 9.81;
  b.dp_dt = (momentum_y(sim.grains()) - p0) / (steps * sim.world().clock.dt);
  return b;
}

// The comma-separated fields of one CSV line.
std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) out.push_back(f);
  return out;
}

}  // namespace

TEST_CASE("a settled bed's weight rests on the walls, and on the floor") {
  // A bed of 310 grains: the walls carry M g + dp/dt (y up), the grains' collective motion that seed 000's soft
  // springs leave after 0.25 s (3 % of the weight over this window); the remainder is the trapezoid of
  // the integrator's kicks against the sum of the steps' forces, (F_0 - F_N) / 2N, under 1e-4 of the weight.
  const BedLoads bed = bed_loads(300, 10, 2000);
  CHECK(-bed.walls == Approx(bed.weight + bed.dp_dt).epsilon(1e-4));
  CHECK(bed.floor / bed.walls > 0.99);  // the side walls carry a shallow bed's friction only
  // Twenty grains at rest on the floor: the floor carries their weight to rounding.
  const BedLoads layer = bed_loads(20, 0, 2000);
  CHECK(std::abs(layer.dp_dt) < 1e-9 * layer.weight);
  CHECK(-layer.floor == Approx(layer.weight).epsilon(1e-9));
}

TEST_CASE("a turning drum's torque balances the bed's moment of weight about its axis") {
  DemSimulation sim = DemSimulation::from_text(gf::test::small_drum_scene(9.81, "", 0.1));
  sim.settle();
  sim.advance(10000);  // 0.1 s at 3 rad/s: the bed reaches its steady slope
  const Grains& g = sim.grains();
  const gf::WallLoads before = sim.world().resources.get<gf::Walls>().loads;
  const double l0 = angular_momentum_z(g), dt = sim.world().clock.dt;
  double weight_moment = 0.0;  // sum over the steps of the weight's moment about z, sum m (x g_y - y g_x)
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    double m = 0.0;
    for (std::size_t i = 0; i < g.n_owned; ++i) m += g.mass.m[i] * g.pos.x[i] * -9.81;
    weight_moment += m;
    sim.advance(1);
  }
  const Window w = since(sim.world().resources.get<gf::Walls>().loads, before);
  REQUIRE(w.steps == n);
  double walls_on_grains = 0.0, power = 0.0;
  for (const gf::WallLoad& l : w.sum) walls_on_grains += l.moment.z, power += l.power;
  const double dl = angular_momentum_z(g) - l0;
  const double mean_weight = weight_moment / n, mean_walls = walls_on_grains / n, shift = dl / (n * dt);
  INFO("weight " << mean_weight << " N m, walls on grains " << mean_walls << ", dL/T " << shift);
  CHECK(mean_walls + mean_weight == Approx(shift).margin(2e-3 * std::abs(mean_weight)));
  const double torque_on_drum = -mean_walls;
  CHECK(torque_on_drum == Approx(mean_weight).margin(std::abs(shift) + 0.01 * std::abs(mean_weight)));
  // The drive lifts the bed: power omega times the torque it applies, positive.
  CHECK(power / n == Approx(3.0 * mean_walls).epsilon(1e-9));
  CHECK(power > 0.0);
}

TEST_CASE("the vectorised and scalar wall drivers give the same loads") {
  DemSimulation sim = DemSimulation::from_text(gf::test::small_drum_scene(9.81, "", 0.05));
  sim.settle();
  sim.advance(500);
  Grains& g = sim.grains();
  gf::Walls a = sim.world().resources.get<gf::Walls>(), b = a;
  gf::WallHistory ha = g.extras.get<gf::WallHistory>(), hb = ha;
  const gf::ContactTable& table = sim.world().resources.get<gf::ContactTable>();
  const double t = sim.world().clock.t, dt = sim.world().clock.dt;
  gf::compute_wall_forces<gf::LinearSpringDashpot>(g, a, ha, table, dt, t);
  gf::compute_wall_forces_scalar<gf::LinearSpringDashpot>(g, b, hb, table, dt, t);
  REQUIRE(a.loads.now.size() == 3);
  // The two drivers add the same terms in different orders. An end wall's moment about the axis and its
  // power are sums of terms of size |F| R (and omega |F| R) that largely cancel, so their round-off is
  // measured against that size, R = 12 mm the drum's radius and omega = 3 rad/s.
  for (std::size_t w = 0; w < 3; ++w) {
    const gf::WallLoad& la = a.loads.now[w];
    const gf::WallLoad& lb = b.loads.now[w];
    const double f = std::sqrt(la.force.x * la.force.x + la.force.y * la.force.y + la.force.z * la.force.z) + 1e-12;
    INFO("wall " << w << ": moment.z " << la.moment.z << " and " << lb.moment.z << ", power " << la.power << " and " << lb.power);
    CHECK(std::abs(la.force.y - lb.force.y) < 1e-12 * f);
    CHECK(std::abs(la.moment.z - lb.moment.z) < 1e-12 * (std::abs(la.moment.z) + 0.012 * f));
    CHECK(std::abs(la.power - lb.power) < 1e-12 * (std::abs(la.power) + 3.0 * 0.012 * f));
  }
}

TEST_CASE("walls.csv holds a row per series row and seven columns per wall") {
  const gf::test::TempDir dir("walls_csv");
  const std::filesystem::path scene = dir.path / "drum.toml", out = dir.path / "run";
  std::ofstream(scene) << gf::test::small_drum_scene(9.81, "", 0.02);
  const gf::test::Exit e = gf::test::run_cli(dir, "run " + gf::test::quote(scene.string()) + " --out " +
                                                       gf::test::quote(out.string()) + " --quiet");
  REQUIRE(e.code == 0);
  const std::vector<std::string> rows = gf::test::read_lines(out / "walls.csv");
  const std::vector<std::string> series = gf::test::read_lines(out / "series.csv");
  REQUIRE(rows.size() == series.size());
  CHECK(rows[0].rfind("time,drum.fx,drum.fy,drum.fz,drum.tx,drum.ty,drum.tz,drum.power,drum-end-.fx", 0) == 0);
  CHECK(std::count(rows[0].begin(), rows[0].end(), ',') == 3 * 7);
  CHECK(gf::wall_load_columns({"a", "a", "b,c"}) == std::vector<std::string>{"a", "a-2", "b_c"});
}

TEST_CASE("coupled walls.csv: grains at rest on a liquid-filled tank's floor weigh on it less Archimedes' buoyancy",
          "[walls][coupled][cli]") {
  // Three 2 mm glass grains poured just above the floor of the water tank settle within 0.1 s; over the last
  // 0.1 s of 0.3 s the floor carries 3 (rho_p - rho_l) V g (the walls' loads are what the DEM sub-steps'
  // contacts put on them). Measured: 1.003 of it, single rows 0.992 to 1.012 (the liquid's pressure noise at
  // the grains); 2 % bounds the mean. The other faces carry nothing.
  gf::test::TempDir dir("coupled_walls");
  const std::string file = dir.write("coupled.toml", gf::test::coupled_tank_scene("substeps = 16\nsmoothing_radius = 0.0075\n",
                                                                                    "[output]\nseries_interval = 0.01\n"))
                               .string();
  const gf::test::Exit run = gf::test::run_cli(
      dir, "run " + gf::test::quote(file) + " --out " + gf::test::quote((dir.path / "run").string()) +
               " --quiet --set run.duration=0.3 --set 'fill.0.region.lo=[0.008, 0.001, 0.008]'"
               " --set 'fill.0.region.hi=[0.022, 0.004, 0.022]'");
  INFO(run.err);
  REQUIRE(run.code == 0);
  const std::vector<std::string> lines = gf::test::read_lines(dir.path / "run" / "walls.csv");
  REQUIRE(lines.size() == 32);  // the header and rows at 0, 0.01, ..., 0.3 s
  const std::vector<std::string> head = split_fields(lines[0]);
  const auto column = [&](const std::string& name) {
    for (std::size_t c = 0; c < head.size(); ++c)
      if (head[c] == name) return c;
    FAIL("walls.csv has no column " << name);
    return std::size_t(0);
  };
  const double v = std::numbers::pi / 6.0 * 8e-9, want = -3.0 * (2500.0 - 1000.0) * v * 9.81;
  double floor = 0.0, others = 0.0;
  for (std::size_t r = 22; r < 32; ++r) {
    const std::vector<std::string> f = split_fields(lines[r]);
    floor += std::stod(f[column("box-y.fy")]) / 10.0;
    for (const char* w : {"box+y.fy", "box-x.fx", "box+x.fx", "box-z.fz", "box+z.fz"}) others += std::abs(std::stod(f[column(w)]));
  }
  CHECK(floor == Approx(want).epsilon(0.02));
  CHECK(others == 0.0);
}

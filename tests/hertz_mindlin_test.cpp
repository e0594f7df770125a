// Hertz-Mindlin no-slip (systems/contact/hertz_mindlin.hpp) through the whole pipeline (scene reader,
// contact table, pair and wall drivers, integrator), against the Chung & Ooi (2011, Granular Matter
// 13:643) benchmark tests as the LAMMPS and Yade suites run them:
//   T1 two identical glass spheres head-on, T2 a sphere on a rigid plane, T3 restitution on a plane,
//   T4 oblique impact on a plane (tangential restitution and rebound spin in gross sliding).
// With GRAINFLOW_RESULTS set to a folder, each case also writes its figures to chung_ooi.csv there
// (studies/contact/chung_ooi_table.py turns that file into the README's table).
#include <catch2/catch.hpp>

#include <cstring>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <string>

#include "systems/contact/hertz_mindlin.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/setup/dem_checkpoint.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

using gf::DemSimulation;

namespace {

struct Material {
  double radius, youngs, poisson, density;
};
// Chung & Ooi's materials.
constexpr Material kGlass{0.01, 4.8e10, 0.20, 2800.0};
constexpr Material kAlAlloy{0.1, 7.0e10, 0.30, 2699.0};
constexpr Material kAl2O3{0.0025, 3.8e11, 0.23, 4000.0};

// One species of `m` with Hertz-Mindlin, no gravity, the given time step; walls as TOML text.
std::string scene(const Material& m, double dt, int count, double restitution, double friction,
                  const std::string& walls, const std::string& wall_contact = "") {
  std::ostringstream s;
  s.precision(17);
  const double box = 10.0 * m.radius;
  s << "[run]\ndt = " << dt << "\nduration = 1.0\nskin = " << 0.05 * m.radius << "\ngravity = [0.0, 0.0, 0.0]\n"
    << "[[species]]\nname = \"s\"\ndiameter = " << 2 * m.radius << "\ndensity = " << m.density
    << "\nyoungs_modulus = " << m.youngs << "\npoisson_ratio = " << m.poisson << "\n"
    << "[contact]\nmodel = \"hertz_mindlin\"\nrestitution = " << restitution << "\nfriction = " << friction << "\n"
    << wall_contact << walls << "[[fill]]\nkind = \"random\"\n"
    << "region = { shape = \"box\", lo = [" << -box << ", " << m.radius * 1.5 << ", " << -box << "], hi = [" << box
    << ", " << box << ", " << box << "] }\ncount = { s = " << count << " }\n";
  return s.str();
}
const std::string kFloor = "[[wall]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n";

void place(gf::Grains& g, std::size_t i, gf::V3<double> x, gf::V3<double> v) {
  g.pos.x[i] = x.x, g.pos.y[i] = x.y, g.pos.z[i] = x.z;
  g.vel.x[i] = v.x, g.vel.y[i] = v.y, g.vel.z[i] = v.z;
  g.omega.x[i] = g.omega.y[i] = g.omega.z[i] = 0.0;
}

// What one impact shows: peak force, largest overlap, contact duration, and the state after it.
struct Impact {
  double peak_force = 0, max_overlap = 0, duration = 0;
  gf::V3<double> v_after{0, 0, 0}, w_after{0, 0, 0};
};

// Steps until the contact has opened again; overlap(g) is the overlap of the contact watched,
// force(g) the magnitude of the contact force on row 0.
template <class Overlap, class Force>
Impact run_impact(DemSimulation& sim, Overlap overlap, Force force, std::int64_t max_steps) {
  Impact r;
  const double dt = sim.world().clock.dt;
  std::int64_t touching = 0;
  bool opened = false;
  for (std::int64_t k = 0; k < max_steps && !opened; ++k) {
    sim.advance(1);
    const gf::Grains& g = sim.grains();
    const double d = overlap(g);
    if (d > 0) {
      ++touching;
      r.max_overlap = std::max(r.max_overlap, d);
      r.peak_force = std::max(r.peak_force, force(g));
    } else if (touching > 0) {
      opened = true;
    }
  }
  REQUIRE(opened);
  r.duration = static_cast<double>(touching) * dt;
  const gf::Grains& g = sim.grains();
  r.v_after = {g.vel.x[0], g.vel.y[0], g.vel.z[0]};
  r.w_after = {g.omega.x[0], g.omega.y[0], g.omega.z[0]};
  return r;
}

// A row of chung_ooi.csv, when GRAINFLOW_RESULTS names a folder.
void record(const std::string& test, const std::string& quantity, double reference, double ours) {
  using gf::test::csv_field, gf::test::csv_number;
  gf::test::record_result("chung_ooi.csv", "test,quantity,reference,grainflow,relative_error",
                          csv_field(test) + "," + csv_field(quantity) + "," + csv_number(reference) + "," +
                              csv_number(ours) + "," + csv_number((ours - reference) / reference));
}

// An impact against Chung & Ooi's published peak force (N), largest overlap (m) and duration (s), within 1 %.
void check_published(const std::string& test, const Impact& imp, double force, double overlap, double duration) {
  record(test, "peak force (N)", force, imp.peak_force);
  record(test, "max overlap (m)", overlap, imp.max_overlap);
  record(test, "contact time (s)", duration, imp.duration);
  CHECK(imp.peak_force == Approx(force).epsilon(0.01));
  CHECK(imp.max_overlap == Approx(overlap).epsilon(0.01));
  CHECK(imp.duration == Approx(duration).epsilon(0.01));
}

// Sphere of `m` dropped on the floor with velocity v (and no spin); returns the impact.
Impact plane_impact(const Material& m, double dt, double restitution, double friction, gf::V3<double> v,
                    const std::string& wall_contact = "") {
  DemSimulation sim = DemSimulation::from_text(scene(m, dt, 1, restitution, friction, kFloor, wall_contact));
  // Starts a hair above the floor, so the contact opens within a step or two.
  place(sim.grains(), 0, {0.0, m.radius - v.y * dt, 0.0}, v);
  const double r = m.radius;
  return run_impact(
      sim, [r](const gf::Grains& g) { return r - g.pos.y[0]; },
      [](const gf::Grains& g) { return std::hypot(g.wall_force.x[0], g.wall_force.y[0], g.wall_force.z[0]); },
      4000000);
}

}  // namespace

// Tolerances: the 1 % on the published figures (three significant digits). The time step
// resolves the contact in ~4,000-7,000 steps, so the discretisation error of velocity Verlet on the
// Hertz force (O(dt^2)) and the duration's one-step resolution are below 1e-3 relative.
TEST_CASE("hertz_mindlin: Chung-Ooi T1, two glass spheres head-on at 10 m/s each", "[contact][hertz]") {
  const Material m = kGlass;
  const double dt = 1.0e-8;
  DemSimulation sim = DemSimulation::from_text(scene(m, dt, 2, 1.0, 0.0, ""));
  // Each sphere moves 1e-7 m per step: they start 2e-7 m apart.
  place(sim.grains(), 0, {-m.radius - 1e-7, 0.5, 0.0}, {10.0, 0.0, 0.0});
  place(sim.grains(), 1, {m.radius + 1e-7, 0.5, 0.0}, {-10.0, 0.0, 0.0});
  const double r = m.radius;
  const Impact imp = run_impact(
      sim,
      [r](const gf::Grains& g) {
        return 2 * r - std::hypot(g.pos.x[1] - g.pos.x[0], g.pos.y[1] - g.pos.y[0], g.pos.z[1] - g.pos.z[0]);
      },
      [](const gf::Grains& g) { return std::hypot(g.force.x[0], g.force.y[0], g.force.z[0]); }, 100000);
  check_published("T1 glass-glass 10 m/s", imp, 10.70e3, 274e-6, 40.3e-6);
  // Elastic: the spheres leave at their impact speed (e = 1 makes beta = 0, no damping).
  CHECK(imp.v_after.x == Approx(-10.0).epsilon(1e-4));
}

TEST_CASE("hertz_mindlin: Chung-Ooi T2, an aluminium-alloy sphere on a rigid plane at 0.2 m/s", "[contact][hertz]") {
  const Impact imp = plane_impact(kAlAlloy, 1.0e-7, 1.0, 0.0, {0.0, -0.2, 0.0});
  check_published("T2 Al alloy-plane 0.2 m/s", imp, 11.37e3, 49.7e-6, 0.732e-3);
}

TEST_CASE("hertz_mindlin: Chung-Ooi T3, rebound over impact speed equals the input restitution", "[contact][hertz]") {
  for (double e : {0.2, 0.4, 0.6, 0.8, 1.0}) {
    const Impact imp = plane_impact(kAl2O3, 1.0e-9, e, 0.0, {0.0, -3.9, 0.0});
    const double measured = imp.v_after.y / 3.9;
    INFO("input e = " << e << ", measured " << measured);
    record("T3 Al2O3-plane 3.9 m/s", "restitution at e = " + std::to_string(e).substr(0, 3), e, measured);
    CHECK(measured == Approx(e).epsilon(0.01));
  }
}

TEST_CASE("hertz_mindlin: Chung-Ooi T4, oblique impact in gross sliding follows Coulomb's impulse", "[contact][hertz]") {
  // Al2O3 on an aluminium-alloy plane ([contact.wall] states the plane's material), 3.9 m/s, mu = 0.092,
  // e = 0.98. Beyond tan(theta) = 3.5 mu (1 + e) the sphere slides throughout the contact, so the
  // tangential impulse is mu times the normal one, m v cos(theta) (1 + e):
  //   e_t = v_t'/v_t = 1 - mu (1 + e) / tan(theta),   w' = 5 mu (1 + e) v cos(theta) / (2 R).
  // Below it the sphere sticks for part of the contact; there Coulomb's limit still bounds both.
  const double mu = 0.092, e = 0.98, v = 3.9, r = kAl2O3.radius;
  const std::string plate = "[contact.wall]\nyoungs_modulus = 7.0e10\npoisson_ratio = 0.33\n";
  const double limit = std::atan(3.5 * mu * (1 + e));
  for (double deg : {5.0, 15.0, 25.0, 40.0, 50.0, 60.0, 70.0, 85.0}) {
    const double th = deg * std::numbers::pi / 180.0;
    const Impact imp = plane_impact(kAl2O3, 1.0e-9, e, mu, {v * std::sin(th), -v * std::cos(th), 0.0}, plate);
    const double et = imp.v_after.x / (v * std::sin(th));
    const double spin = -imp.w_after.z;  // sliding along +x on a floor below turns the sphere about -z
    const double et_slide = 1.0 - mu * (1 + e) / std::tan(th);
    const double spin_slide = 5.0 * mu * (1 + e) * v * std::cos(th) / (2.0 * r);
    INFO("incidence " << deg << " deg: e_t = " << et << " (sliding " << et_slide << "), spin " << spin << " (sliding "
                      << spin_slide << ")");
    // The normal restitution is unchanged by friction (T3's 1 %).
    CHECK(imp.v_after.y / (v * std::cos(th)) == Approx(e).epsilon(0.01));
    if (th > limit * 1.1) {
      record("T4 Al2O3-Al alloy 3.9 m/s", "e_t at " + std::to_string(static_cast<int>(deg)) + " deg", et_slide, et);
      record("T4 Al2O3-Al alloy 3.9 m/s", "spin (rad/s) at " + std::to_string(static_cast<int>(deg)) + " deg", spin_slide,
             spin);
      CHECK(et == Approx(et_slide).epsilon(0.01));
      CHECK(spin == Approx(spin_slide).epsilon(0.01));
    } else {
      // Coulomb bounds the tangential impulse by mu times the normal one (0.5 % for round-off and the
      // damping part of |F_n|); sticking keeps the spin in the sense of rolling.
      CHECK(et >= et_slide - 0.005);
      CHECK(spin <= spin_slide * 1.005);
      CHECK(spin > 0.0);
    }
  }
}

// The small drum of test_support with Hertz-Mindlin instead of the linear law.
std::string hertz_drum(double gravity, const std::string& extra_run = "") {
  return gf::test::with_hertz_mindlin(gf::test::small_drum_scene(gravity, extra_run));
}

TEST_CASE("hertz_mindlin: a checkpoint of another law is refused by name", "[contact][hertz][checkpoint]") {
  gf::test::TempDir dir("hertz_ckpt");
  DemSimulation lin = DemSimulation::from_text(gf::test::small_drum_scene(9.81));
  lin.advance(10);
  gf::CheckpointWriter out;
  gf::save_dem_state(out, lin.world(), lin.scene());
  out.write(dir.path / "lin.gfc");
  DemSimulation hm = DemSimulation::from_text(hertz_drum(9.81));
  const gf::CheckpointReader in(dir.path / "lin.gfc");
  REQUIRE_THROWS_WITH(hm.resume(in), Catch::Contains("contact law 'linear_spring_dashpot'") &&
                                         Catch::Contains("'hertz_mindlin'"));
}

TEST_CASE("hertz_mindlin: a run resumed from a checkpoint continues bit for bit", "[contact][hertz][checkpoint]") {
  // The drum poured under 60 m/s^2 while it turns: contacts form, slide and roll, the list is rebuilt
  // on both sides of the checkpoint, so the law's springs cross it in the file.
  gf::test::TempDir dir("hertz_resume");
  const std::string text = hertz_drum(60.0, "max_overlap = 0.3\n");
  DemSimulation whole = DemSimulation::from_text(text);
  whole.advance(3000);
  DemSimulation first = DemSimulation::from_text(text);
  first.advance(2200);
  const auto rebuilds = first.world().resources.get<gf::BroadphaseState>().rebuilds;
  gf::CheckpointWriter out;
  gf::save_dem_state(out, first.world(), first.scene());
  out.write(dir.path / "hm.gfc");
  DemSimulation resumed = DemSimulation::from_text(text);
  resumed.resume(gf::CheckpointReader(dir.path / "hm.gfc"));
  resumed.advance(800);
  REQUIRE(whole.world().resources.get<gf::BroadphaseState>().rebuilds > rebuilds + 3);
  const auto& h1 = whole.world().resources.get<gf::PairHistory>();
  const auto& h2 = resumed.world().resources.get<gf::PairHistory>();
  REQUIRE(h1.size() > 100);
  REQUIRE(h1.size() == h2.size());
  REQUIRE(h1.component == "hertz_mindlin.shear");
  for (std::size_t q = 0; q < h1.width; ++q)
    CHECK(std::memcmp(h1.value[q].data(), h2.value[q].data(), h1.size() * sizeof(double)) == 0);
  CHECK(gf::test::state_by_id(whole.grains()) == gf::test::state_by_id(resumed.grains()));
}

TEST_CASE("hertz_mindlin: a wall material needs both of its keys, named with the scene's line", "[contact][hertz][scene]") {
  const std::string half = "[contact.wall]\npoisson_ratio = 0.3\n";
  REQUIRE_THROWS_WITH(DemSimulation::from_text(scene(kAl2O3, 1e-9, 1, 0.5, 0.1, kFloor, half)),
                      Catch::Contains("scene.toml:") && Catch::Contains("contact.wall.youngs_modulus") &&
                          Catch::Contains("give both"));
  const std::string missing = scene(kAl2O3, 1e-9, 1, 0.5, 0.1, kFloor);
  const std::string no_e = missing.substr(0, missing.find("youngs_modulus")) +
                           missing.substr(missing.find("poisson_ratio"));
  REQUIRE_THROWS_WITH(DemSimulation::from_text(no_e), Catch::Contains("species[0].youngs_modulus") &&
                                                         Catch::Contains("missing required key"));
}

// Velocity Verlet (systems/integrate) through the whole engine: energy conservation of perfectly elastic,
// frictionless spheres in a box under gravity, and free flight reproduced exactly.
#include "systems/setup/dem_simulation.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <limits>
#include <random>
#include <string>

#include "systems/contact/pair_contact.hpp"
#include "systems/walls/wall_contact.hpp"
#include "tests/test_support.hpp"

using gf::DemSimulation;
using gf::Grains;
using gf::test::ErrorKind;
using gf::test::norm;
using gf::test::record_analytic;
using V = gf::V3<double>;

namespace {

struct EnergyParts {
  double kinetic = 0, rotational = 0, gravity = 0, springs = 0;
  double total() const { return kinetic + rotational + gravity + springs; }
};

// Everything from positions and velocities, independently of the engine's contact lists: all pairs are checked, and
// the box faces are the planes x, y, z = lo and hi.
EnergyParts energy(const Grains& g, double kn, double gy, const V& lo, const V& hi) {
  EnergyParts e;
  const std::size_t n = g.n_owned;
  for (std::size_t i = 0; i < n; ++i) {
    const double m = g.mass.m[i], inertia = 1.0 / g.mass.inv_inertia[i], r = g.radius.r[i];
    const V v{g.vel.x[i], g.vel.y[i], g.vel.z[i]};
    const V w{g.omega.x[i], g.omega.y[i], g.omega.z[i]};
    e.kinetic += 0.5 * m * gf::dot(v, v);
    e.rotational += 0.5 * inertia * gf::dot(w, w);
    e.gravity += -m * gy * g.pos.y[i];  // relative to the floor y = 0
    const double faces[6] = {g.pos.x[i] - lo.x, hi.x - g.pos.x[i], g.pos.y[i] - lo.y,
                             hi.y - g.pos.y[i], g.pos.z[i] - lo.z, hi.z - g.pos.z[i]};
    for (const double gap : faces)
      if (gap < r) e.springs += 0.5 * kn * (r - gap) * (r - gap);
    for (std::size_t j = i + 1; j < n; ++j) {
      const V d{g.pos.x[j] - g.pos.x[i], g.pos.y[j] - g.pos.y[i], g.pos.z[j] - g.pos.z[i]};
      const double delta = r + g.radius.r[j] - norm(d);
      if (delta > 0) e.springs += 0.5 * kn * delta * delta;
    }
  }
  return e;
}

}  // namespace

TEST_CASE("integrate: elastic spheres in a box conserve energy over 1e5 steps", "[integrate]") {
  const std::string scene = std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/tests/elastic_box.toml";
  DemSimulation sim = DemSimulation::from_file(scene);
  Grains& g = sim.grains();
  const double kn = 1000.0, gy = -9.81;
  const V lo{0, 0, 0}, hi{0.02, 0.02, 0.01};
  // Random velocities (~0.3 m/s, so that pairs meet as well as walls) and spins (kept: no tangential coupling).
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    g.vel.x[i] = 0.3 * u(rng), g.vel.y[i] = 0.3 * u(rng), g.vel.z[i] = 0.3 * u(rng);
    g.omega.x[i] = 50 * u(rng), g.omega.y[i] = 50 * u(rng), g.omega.z[i] = 50 * u(rng);
  }
  const EnergyParts e0 = energy(g, kn, gy, lo, hi);
  REQUIRE(e0.springs == 0.0);  // the state file places the spheres clear of each other and of the walls
  double worst = 0.0, worst_t = 0.0, max_springs = 0.0;
  int pair_touches = 0;
  const int steps = 100000, every = 10;
  for (int k = 0; k < steps; k += every) {
    sim.advance(every);
    const EnergyParts e = energy(g, kn, gy, lo, hi);
    const double err = std::abs(e.total() - e0.total()) / e0.total();
    if (err > worst) worst = err, worst_t = sim.world().clock.t;
    max_springs = std::max(max_springs, e.springs);
    // Count samples with a pair in contact, to make sure the run exercises pair contacts and not only walls.
    for (std::size_t i = 0; i < g.n_owned; ++i)
      for (std::size_t j = i + 1; j < g.n_owned; ++j) {
        const V d{g.pos.x[j] - g.pos.x[i], g.pos.y[j] - g.pos.y[i], g.pos.z[j] - g.pos.z[i]};
        if (norm(d) < g.radius.r[i] + g.radius.r[j]) ++pair_touches;
      }
  }
  const EnergyParts e1 = energy(g, kn, gy, lo, hi);
  INFO("E0 = " << e0.total() << " J (kinetic " << e0.kinetic << ", rotational " << e0.rotational << ", gravity "
               << e0.gravity << "); at the end kinetic " << e1.kinetic << ", gravity " << e1.gravity << ", springs "
               << e1.springs << "; largest spring energy seen " << max_springs << " J; samples with a pair in contact "
               << pair_touches);
  WARN("elastic box: worst relative energy error over 1e5 steps of " << sim.scene().dt << " s: " << worst << " at t = " << worst_t
                                                                   << " s (tolerance 1e-3)");
  // The premise: energy really moved between its forms, through pair and wall contacts.
  REQUIRE(pair_touches > 10);
  REQUIRE(max_springs > 1e-3 * e0.total());
  // 0.1 % (the task's). Velocity Verlet is symplectic: with no dissipation the energy does not drift. But the
  // spring force has a kink at delta = 0 (smooth-force shadow-Hamiltonian bounds do not apply across it), and each
  // contact leaves a zero-mean energy error that depends on where the touch falls within a step: a 1-D model of this
  // integrator gives rms 3e-5 (max 5e-5) of the contact's normal kinetic energy at 42 steps per contact and 4e-6
  // (max 7e-6) at 84, i.e. ~(omega dt)^3. These random-walk over the run's ~1e3 contacts. At the scene's dt (84
  // steps per glass-glass contact) this run stays near 1e-4; at dt = 1e-5 (42 steps) the same 1e5 steps
  // accumulate 1.3e-3 over 1 s, so dt was halved rather than the tolerance widened. Any dissipation leak (a
  // dashpot with e = 1, a spurious tangential coupling) or a wrong half-kick is a systematic drift that breaks it.
  record_analytic({.case_name = std::to_string(g.n_owned) + " spheres in a box, e = 1, no friction, " +
                                std::to_string(steps) + " steps",
                   .quantity = "total energy, largest drift", .closed_form = "conserved", .error = worst,
                   .kind = ErrorKind::relative, .tolerance = 1e-3});
  CHECK(worst < 1e-3);
  // Spins are untouched: no tangential spring, no friction, no rolling torque.
  CHECK(std::abs(e1.rotational / e0.rotational - 1.0) < 1e-14);
}

TEST_CASE("integrate: free flight under gravity is x0 + v0 t + g t^2 / 2 to round-off", "[integrate]") {
  // One sphere, no walls, gravity along all three axes.
  const char* scene = R"(
[run]
dt = 5.0e-5
duration = 0.2
skin = 1.0e-4
gravity = [1.5, -9.81, 0.5]

[[species]]
name = "glass"
diameter = 3.0e-3
density = 2500.0

[contact]
model = "linear_spring_dashpot"
kn = 1000.0
kt = 600.0
en = 0.3
et = 0.3
friction = 0.3

[[fill]]
kind = "random"
region = { shape = "box", lo = [0.0, 0.0, 0.0], hi = [0.01, 0.01, 0.01] }
count = { glass = 1 }
)";
  DemSimulation sim = DemSimulation::from_text(scene);
  Grains& g = sim.grains();
  REQUIRE(g.n_owned == 1);
  const V x0{0.01, 0.5, -0.02}, v0{0.3, 2.0, -0.1}, w0{3.0, -2.0, 1.0}, grav{1.5, -9.81, 0.5};
  g.pos.x[0] = x0.x, g.pos.y[0] = x0.y, g.pos.z[0] = x0.z;
  g.vel.x[0] = v0.x, g.vel.y[0] = v0.y, g.vel.z[0] = v0.z;
  g.omega.x[0] = w0.x, g.omega.y[0] = w0.y, g.omega.z[0] = w0.z;
  const double dt = sim.scene().dt;
  const int steps = 4000;
  double worst_x = 0, worst_v = 0, max_x = 0, max_v = 0;
  for (int k = 1; k <= steps; ++k) {
    sim.advance(1);
    const double t = k * dt;
    const V x{x0.x + v0.x * t + 0.5 * grav.x * t * t, x0.y + v0.y * t + 0.5 * grav.y * t * t,
              x0.z + v0.z * t + 0.5 * grav.z * t * t};
    const V v{v0.x + grav.x * t, v0.y + grav.y * t, v0.z + grav.z * t};
    worst_x = std::max(worst_x, norm(V{g.pos.x[0], g.pos.y[0], g.pos.z[0]} - x));
    worst_v = std::max(worst_v, norm(V{g.vel.x[0], g.vel.y[0], g.vel.z[0]} - v));
    max_x = std::max(max_x, norm(x));
    max_v = std::max(max_v, norm(v));
  }
  // Velocity Verlet is exact for a constant force: v_{k+1/2} = v0 + (k + 1/2) g dt and x_n = x0 + v0 t + g t^2/2
  // in exact arithmetic. What remains is round-off: each step rounds x and v by half an ulp, and a velocity error
  // carried for the rest of the run moves x by it times t. Bounds after n steps, with eps = 2.2e-16:
  //   |dx| <= 2 n eps (max|x| + t max|v|),   |dv| <= 2 n eps max|v|.
  // An O(dt) integrator (explicit Euler) would be off by g t dt / 2 ~ 5e-5 m here, 8 orders of magnitude more.
  const double eps = std::numeric_limits<double>::epsilon();
  const double tol_x = 2.0 * steps * eps * (max_x + steps * dt * max_v), tol_v = 2.0 * steps * eps * max_v;
  WARN("free flight over " << steps << " steps: position error " << worst_x << " m (bound " << tol_x
                           << "), velocity error " << worst_v << " m/s (bound " << tol_v << ")");
  const std::string flight = "free flight under gravity, " + std::to_string(steps) + " steps";
  record_analytic({.case_name = flight, .quantity = "position (m), largest error (tolerance: the round-off bound)",
                   .closed_form = "x0 + v0 t + g t²/2", .error = worst_x, .kind = ErrorKind::absolute,
                   .tolerance = tol_x});
  record_analytic({.case_name = flight, .quantity = "velocity (m/s), largest error (tolerance: the round-off bound)",
                   .closed_form = "v0 + g t", .error = worst_v, .kind = ErrorKind::absolute, .tolerance = tol_v});
  CHECK(worst_x <= tol_x);
  CHECK(worst_v <= tol_v);
  // No contact, no torque: the spin is untouched, bit for bit.
  CHECK(g.omega.x[0] == w0.x);
  CHECK(g.omega.y[0] == w0.y);
  CHECK(g.omega.z[0] == w0.z);
}

namespace {
// A force a later system would fill (drag from a liquid, say), attached to the grains by the test.
struct Push {
  gf::ColumnD x, y, z;  // N
  auto columns() { return std::tie(x, y, z); }
};
}  // namespace

TEST_CASE("integrate: a declared force term is summed without touching the integrator", "[integrate][fast]") {
  gf::World w;
  Grains& g = w.grains;
  g.resize(13);  // one whole batch and a scalar tail at any batch width up to 8
  Push& push = g.extras.attach<Push>(g.n);
  for (std::size_t i = 0; i < g.n; ++i) {
    g.mass.m[i] = 0.5 + 0.1 * static_cast<double>(i);
    g.mass.inv_m[i] = 1.0 / g.mass.m[i];
    g.mass.inv_inertia[i] = 1.0;
    g.force.x[i] = 1.0;  // pair term
    g.wall_force.y[i] = 2.0;
    push.z[i] = 3.0 + static_cast<double>(i);
  }
  gf::ForceTerms terms{{gf::pair_force_term(), gf::wall_force_term()}};
  terms.list.push_back(gf::force_term<Push>("push"));
  const double h = 0.25;
  gf::kick(g, terms, gf::Gravity{0.0, 0.0, -1.0}, h);
  for (std::size_t i = 0; i < g.n; ++i) {
    // v = h (F/m + g), up to the last bit: the compiler may fuse the multiply-add (one rounding
    // fewer), so the bound is a few units in the last place, far below a missing or doubled term.
    CHECK(g.vel.x[i] == Approx(h * g.mass.inv_m[i] * 1.0).epsilon(1e-15));
    CHECK(g.vel.y[i] == Approx(h * g.mass.inv_m[i] * 2.0).epsilon(1e-15));
    CHECK(g.vel.z[i] == Approx(h * g.mass.inv_m[i] * push.z[i] - h).epsilon(1e-15));
    CHECK(g.omega.x[i] == 0.0);
  }
  // The schedule orders the push's producer before the integrator: the integrator reads it.
  gf::IntegrateVelocities closing(terms);
  const gf::Access a = closing.access();
  CHECK(std::find(a.reads.begin(), a.reads.end(), gf::type_id<Push>()) != a.reads.end());
  CHECK(std::find(a.reads.begin(), a.reads.end(), gf::type_id<gf::WallForce>()) != a.reads.end());
}

TEST_CASE("integrate: a closing kick left to the next step's opening pass changes no bit", "[integrate][fast]") {
  // A stepping loop lets the closing kick of a step nobody observes wait for the next opening pass
  // (two kicks with the same forces and one drift, in one pass). Stepped as one stage of 300 steps
  // (299 kicks deferred, the last applied when the stage ends) against 300 stages of one step (each
  // step its stage's last: none deferred), the states must agree bit for bit, spins included.
  const std::string scene = gf::test::small_drum_scene(9.81, "", 0.05);
  DemSimulation deferred = DemSimulation::from_text(scene);
  DemSimulation stepwise = DemSimulation::from_text(scene);
  deferred.advance(300);
  for (int k = 0; k < 300; ++k) stepwise.advance(1);
  const Grains& a = deferred.grains();
  const Grains& b = stepwise.grains();
  REQUIRE(a.n_owned == b.n_owned);
  REQUIRE(a.n_owned > 100);
  std::size_t differ = 0;
  double speed = 0.0;
  for (std::size_t i = 0; i < a.n_owned; ++i) {
    const double u[9] = {a.pos.x[i], a.pos.y[i], a.pos.z[i], a.vel.x[i], a.vel.y[i], a.vel.z[i],
                         a.omega.x[i], a.omega.y[i], a.omega.z[i]};
    const double v[9] = {b.pos.x[i], b.pos.y[i], b.pos.z[i], b.vel.x[i], b.vel.y[i], b.vel.z[i],
                         b.omega.x[i], b.omega.y[i], b.omega.z[i]};
    for (int k = 0; k < 9; ++k) differ += u[k] != v[k];
    speed = std::max(speed, std::abs(a.vel.y[i]));
  }
  CHECK(differ == 0);
  CHECK(speed > 1e-3);  // the grains move: the comparison is not of a state at rest
}

// The coupling through its seam (systems/coupling/coupled_liquid.hpp): a stand-in liquid, carriers on a
// cubic lattice all moving at one velocity, couples to a grain held in place without any MPS. With
// coupling.min_liquid_fraction = 1 the liquid fraction is 1 everywhere, so the force on the grain is the
// closed form of a lone sphere, drag (1/2) rho C_d A |w| w (Schiller-Naumann C_d at Re = rho d |w| / mu)
// plus buoyancy -V rho g; the momentum the liquid takes is minus the grain's impulse, the fixed carriers'
// part going to the container; and the systems declare the stand-in's table among what they touch.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "systems/coupling/coupled_step.hpp"
#include "systems/integrate/integrate.hpp"

namespace {

using gf::V3;

// The stand-in's state, a world resource: carriers every 1 mm within 6 mm of the origin, each with the
// momentum it was given. Every seventh carrier is fixed, as a wall node would be.
struct UniformState {
  std::vector<double> x, y, z, u, v, w;
  std::vector<V3<double>> given;
};

constexpr V3<double> kFlow{0.02, -0.01, 0.005};  // m/s

UniformState lattice() {
  UniformState s;
  for (int i = -6; i <= 6; ++i)
    for (int j = -6; j <= 6; ++j)
      for (int k = -6; k <= 6; ++k) {
        s.x.push_back(1e-3 * i), s.y.push_back(1e-3 * j), s.z.push_back(1e-3 * k);
        s.u.push_back(kFlow.x), s.v.push_back(kFlow.y), s.w.push_back(kFlow.z);
      }
  s.given.assign(s.x.size(), V3<double>{0, 0, 0});
  return s;
}

class UniformLiquid {
 public:
  using SampleReads = gf::Reads<UniformState>;
  using SampleWrites = gf::Writes<>;
  using ReactReads = gf::Reads<>;
  using ReactWrites = gf::Writes<UniformState>;

  explicit UniformLiquid(gf::World& w) : s_(w.resources.get<UniformState>()) {}
  std::size_t carriers() const { return s_.x.size(); }
  std::span<const double> position(int a) const { return a == 0 ? s_.x : a == 1 ? s_.y : s_.z; }
  std::span<const double> velocity(int a) const { return a == 0 ? s_.u : a == 1 ? s_.v : s_.w; }
  bool moves(std::size_t i) const { return i % 7 != 0; }
  bool averaged() const { return false; }
  std::vector<double> carrier_volumes() const { return {}; }
  void take_fraction(std::span<const double>) {}
  void add_momentum(std::size_t i, const V3<double>& dp) { s_.given[i] = s_.given[i] + dp; }

 private:
  UniformState& s_;
};

static_assert(gf::CoupledLiquid<UniformLiquid>);

constexpr double kD = 1e-3, kRhoP = 2500.0, kRho = 1000.0, kMu = 1e-3, kG = 9.81, kDt = 1e-3;
constexpr V3<double> kGrainV{0.001, 0.0, 0.0};

// A world of one grain at the origin, moving at kGrainV but held in place, in the stand-in liquid.
void build(gf::World& w, bool fluid_only) {
  gf::Grains& g = w.grains;
  g.resize(1);
  g.radius.r[0] = 0.5 * kD;
  g.mass.m[0] = kRhoP * std::numbers::pi / 6.0 * kD * kD * kD;
  g.vel.x[0] = kGrainV.x, g.vel.y[0] = kGrainV.y, g.vel.z[0] = kGrainV.z;
  w.resources.emplace<gf::Gravity>(gf::Gravity{0.0, -kG, 0.0});
  w.resources.emplace<UniformState>(lattice());
  gf::CouplingSpec spec;
  spec.smoothing_radius = 2.5e-3;
  spec.min_liquid_fraction = 1.0;
  spec.fluid_nodes_only = fluid_only;
  gf::attach_coupling(spec, gf::LiquidFacts{{kRho, kMu}, 1e-9, -1, 0, 0}, w);
}

double norm(const V3<double>& a) { return std::sqrt(gf::dot(a, a)); }

V3<double> given(const UniformState& s) {
  V3<double> sum{0, 0, 0};
  for (const V3<double>& p : s.given) sum = sum + p;
  return sum;
}

// (1/2) rho C_d A |w| w - V rho g, the liquid's force on a lone sphere.
V3<double> closed_form() {
  const V3<double> w = kFlow - kGrainV;
  const double speed = std::sqrt(gf::dot(w, w)), re = kRho * kD * speed / kMu;
  const double cd = 24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687));
  const double area = std::numbers::pi / 4.0 * kD * kD, volume = std::numbers::pi / 6.0 * kD * kD * kD;
  return (0.5 * kRho * cd * area * speed) * w - (volume * kRho) * V3<double>{0.0, -kG, 0.0};
}

}  // namespace

TEST_CASE("coupled liquid: a stand-in liquid drags a grain by the closed form and takes minus its impulse",
          "[coupled]") {
  const bool fluid_only = GENERATE(false, true);
  INFO("shares over " << (fluid_only ? "moving carriers only" : "every carrier"));
  gf::World w;
  build(w, fluid_only);
  gf::Schedule outer;
  gf::schedule_coupled_step<UniformLiquid>(outer, gf::fixed_grains_step(), 4);
  outer.build(w);
  gf::StepContext step;
  step.dt = kDt;
  const gf::CouplingState& c = w.resources.get<gf::CouplingState>();
  const UniformState& s = w.resources.get<UniformState>();
  // The second step's opening half-kick uses the first's force: its impulse is dt F.
  for (int k = 0; k < 2; ++k) {
    const V3<double> before = given(s);
    outer.run_step(step);
    INFO("step " << k);
    const double scale = norm(c.grain_impulse);
    REQUIRE(scale > 0.0);
    CHECK(norm(c.grain_impulse + c.reaction_impulse) <= 1e-12 * scale);  // minus the grain's impulse
    CHECK(norm(given(s) - before - c.fluid_reaction) <= 1e-12 * scale);   // the moving carriers' part
    if (fluid_only) CHECK(norm(c.reaction_impulse - c.fluid_reaction) <= 1e-12 * scale);  // no share on a fixed one
  }
  for (std::size_t i = 0; i < s.given.size(); i += 7) CHECK(norm(s.given[i]) == 0.0);  // fixed carriers take none

  const gf::LiquidAtGrain& at = w.grains.extras.get<gf::LiquidAtGrain>();
  CHECK(at.eps[0] == Approx(1.0).epsilon(1e-12));
  CHECK(at.ux[0] == Approx(kFlow.x).epsilon(1e-12));
  CHECK(at.uy[0] == Approx(kFlow.y).epsilon(1e-12));
  CHECK(at.uz[0] == Approx(kFlow.z).epsilon(1e-12));
  const gf::LiquidForce& f = w.grains.extras.get<gf::LiquidForce>();
  const V3<double> expected = closed_form();
  CHECK(f.x[0] == Approx(expected.x).epsilon(1e-9));
  CHECK(f.y[0] == Approx(expected.y).epsilon(1e-9));
  CHECK(f.z[0] == Approx(expected.z).epsilon(1e-9));
  CHECK(c.grain_impulse.x == Approx(kDt * expected.x).epsilon(1e-9));
  CHECK(c.grain_impulse.y == Approx(kDt * expected.y).epsilon(1e-9));
}

TEST_CASE("coupled liquid: the systems declare the liquid's tables among what they read and write", "[coupled]") {
  const std::size_t table = gf::type_id<UniformState>();
  const gf::Access prepare = gf::access_of<gf::CouplingPrepare<UniformLiquid>>();
  const gf::Access reaction = gf::access_of<gf::LiquidReaction<UniformLiquid>>();
  CHECK(std::count(prepare.reads.begin(), prepare.reads.end(), table) == 1);
  CHECK(std::count(prepare.writes.begin(), prepare.writes.end(), table) == 0);
  CHECK(std::count(reaction.writes.begin(), reaction.writes.end(), table) == 1);
}

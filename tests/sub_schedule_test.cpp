// A sub-schedule: the DEM step run k times inside one outer step of k dt gives the state of k
// separate steps of dt, bit for bit, and each sub-step is told its own (t, dt, index).
#include <catch2/catch.hpp>

#include <memory>
#include <vector>

#include "engine/sub_schedule.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/contact/pair_contact.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

namespace {

// Records the context of every call.
class Recorder : public gf::SystemBase<Recorder> {
 public:
  using Reads = gf::Reads<>;
  using Writes = gf::Writes<>;
  explicit Recorder(std::vector<gf::StepContext>& seen) : seen_(seen) {}
  std::string_view name() const override { return "recorder"; }
  void run(gf::World&, const gf::StepContext& step) override { seen_.push_back(step); }

 private:
  std::vector<gf::StepContext>& seen_;
};

}  // namespace

TEST_CASE("sub-schedule: each of the k runs serves t + s dt/k for dt/k", "[sub_schedule][fast]") {
  std::vector<gf::StepContext> seen;
  auto inner = std::make_unique<gf::Schedule>();
  inner->emplace<Recorder>(seen);
  gf::Schedule outer;
  outer.emplace<gf::SubSchedule>("dem_substeps", 4, std::move(inner));
  gf::World world;
  outer.build(world);
  outer.run_step({1.0, 0.5, 7, 0, 1, false});
  REQUIRE(seen.size() == 4);
  for (int s = 0; s < 4; ++s) {
    CHECK(seen[s].t == 1.0 + 0.125 * s);  // exact in binary
    CHECK(seen[s].dt == 0.125);
    CHECK(seen[s].substep == s);
    CHECK(seen[s].substeps == 4);
    CHECK(seen[s].step == 7);
  }
  REQUIRE_THROWS(gf::SubSchedule("none", 0, std::make_unique<gf::Schedule>()));
}

TEST_CASE("sub-schedule: the DEM step run 4 times per outer step equals 4 separate steps, bit for bit",
          "[sub_schedule][fast]") {
  // 300 grains falling into a closed box, stirred so that contacts, rebuilds and wall hits all occur
  // within the 40 steps compared. Box walls do not move, so the wall time plays no part.
  const std::string scene = gf::test::binary_box_scene(250, 50, 200.0);
  gf::DemSimulation plain = gf::DemSimulation::from_text(scene);
  gf::DemSimulation sub = gf::DemSimulation::from_text(scene);
  for (gf::DemSimulation* s : {&plain, &sub}) {
    s->advance(200);
    gf::test::stir_by_id(s->grains(), 5);
  }
  const auto rebuilds_before = plain.world().resources.get<gf::BroadphaseState>().rebuilds;
  plain.advance(40);
  REQUIRE(plain.world().resources.get<gf::BroadphaseState>().rebuilds > rebuilds_before);
  REQUIRE(plain.world().resources.get<gf::PairForces>().contacts() > 0);

  constexpr int k = 4;
  auto inner = std::make_unique<gf::Schedule>();
  gf::schedule_dem_step(*inner, sub.scene());
  gf::Schedule outer;
  outer.emplace<gf::SubSchedule>("dem_substeps", k, std::move(inner));
  gf::World& w = sub.world();
  outer.build(w);
  gf::StageOptions so;
  so.steps = 40 / k;
  so.progress_seconds = 0;
  w.clock.dt *= k;  // the outer step; k dt / k is dt exactly (a power of two)
  gf::run_stage(w, outer, so);

  const auto a = gf::test::state_by_id(plain.grains());
  const auto b = gf::test::state_by_id(sub.grains());
  REQUIRE(a.size() == b.size());
  std::size_t differ = 0;
  for (std::size_t id = 0; id < a.size(); ++id) differ += a[id] != b[id];
  CHECK(differ == 0);
  CHECK(plain.world().resources.get<gf::BroadphaseState>().rebuilds ==
        w.resources.get<gf::BroadphaseState>().rebuilds);
}

// Particle-particle contact throughput: the pair driver with the linear spring-dashpot law (the
// overlap prefilter over every pair of the Verlet list, the law over the packed contacts, the sums
// per fixed slab of owner rows; pair_contact.hpp) on the standard benchmark state
// (scenes/drum_seed000_settled.toml, 47,108 grains), at 1 and 2 TBB threads.
// items_per_second counts list pairs (touching or not); contacts/s counts the pairs in contact,
// which are the ones that evaluate the law.
//
// The drum is primed and stepped a few times first, so the neighbour list and the tangential and
// rolling springs are those of a running simulation. Iterations re-evaluate forces on the same
// positions and velocities: the set of contacts and so the work are fixed, while the springs keep
// integrating v_t dt and the Coulomb/rolling caps clip them, so the history evolves a little from
// one iteration to the next. That changes values, not the amount of work (the law is branch-free:
// its selections compute both sides), which is acceptable for a throughput figure.
//
// Both drivers are benchmarked: BM_PairForces/simd is compute_pair_forces, the xsimd driver the
// program runs; BM_PairForces/scalar is compute_pair_forces_scalar, its scalar twin (same slab sums),
// the reference the tests compare it with.
//
// Run:  ./build/bench/pair_contact_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <cstddef>
#include <cstdint>
#include <exception>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/laws.hpp"
#include "systems/contact/pair_contact.hpp"
#include "bench/settled_drum.hpp"
#include "systems/setup/dem_simulation.hpp"

namespace {

// Pairs of the list whose spheres overlap, by the driver's own test.
std::int64_t count_contacts(const gf::Grains& g, const gf::NeighborList& list) {
  std::int64_t n = 0;
  for (std::size_t k = 0; k < list.pairs(); ++k) {
    const std::uint32_t i = list.i[k], j = list.j[k];
    const double dx = g.pos.x[j] - g.pos.x[i], dy = g.pos.y[j] - g.pos.y[i], dz = g.pos.z[j] - g.pos.z[i];
    const double rsum = g.radius.r[i] + g.radius.r[j];
    if (dx * dx + dy * dy + dz * dz < rsum * rsum) ++n;
  }
  return n;
}

template <auto Driver>
void BM_PairForces(benchmark::State& state) {
  // A benchmark program owns its process, so it may set the thread count here (not in a library).
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  gf::DemSimulation* sim = gf::bench::settled_drum_or_skip(state);
  if (!sim) return;
  gf::World& w = sim->world();
  gf::Grains& g = w.grains;
  const auto& list = w.resources.get<gf::NeighborList>();
  auto& history = w.resources.get<gf::PairHistory>();
  const auto& table = w.resources.get<gf::ContactTable>();
  auto& out = w.resources.get<gf::PairForces>();
  const double dt = w.clock.dt;
  for (auto _ : state) {
    Driver(g, list, history, table, dt, out, w.resources.get<gf::OverlapLimit>().ratio);
    benchmark::ClobberMemory();
  }
  const auto pairs = static_cast<std::int64_t>(list.pairs());
  const std::int64_t contacts = count_contacts(g, list);
  state.SetItemsProcessed(state.iterations() * pairs);
  state.counters["rows"] = static_cast<double>(g.n);
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["contacts"] = static_cast<double>(contacts);
  state.counters["pairs/s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * pairs), benchmark::Counter::kIsRate);
  state.counters["contacts/s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * contacts), benchmark::Counter::kIsRate);
  state.SetLabel("items=pairs");
}

// Real time: TBB workers' CPU time is not the main thread's.
BENCHMARK_TEMPLATE(BM_PairForces, gf::compute_pair_forces<gf::LinearSpringDashpot>)->Name("BM_PairForces/simd")->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_PairForces, gf::compute_pair_forces_scalar<gf::LinearSpringDashpot>)->Name("BM_PairForces/scalar")->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

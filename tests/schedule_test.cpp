// The schedule: task-graph edges come only from conflicting declared accesses (write->read,
// read->write, write->write), transitive edges are dropped, the graph enforces the order it promises,
// independent systems really run side by side, a system's exception reaches the caller of run_step
// and leaves the schedule usable, and every node's calls are counted.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "engine/schedule.hpp"
#include "engine/system.hpp"
#include "engine/type_id.hpp"
#include "engine/world.hpp"

using gf::Schedule;
using gf::World;
using Edges = std::vector<std::pair<std::size_t, std::size_t>>;

namespace {

// Marker components/resources: only their type ids matter.
struct A {};
struct B {};
struct C {};
struct D {};
struct E {};

// A system whose accesses are declared in its type, like the real ones.
template <class R, class W>
class Probe : public gf::SystemBase<Probe<R, W>> {
 public:
  using Reads = R;
  using Writes = W;
  Probe(std::string name, std::function<void(World&)> body = {}) : name_(std::move(name)), body_(std::move(body)) {}
  std::string_view name() const override { return name_; }
  void run(World& w, const gf::StepContext&) override {
    if (body_) body_(w);
  }

 private:
  std::string name_;
  std::function<void(World&)> body_;
};

template <class R, class W>
Probe<R, W>& add(Schedule& s, std::string name, std::function<void(World&)> body = {}) {
  return s.emplace<Probe<R, W>>(std::move(name), std::move(body));
}

Edges sorted(Edges e) {
  std::sort(e.begin(), e.end());
  return e;
}

// A system with accesses chosen at run time, for property tests over random access patterns.
class Dynamic : public gf::System {
 public:
  Dynamic(std::string name, gf::Access acc, std::function<void()> body)
      : name_(std::move(name)), acc_(std::move(acc)), body_(std::move(body)) {}
  std::string_view name() const override { return name_; }
  gf::Access access() const override { return acc_; }
  void run(World&, const gf::StepContext&) override { body_(); }

 private:
  std::string name_;
  gf::Access acc_;
  std::function<void()> body_;
};

// Transitive closure of a DAG on n nodes given by edges (a, b) with a < b.
std::vector<std::vector<bool>> closure(std::size_t n, const Edges& edges) {
  std::vector<std::vector<bool>> r(n, std::vector<bool>(n, false));
  for (auto [a, b] : edges) r[a][b] = true;
  // Nodes are in topological order (a < b), so one backward sweep suffices.
  for (std::size_t a = n; a-- > 0;)
    for (std::size_t b = a + 1; b < n; ++b)
      if (r[a][b])
        for (std::size_t c = b + 1; c < n; ++c)
          if (r[b][c]) r[a][c] = true;
  return r;
}

bool conflict(const gf::Access& x, const gf::Access& y) {
  auto meet = [](const std::vector<std::size_t>& p, const std::vector<std::size_t>& q) {
    return std::any_of(p.begin(), p.end(), [&](std::size_t v) { return std::find(q.begin(), q.end(), v) != q.end(); });
  };
  return meet(x.writes, y.reads) || meet(x.reads, y.writes) || meet(x.writes, y.writes);
}

// Waits until `count` reaches `target` or the timeout passes; true if reached. Never hangs a test.
class Rendezvous {
 public:
  bool arrive_and_wait(int target, std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(m_);
    ++count_;
    cv_.notify_all();
    return cv_.wait_for(lock, timeout, [&] { return count_ >= target; });
  }
  void reset() {
    std::lock_guard<std::mutex> lock(m_);
    count_ = 0;
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  int count_ = 0;
};

struct Boom : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace

TEST_CASE("schedule: edges exactly where declared accesses conflict", "[schedule]") {
  using gf::Reads;
  using gf::Writes;
  World world;
  SECTION("write then read") {
    Schedule s;
    add<Reads<>, Writes<A>>(s, "w");
    add<Reads<A>, Writes<>>(s, "r");
    s.build(world);
    CHECK(s.edges() == Edges{{0, 1}});
  }
  SECTION("read then write") {
    Schedule s;
    add<Reads<A>, Writes<>>(s, "r");
    add<Reads<>, Writes<A>>(s, "w");
    s.build(world);
    CHECK(s.edges() == Edges{{0, 1}});
  }
  SECTION("write then write") {
    Schedule s;
    add<Reads<>, Writes<A>>(s, "w1");
    add<Reads<>, Writes<A>>(s, "w2");
    s.build(world);
    CHECK(s.edges() == Edges{{0, 1}});
  }
  SECTION("read and read: no edge") {
    Schedule s;
    add<Reads<A, B>, Writes<C>>(s, "r1");
    add<Reads<A, B>, Writes<D>>(s, "r2");
    s.build(world);
    CHECK(s.edges().empty());
  }
  SECTION("disjoint writes: no edge") {
    Schedule s;
    add<Reads<>, Writes<A>>(s, "a");
    add<Reads<>, Writes<B>>(s, "b");
    add<Reads<C>, Writes<D>>(s, "c");
    s.build(world);
    CHECK(s.edges().empty());
  }
  SECTION("a transitive edge is dropped") {
    Schedule s;
    add<Reads<>, Writes<A>>(s, "make_a");
    add<Reads<A>, Writes<B>>(s, "a_to_b");
    add<Reads<A, B>, Writes<>>(s, "use_both");  // conflicts with make_a too, but that is implied
    s.build(world);
    CHECK(sorted(s.edges()) == Edges{{0, 1}, {1, 2}});
  }
  SECTION("an edge that is not implied is kept") {
    Schedule s;
    add<Reads<>, Writes<A>>(s, "make_a");
    add<Reads<>, Writes<B>>(s, "make_b");
    add<Reads<A, B>, Writes<>>(s, "use_both");
    s.build(world);
    CHECK(sorted(s.edges()) == Edges{{0, 2}, {1, 2}});
  }
  SECTION("a long chain keeps only its links") {
    Schedule s;
    add<Reads<>, Writes<A>>(s, "s0");
    add<Reads<A>, Writes<B>>(s, "s1");
    add<Reads<B>, Writes<C>>(s, "s2");
    add<Reads<A, C>, Writes<E>>(s, "s3");
    add<Reads<D>, Writes<>>(s, "loner");
    s.build(world);
    CHECK(sorted(s.edges()) == Edges{{0, 1}, {1, 2}, {2, 3}});
    const std::string d = s.describe();
    CHECK(d.find("s3  <- s2") != std::string::npos);
    CHECK(d.find("loner\n") != std::string::npos);  // no predecessors listed
  }
  SECTION("names in phase order") {
    Schedule s;
    add<Reads<>, Writes<A>>(s, "first");
    add<Reads<>, Writes<B>>(s, "second");
    CHECK(s.names() == std::vector<std::string>{"first", "second"});
    CHECK(s.size() == 2);
  }
}

TEST_CASE("schedule: random access patterns give the transitive reduction of the conflicts, and the "
          "graph runs in that order", "[schedule]") {
  const std::size_t ids[5] = {gf::type_id<A>(), gf::type_id<B>(), gf::type_id<C>(), gf::type_id<D>(),
                              gf::type_id<E>()};
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    INFO("seed " << seed);
    std::mt19937_64 rng(seed);
    const std::size_t n = 3 + rng() % 7;
    std::vector<gf::Access> acc(n);
    for (auto& a : acc)
      for (std::size_t id : ids) {
        const auto roll = rng() % 6;  // 1/6 write, 1/6 read, else untouched
        if (roll == 0) a.writes.push_back(id);
        if (roll == 1) a.reads.push_back(id);
      }
    // The conflict graph in phase order, and the order each system started and finished in.
    Edges dep;
    for (std::size_t b = 0; b < n; ++b)
      for (std::size_t a = 0; a < b; ++a)
        if (conflict(acc[a], acc[b])) dep.emplace_back(a, b);

    std::atomic<int> tick{0};
    std::vector<int> start(n, -1), finish(n, -1);
    World world;
    Schedule s;
    for (std::size_t i = 0; i < n; ++i) {
      // Appended, not "s" + to_string(i): GCC 12 warns on that (-Wrestrict, a known false positive).
      std::string name = "s";
      name += std::to_string(i);
      s.add(std::make_unique<Dynamic>(name, acc[i], [&, i] {
        start[i] = tick++;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        finish[i] = tick++;
      }));
    }
    s.build(world);
    const Edges e = sorted(s.edges());

    // Same reachability as the conflicts ...
    const auto want = closure(n, dep);
    CHECK(closure(n, e) == want);
    // ... with no edge that the others imply (the transitive reduction of a DAG is unique).
    for (std::size_t q = 0; q < e.size(); ++q) {
      Edges without = e;
      without.erase(without.begin() + static_cast<std::ptrdiff_t>(q));
      INFO("edge " << e[q].first << " -> " << e[q].second << " is implied by the others");
      CHECK_FALSE(closure(n, without)[e[q].first][e[q].second]);
    }
    // Every conflicting pair ran one after the other, in phase order.
    for (int step = 0; step < 3; ++step) {
      s.run_step({});
      for (auto [a, b] : dep) {
        INFO("step " << step << ": s" << a << " and s" << b << " conflict");
        CHECK(finish[a] < start[b]);
      }
    }
  }
}

TEST_CASE("schedule: independent systems run at the same time", "[schedule]") {
  // Two systems with disjoint accesses each wait for the other to arrive. They can only both
  // succeed if they ran concurrently; a schedule that serialised them would make the first one time
  // out (after 5 s, so a failure never hangs the test).
  using gf::Reads;
  using gf::Writes;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  tbb::task_arena arena(2);
  Rendezvous meet;
  std::atomic<int> met{0}, missed{0};
  auto body = [&](World&) {
    if (meet.arrive_and_wait(2, std::chrono::milliseconds(5000)))
      ++met;
    else
      ++missed;
  };
  World world;
  Schedule s;
  add<Reads<C>, Writes<A>>(s, "left", body);
  add<Reads<C>, Writes<B>>(s, "right", body);
  // The graph binds to the arena it is built in, so build and run inside the two-thread arena.
  arena.execute([&] { s.build(world); });
  REQUIRE(s.edges().empty());
  for (int step = 0; step < 3 && missed == 0; ++step) {
    meet.reset();
    arena.execute([&] { s.run_step({}); });
  }
  CHECK(missed == 0);
  CHECK(met == 6);
}

TEST_CASE("schedule: dependent systems never overlap", "[schedule]") {
  using gf::Reads;
  using gf::Writes;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  std::atomic<int> in_flight{0}, overlaps{0};
  std::atomic<bool> producer_done{false};
  std::atomic<int> consumer_saw_unfinished{0};
  World world;
  Schedule s;
  add<Reads<>, Writes<A>>(s, "producer", [&](World&) {
    if (in_flight++ != 0) ++overlaps;
    producer_done = false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    producer_done = true;
    --in_flight;
  });
  add<Reads<A>, Writes<B>>(s, "consumer", [&](World&) {
    if (in_flight++ != 0) ++overlaps;
    if (!producer_done) ++consumer_saw_unfinished;
    --in_flight;
  });
  s.build(world);
  for (int step = 0; step < 5; ++step) s.run_step({});
  CHECK(overlaps == 0);
  CHECK(consumer_saw_unfinished == 0);
}

TEST_CASE("schedule: an exception in a system reaches run_step, and the schedule runs again", "[schedule]") {
  using gf::Reads;
  using gf::Writes;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  int calls_thrower = 0;
  std::atomic<int> ran_after{0}, ran_beside{0};
  bool fail_next = false;
  World world;
  Schedule s;
  add<Reads<>, Writes<A>>(s, "thrower", [&](World&) {
    ++calls_thrower;
    if (fail_next) throw Boom("boom in step " + std::to_string(calls_thrower));
  });
  add<Reads<A>, Writes<B>>(s, "after", [&](World&) { ++ran_after; });
  add<Reads<>, Writes<C>>(s, "beside", [&](World&) { ++ran_beside; });
  s.build(world);

  s.run_step({});
  fail_next = true;
  REQUIRE_THROWS_AS(s.run_step({}), Boom);  // the system's own exception type, not a wrapper
  CHECK(ran_after == 1);                  // the dependent system did not run on a failed input
  fail_next = false;
  REQUIRE_NOTHROW(s.run_step({}));  // the error is cleared: the next step runs normally
  CHECK(ran_after == 2);
  // An independent system runs in every good step; in the failed one it runs only if it started
  // before the failure was recorded (systems that start later are skipped), which is up to timing.
  CHECK(ran_beside >= 2);
  CHECK(ran_beside <= 3);

  fail_next = true;
  REQUIRE_THROWS_WITH(s.run_step({}), "boom in step 4");
  fail_next = false;
  s.run_step({});

  // Calls are counted per node: a failed call counts, a skipped one does not.
  const auto t = s.timings();
  REQUIRE(t.size() == 3);
  CHECK(t[0].name == "thrower");
  CHECK(t[0].calls == 5);
  CHECK(t[1].calls == 3);
  CHECK(t[2].calls == ran_beside);
  CHECK(t[2].calls >= 3);
}

TEST_CASE("schedule: two systems failing in one step give one exception", "[schedule]") {
  using gf::Reads;
  using gf::Writes;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  World world;
  Schedule s;
  bool fail = true;
  add<Reads<>, Writes<A>>(s, "one", [&](World&) {
    if (fail) throw Boom("first");
  });
  add<Reads<>, Writes<B>>(s, "two", [&](World&) {
    if (fail) throw std::logic_error("second");
  });
  s.build(world);
  bool caught = false;
  try {
    s.run_step({});
  } catch (const Boom& e) {
    caught = std::string(e.what()) == "first";
  } catch (const std::logic_error& e) {
    caught = std::string(e.what()) == "second";
  }
  CHECK(caught);
  fail = false;
  CHECK_NOTHROW(s.run_step({}));
}

TEST_CASE("schedule: timings count calls and time per system", "[schedule]") {
  using gf::Reads;
  using gf::Writes;
  World world;
  Schedule s;
  add<Reads<>, Writes<A>>(s, "sleeper", [](World&) { std::this_thread::sleep_for(std::chrono::milliseconds(10)); });
  add<Reads<A>, Writes<>>(s, "quick");
  CHECK(s.timings().size() == 2);  // before build: names, nothing counted
  CHECK(s.timings()[0].calls == 0);
  s.build(world);
  for (int k = 0; k < 4; ++k) s.run_step({});
  auto t = s.timings();
  REQUIRE(t.size() == 2);
  CHECK(t[0].name == "sleeper");
  CHECK(t[1].name == "quick");
  CHECK(t[0].calls == 4);
  CHECK(t[1].calls == 4);
  CHECK(t[0].seconds >= 0.040);  // sleep_for sleeps at least as long as asked
  CHECK(t[1].seconds < t[0].seconds);
  s.reset_timings();
  t = s.timings();
  CHECK(t[0].calls == 0);
  CHECK(t[0].seconds == 0.0);
  s.run_step({});
  CHECK(s.timings()[1].calls == 1);
}

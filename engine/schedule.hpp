// Builds a tbb::flow::graph once from the systems' declared accesses and triggers it every step.
#pragma once

#include <chrono>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <tbb/flow_graph.h>

#include "engine/system.hpp"

namespace gf {

struct SystemTiming {
  std::string name;
  double seconds = 0.0;
  std::int64_t calls = 0;
};

class Schedule {
 public:
  Schedule();
  ~Schedule();
  Schedule(const Schedule&) = delete;
  Schedule& operator=(const Schedule&) = delete;

  // Systems are added in phase order; a later system depends on an earlier one wherever their
  // accesses conflict (write/read, read/write, write/write on the same component or resource).
  System& add(std::unique_ptr<System> system);
  template <class S, class... Args>
  S& emplace(Args&&... args) {
    return static_cast<S&>(add(std::make_unique<S>(std::forward<Args>(args)...)));
  }

  void build(World& world);
  // Triggers the graph once for the step `ctx` and waits; rethrows the first failure of a system.
  void run_step(const StepContext& ctx);
  // Whether any of its systems (observers) will read the state when run at `now`.
  bool samples(const World& world, const StepContext& now) const;
  // System::complete of every system, in order.
  void complete(World& world);
  // Every component and resource its systems read and write (a sub-schedule declares these).
  Access access() const;

  std::size_t size() const { return systems_.size(); }
  const std::vector<std::pair<std::size_t, std::size_t>>& edges() const { return edges_; }
  std::vector<std::string> names() const;
  std::vector<SystemTiming> timings() const;
  void reset_timings();
  std::string describe() const;  // one line per system with its predecessors

 private:
  struct Node;
  std::vector<std::unique_ptr<System>> systems_;
  std::vector<std::pair<std::size_t, std::size_t>> edges_;
  std::unique_ptr<tbb::flow::graph> graph_;
  std::unique_ptr<tbb::flow::broadcast_node<tbb::flow::continue_msg>> root_;
  std::vector<std::unique_ptr<Node>> nodes_;
  std::mutex error_mutex_;
  std::exception_ptr error_;
  StepContext ctx_;
};

}  // namespace gf

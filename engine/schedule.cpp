#include "engine/schedule.hpp"

#include <algorithm>
#include <sstream>

namespace gf {

struct Schedule::Node {
  std::unique_ptr<tbb::flow::continue_node<tbb::flow::continue_msg>> node;
  double seconds = 0.0;
  std::int64_t calls = 0;
};

Schedule::Schedule() = default;
Schedule::~Schedule() {
  if (graph_) graph_->wait_for_all();
}

System& Schedule::add(std::unique_ptr<System> system) {
  systems_.push_back(std::move(system));
  return *systems_.back();
}

namespace {
bool intersects(const std::vector<std::size_t>& a, const std::vector<std::size_t>& b) {
  for (std::size_t x : a)
    if (std::find(b.begin(), b.end(), x) != b.end()) return true;
  return false;
}
}  // namespace

void Schedule::build(World& world) {
  const std::size_t n = systems_.size();
  std::vector<Access> acc;
  acc.reserve(n);
  for (auto& s : systems_) acc.push_back(s->access());

  // Conflict edges in phase order, then a transitive reduction so the graph stays readable.
  std::vector<std::vector<bool>> dep(n, std::vector<bool>(n, false));
  for (std::size_t b = 0; b < n; ++b)
    for (std::size_t a = 0; a < b; ++a)
      dep[a][b] = intersects(acc[a].writes, acc[b].reads) || intersects(acc[a].reads, acc[b].writes) ||
                  intersects(acc[a].writes, acc[b].writes);
  std::vector<std::vector<bool>> reach = dep;
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t a = 0; a < n; ++a)
      if (reach[a][k])
        for (std::size_t b = 0; b < n; ++b)
          if (reach[k][b]) reach[a][b] = true;
  edges_.clear();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      if (!dep[a][b]) continue;
      bool implied = false;
      for (std::size_t k = a + 1; k < b && !implied; ++k) implied = reach[a][k] && reach[k][b];
      if (!implied) edges_.emplace_back(a, b);
    }

  for (auto& s : systems_) s->build(world);
  graph_ = std::make_unique<tbb::flow::graph>();
  root_ = std::make_unique<tbb::flow::broadcast_node<tbb::flow::continue_msg>>(*graph_);
  nodes_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    auto node = std::make_unique<Node>();
    System* sys = systems_[i].get();
    Node* self = node.get();
    node->node = std::make_unique<tbb::flow::continue_node<tbb::flow::continue_msg>>(
        *graph_, [this, sys, self, &world](const tbb::flow::continue_msg&) {
          {
            std::lock_guard<std::mutex> lock(error_mutex_);
            if (error_) return;
          }
          const auto t0 = std::chrono::steady_clock::now();
          try {
            sys->run(world, ctx_);
          } catch (...) {
            std::lock_guard<std::mutex> lock(error_mutex_);
            if (!error_) error_ = std::current_exception();
          }
          self->seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          ++self->calls;
        });
    nodes_.push_back(std::move(node));
  }
  std::vector<bool> has_pred(n, false);
  for (auto [a, b] : edges_) {
    tbb::flow::make_edge(*nodes_[a]->node, *nodes_[b]->node);
    has_pred[b] = true;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!has_pred[i]) tbb::flow::make_edge(*root_, *nodes_[i]->node);
}

void Schedule::run_step(const StepContext& ctx) {
  ctx_ = ctx;
  root_->try_put(tbb::flow::continue_msg());
  graph_->wait_for_all();
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    std::rethrow_exception(e);
  }
}

bool Schedule::samples(const World& world, const StepContext& now) const {
  return std::any_of(systems_.begin(), systems_.end(), [&](const auto& s) { return s->samples(world, now); });
}

void Schedule::complete(World& world) {
  for (auto& s : systems_) s->complete(world);
}

Access Schedule::access() const {
  Access all;
  auto add = [](std::vector<std::size_t>& to, const std::vector<std::size_t>& from) {
    for (std::size_t x : from)
      if (std::find(to.begin(), to.end(), x) == to.end()) to.push_back(x);
  };
  for (auto& s : systems_) {
    const Access a = s->access();
    add(all.reads, a.reads);
    add(all.writes, a.writes);
  }
  return all;
}

std::vector<std::string> Schedule::names() const {
  std::vector<std::string> out;
  for (auto& s : systems_) out.emplace_back(s->name());
  return out;
}

std::vector<SystemTiming> Schedule::timings() const {
  std::vector<SystemTiming> out;
  for (std::size_t i = 0; i < systems_.size(); ++i) {
    SystemTiming t{std::string(systems_[i]->name()), 0.0, 0};
    if (i < nodes_.size()) {
      t.seconds = nodes_[i]->seconds;
      t.calls = nodes_[i]->calls;
    }
    out.push_back(std::move(t));
  }
  return out;
}

void Schedule::reset_timings() {
  for (auto& n : nodes_) {
    n->seconds = 0.0;
    n->calls = 0;
  }
}

std::string Schedule::describe() const {
  std::ostringstream os;
  for (std::size_t i = 0; i < systems_.size(); ++i) {
    os << "  " << (i + 1) << ". " << systems_[i]->name();
    bool first = true;
    for (auto [a, b] : edges_)
      if (b == i) {
        os << (first ? "  <- " : ", ") << systems_[a]->name();
        first = false;
      }
    os << "\n";
  }
  return os.str();
}

}  // namespace gf

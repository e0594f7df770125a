// A system runs over whole columns and declares, in its type, what it reads and writes.
// The schedule turns those declarations into task-graph edges; nothing else orders systems.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "engine/step_context.hpp"
#include "engine/type_id.hpp"
#include "engine/world.hpp"

namespace gf {

template <class... T>
struct Reads {};
template <class... T>
struct Writes {};

struct Access {
  std::vector<std::size_t> reads;
  std::vector<std::size_t> writes;
};

namespace detail {
template <class... T>
std::vector<std::size_t> ids(Reads<T...>) {
  return {type_id<T>()...};
}
template <class... T>
std::vector<std::size_t> ids(Writes<T...>) {
  return {type_id<T>()...};
}
}  // namespace detail

// Derived declares `using Reads = gf::Reads<...>; using Writes = gf::Writes<...>;` naming
// components (Position, Force, ...) and resources (Clock, ContactList, ...).
template <class Derived>
Access access_of() {
  return {detail::ids(typename Derived::Reads{}), detail::ids(typename Derived::Writes{})};
}

class System {
 public:
  virtual ~System() = default;
  virtual std::string_view name() const = 0;
  virtual Access access() const = 0;
  // Called once by Schedule::build, before the first run (a sub-schedule builds its own graph).
  virtual void build(World&) {}
  virtual void run(World& world, const StepContext& step) = 0;
  // An observer: whether it will read the state when run at `now` (the stepping loop asks before
  // the step, so that the step completes the state for it). Unsure: true.
  virtual bool samples(const World& world, const StepContext& now) const {
    (void)world;
    (void)now;
    return true;
  }
  // Brings the state to the end of the last step run (work a step left to the next one); the
  // stepping loop calls it when it stops stepping.
  virtual void complete(World& world) { (void)world; }
};

template <class Derived>
class SystemBase : public System {
 public:
  Access access() const final { return access_of<Derived>(); }
};

}  // namespace gf

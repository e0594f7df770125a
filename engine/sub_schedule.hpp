// A schedule run k times per outer step at dt/k, as one system of the outer schedule: the DEM
// sub-steps of one liquid step, say. Sub-step s serves t + s dt/k; the outer schedule orders it by
// the union of its systems' accesses.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "engine/schedule.hpp"

namespace gf {

class SubSchedule : public System {
 public:
  SubSchedule(std::string name, int substeps, std::unique_ptr<Schedule> inner)
      : name_(std::move(name)), substeps_(substeps), inner_(std::move(inner)) {
    if (substeps_ < 1) throw std::invalid_argument("a sub-schedule runs at least once per step");
  }
  std::string_view name() const override { return name_; }
  Access access() const override { return inner_->access(); }
  void build(World& world) override { inner_->build(world); }
  void run(World& world, const StepContext& outer) override {
    (void)world;
    const double h = outer.dt / substeps_;
    for (int s = 0; s < substeps_; ++s) {
      StepContext c = outer;
      c.t = outer.t + s * h;
      c.dt = h;
      c.substep = s;
      c.substeps = substeps_;
      inner_->run_step(c);
    }
  }
  void complete(World& world) override { inner_->complete(world); }
  Schedule& inner() { return *inner_; }
  int substeps() const { return substeps_; }

 private:
  std::string name_;
  int substeps_;
  std::unique_ptr<Schedule> inner_;
};

}  // namespace gf

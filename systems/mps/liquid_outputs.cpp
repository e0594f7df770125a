#include "systems/mps/liquid_outputs.hpp"

#include "systems/mps/liquid_fraction.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_observables.hpp"

namespace gf {

namespace {

std::int64_t every(double interval, double dt) {
  return interval > 0 ? std::max<std::int64_t>(1, std::llround(interval / dt)) : 0;
}

void to_grains(const FluidNodes& f, double l0, Grains& g) {
  if (g.n != f.size()) g.resize(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) {
    g.pos.x[i] = f.x[i];
    g.pos.y[i] = f.y[i];
    g.pos.z[i] = f.z[i];
    g.vel.x[i] = f.u[i];
    g.vel.y[i] = f.v[i];
    g.vel.z[i] = f.w[i];
    g.radius.r[i] = 0.5 * l0;
    g.species.type[i] = f.kind[i];
    g.pid.id[i] = static_cast<std::int64_t>(i);
  }
}

}  // namespace

LiquidOutputs::LiquidOutputs(const std::filesystem::path& out, const LiquidScene& s, const CheckpointReader* resume)
    : s_(s), series_every_(every(s.output.series_interval, s.dt)), frame_every_(every(s.output.frame_interval, s.dt)) {
  if (series_every_) {
    const std::filesystem::path file = out / "series.csv";
    series_ = resume ? std::make_unique<SeriesCsv>(SeriesCsv::resume(
                           file, liquid_series_columns(), resume->value<std::uint64_t>("series_output.rows")))
                     : std::make_unique<SeriesCsv>(file, liquid_series_columns());
  }
  if (frame_every_) frames_ = std::make_unique<FrameSeries>(out);
  if (resume) restore(*resume);
}

void LiquidOutputs::observe(World& w) {
  const std::int64_t k = w.clock.step;
  if (series_ && k % series_every_ == 0) {
    series_->append(sample_liquid(w, s_));
    ++rows_;
  }
  if (frames_ && k % frame_every_ == 0) {
    const FluidNodes& f = w.tables.get<FluidNodes>();
    to_grains(f, s_.params.k.l0, scratch_);
    // A locally averaged liquid's frames carry each node's liquid fraction too.
    const LiquidFraction* eps = w.resources.find<LiquidFraction>();
    const bool with_eps = eps && eps->eps.size() == f.size();
    const PointScalars extra[] = {{"pressure", f.p.data()}, {"number_density", f.n.data()},
                                  {"liquid_fraction", with_eps ? eps->eps.data() : nullptr}};
    frames_->write(scratch_, w.clock.t, {}, std::span<const PointScalars>(extra, with_eps ? 3 : 2));
  }
}

void LiquidOutputs::save(CheckpointWriter& out) const {
  out.value("series_output.rows", static_cast<std::uint64_t>(rows_));
  out.vector("frame_output.times", frames_ ? frames_->times() : std::vector<double>{});
}

void LiquidOutputs::restore(const CheckpointReader& in) {
  rows_ = series_ ? in.value<std::uint64_t>("series_output.rows") : 0;
  if (!frames_) return;
  std::vector<double> times;
  in.vector("frame_output.times", times);
  frames_->resume(times);
}

}  // namespace gf

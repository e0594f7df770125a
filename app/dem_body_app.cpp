#include "app/dem_body_app.hpp"

#include "app/run_outcome.hpp"
#include "app/run_summary.hpp"
#include "app/run_model.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <memory>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/atomic_file.hpp"
#include "systems/analysis/body_repose.hpp"
#include "systems/analysis/packing.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/output/body_outputs.hpp"
#include "systems/output/checkpoint_output.hpp"
#include "systems/output/summary_json.hpp"
#include "systems/setup/dem_body_checkpoint.hpp"
#include "systems/setup/dem_simulation.hpp"

namespace gf {

namespace {

// Empty unless dt passes dt_safety of the rim contacts' period (BodiesSpec::rim): then what that
// risks and the step that keeps to it.
std::string rim_warning(const DemScene& s) {
  const CriticalStep& rim = s.bodies->rim;
  if (!(s.dt > s.dt_safety * rim.period)) return "";
  return "dt is " + short_number(s.dt / rim.period) + " of the period of a contact at a body's rim (" + rim.term +
         "; limit " + short_number(s.dt_safety) + "): flat grains pressed at several rim points at once, such as "
         "plates stacked face to face, can rock unstably (bodies jumping from step to step, kinetic-energy bursts in "
         "a settled bed); to be safe give run.dt = " + short_number(s.dt_safety * rim.period) + " or less";
}

struct BodyCounts {
  std::size_t moving = 0, fixed = 0, timed = 0, members = 0;
};

BodyCounts count_bodies(const DemScene& s, World& w) {
  BodyCounts c;
  for (const BodyPlacement& p : s.bodies->placed) {
    c.fixed += p.fixed;
    c.moving += !p.fixed;
    c.timed += p.remove_at >= 0;
  }
  c.members = w.tables.get<Members>().n;
  return c;
}

// What the body frames write of each body beside its state.
BodyFrameLabels frame_labels(const BodiesSpec& b) {
  BodyFrameLabels l;
  for (const BodyShape& sh : b.shapes) {
    l.shape_name.push_back(sh.name);
    l.shape_axes.emplace_back(sh.props.axes);
  }
  for (const BodyPlacement& p : b.placed) {
    l.shape.push_back(p.shape);
    l.group.push_back(p.group);
  }
  return l;
}

// The pictures' colours per body row, the legend for the PNG's Comment entry and the legend band's
// swatches (picture_legend.hpp).
std::vector<Rgb> picture_colours(const DemScene& s, const std::vector<int>& layers, std::string& legend,
                                 std::vector<PictureLegend::Entry>& entries) {
  const BodiesSpec& b = *s.bodies;
  const BodyOutputSpec& o = b.output;
  std::vector<Rgb> c(b.placed.size());
  std::vector<bool> seen(std::max<std::size_t>(b.shapes.size(), 64), false);
  for (std::size_t i = 0; i < c.size(); ++i) {
    const BodyPlacement& p = b.placed[i];
    c[i] = o.colour_by_layer ? layer_colour(std::max(layers[i], 0))
                             : group_colour(o.colour_by_shape ? static_cast<int>(p.shape) : p.group);
    const std::size_t key = o.colour_by_shape ? p.shape : static_cast<std::size_t>(p.group);
    if (o.colour_by_layer || p.fixed || key >= seen.size() || seen[key]) continue;
    seen[key] = true;
    entries.push_back({o.colour_by_shape ? b.shapes[p.shape].name : "group " + std::to_string(p.group), c[i]});
  }
  if (o.colour_by_layer)
    entries = {{"layers 1, 3, 5 (lowest first)", layer_colour(0)}, {"layers 2, 4", layer_colour(1)}};
  if (std::any_of(b.placed.begin(), b.placed.end(), [](const BodyPlacement& p) { return p.fixed; }))
    entries.push_back({"fixed", kFixedGrey});
  legend = o.colour_by_layer
               ? "five layers of equal counts by height at t = 0, lowest first: blue #0072B2, vermillion #D55E00, "
                 "blue, vermillion, blue; fixed bodies grey"
               : (o.colour_by_shape ? "by shape, Okabe-Ito palette from the first [[shape]]"
                                    : "by [[bodies]] group, Okabe-Ito palette from group 0")
                     + std::string(": blue, vermillion, bluish green, orange, reddish purple, sky blue, yellow; "
                                   "fixed bodies grey");
  return c;
}

// The outer edges of a shape: its cores' bounding box grown by the dilation radius on every side.
std::array<double, 3> outer_edges(const ShapeSpec& shape) {
  const ShapeBox b = core_box(shape);
  return {b.hi.x() - b.lo.x() + 2 * shape.radius, b.hi.y() - b.lo.y() + 2 * shape.radius,
          b.hi.z() - b.lo.z() + 2 * shape.radius};
}

// The packing of the final bed (systems/analysis/packing.hpp: bed_packing), sampled on voxels of a
// sixth of the thinnest moving shape's smallest edge. Its interior lies half a grain length (the
// largest outer edge of any moving shape) inside the bed's walls, above its floor and below its free
// surface: for the seed's flat letters three stroke widths, three letters lying flat on a wall. How
// the fraction depends on that choice is in "by_margin" (a quarter, a half and a whole grain length)
// and in packing.csv, the fraction per voxel layer from the floor: height (m, the layer's centre
// above the floor), interior (within the interior's columns), whole (across the bed's full extent).
// Returns summary.json's "packing" entry.
// The angle of repose of each [[analysis.repose]] heap in the final state (body_repose.hpp), in
// degrees, per flank with its slope, the columns fitted and their span; summary.json's "repose".
nlohmann::json final_repose(const DemScene& s, World& world) {
  const Gravity& g = world.resources.get<Gravity>();
  const double norm = std::sqrt(g.x * g.x + g.y * g.y + g.z * g.z);
  nlohmann::json out = nlohmann::json::object();
  if (s.bodies->output.repose.empty() || !(norm > 0)) return out;
  const V3<double> up{-g.x / norm, -g.y / norm, -g.z / norm};
  auto flank = [](const ReposeFlank& f) {
    nlohmann::json j = {{"columns", f.columns}, {"s_from", f.s_from}, {"s_to", f.s_to}};
    j["angle_deg"] = std::isfinite(f.angle) ? nlohmann::json(f.angle * 180.0 / std::numbers::pi) : nlohmann::json();
    j["slope"] = std::isfinite(f.slope) ? nlohmann::json(f.slope) : nlohmann::json();
    return j;
  };
  for (const ReposeSpec& spec : s.bodies->output.repose) {
    const Repose r = body_repose(world.tables.get<Bodies>(), world.tables.get<Members>(), up, spec);
    nlohmann::json j = {{"first", flank(r.first)}};
    if (spec.geometry != ReposeSpec::Geometry::heap) j["second"] = flank(r.second);
    j["extreme_height"] = std::isfinite(r.extreme_height) ? nlohmann::json(r.extreme_height) : nlohmann::json();
    j["column"] = spec.settings.column;
    out[spec.name] = j;
  }
  return out;
}

nlohmann::json final_packing(const DemScene& s, World& world, const std::filesystem::path& out) {
  const Gravity& g = world.resources.get<Gravity>();
  const double gv[3] = {g.x, g.y, g.z};
  int up = -1, along = 0;
  for (int d = 0; d < 3; ++d)
    if (gv[d] != 0.0) {
      up = d;
      ++along;
    }
  if (along != 1) return {{"valid", false}, {"reason", "gravity is not along one axis"}};
  double length = 0;
  for (const BodyPlacement& p : s.bodies->placed)
    if (!p.fixed)
      for (const double e : outer_edges(s.bodies->shapes[p.shape].shape)) length = std::max(length, e);
  const double h = s.bodies->output.overlap_scale / 6.0;
  if (!(length > 0) || !std::isfinite(h)) return {{"valid", false}, {"reason", "no moving bodies"}};
  auto vec = [](const std::array<double, 3>& v) { return nlohmann::json::array({v[0], v[1], v[2]}); };
  auto measure = [&](double margin, BedPacking& p) {
    p = bed_packing(world.tables.get<Bodies>(), world.tables.get<Members>(), up, gv[up] < 0 ? 1 : -1, margin, h);
    nlohmann::json j = {{"valid", p.valid}, {"margin", margin}};
    if (!p.valid) {
      j["reason"] = p.reason;
      return j;
    }
    j["fraction"] = p.interior.fraction;
    j["interior_voxels"] = p.interior.voxels;
    j["region"] = {{"lo", vec(p.lo)}, {"hi", vec(p.hi)}};
    return j;
  };
  BedPacking p, other;
  nlohmann::json j = measure(0.5 * length, p);
  j["by_margin"] = nlohmann::json::array({measure(0.25 * length, other), j, measure(length, other)});
  j["grain_length"] = length;
  j["voxel"] = h;
  j["up_axis"] = up;
  if (!p.valid) return j;
  j["whole_bed_fraction"] = p.whole.fraction;
  j["bed"] = {{"lo", vec(p.bed_lo)}, {"hi", vec(p.bed_hi)}};
  j["floor"] = p.floor;
  j["surface"] = p.surface;
  j["bed_depth"] = std::abs(p.surface - p.floor);
  std::string csv = "height,interior,whole\n";
  char line[96];
  for (const BedPacking::Layer& l : p.layers) {
    std::snprintf(line, sizeof line, "%.6g,%.6g,%.6g\n", l.height, l.interior, l.whole);
    csv += line;
  }
  write_file_atomic(out / "packing.csv", csv);
  return j;
}

}  // namespace

int check_body_command(const CliOptions& opt, const DemScene& s) {
  (void)opt;
  DemSimulation sim(s);
  sim.prime();
  const BodyCounts c = count_bodies(s, sim.world());
  std::printf("scene %s: valid\n", s.file.string().c_str());
  std::printf("model: composite grains (rigid unions of dilated convex polyhedra); contact law %s\n", s.law.c_str());
  std::printf("bodies: %zu moving, %zu fixed (%zu removed at a time); members: %zu; shapes: %zu; plane walls: %zu\n",
              c.moving, c.fixed, c.timed, c.members, s.bodies->shapes.size(), s.walls.size());
  for (const BodyShape& sh : s.bodies->shapes)
    std::printf("  shape %s: %zu parts, r = %.4g m, mass %.6g kg, volume %.6g m^3, moments %.4g %.4g %.4g kg m^2\n",
                sh.name.c_str(), sh.shape.parts.size(), sh.shape.radius, sh.props.mass, sh.props.volume,
                sh.props.moments.x(), sh.props.moments.y(), sh.props.moments.z());
  std::printf("systems per step (with the systems each waits for):\n%s", sim.step().describe().c_str());
  std::printf("observers: body_series_output, body_frame_output, body_picture_output\n");
  std::printf("critical step: smallest time-step term %.4g s (%s); dt = %.4g s = %.3f of it (limit %.3f)%s\n",
              s.critical.period, s.critical.term.c_str(), s.dt, s.dt / s.critical.period, s.dt_safety,
              s.allow_unstable_dt && s.dt > s.dt_safety * s.critical.period ? " OVERRIDDEN" : "");
  std::printf("rim contacts: smallest time-step term %.4g s (%s, each body's rim mass); dt = %.3f of it%s\n",
              s.bodies->rim.period, s.bodies->rim.term.c_str(), s.dt / s.bodies->rim.period,
              rim_warning(s).empty() ? "" : (" -- " + rim_warning(s)).c_str());
  std::printf("steps: %lld settling + %lld main (%.4g s simulated)\n", static_cast<long long>(s.settle_steps()),
              static_cast<long long>(s.main_steps()), s.duration);
  const BodyContactState& st = sim.world().resources.get<BodyContactState>();
  std::printf("initial contacts: %zu member pairs (%zu with fixed bodies), %zu with plane walls; list pairs %zu\n",
              st.last.pair_contacts, st.last.fixed_contacts, st.last.wall_contacts, st.list.pairs());
  if (s.output.checkpoint_interval > 0)
    std::printf("checkpoints: every %.4g s of the main stage%s\n", s.output.checkpoint_interval,
                s.output.checkpoint_at_end ? " and at its end" : "");
  else
    std::printf("checkpoints: %s\n", s.output.checkpoint_at_end ? "at the end of the run" : "none");
  return 0;
}

namespace {

// Composite bodies (DemSimulation with [[bodies]]), for the run skeleton (run_model.hpp).
class BodyModel final : public ScheduledModel {
 public:
  BodyModel(const DemScene& s, const std::function<void(World&)>& install) : s_(s), sim_(s) {
    if (install) install(sim_.world());
    counts_ = count_bodies(s, sim_.world());
  }

  std::string_view kind() const override { return "bodies"; }
  World& world() override { return sim_.world(); }
  Schedule& step() override { return sim_.step(); }
  RunCounts counts() override { return {static_cast<std::int64_t>(counts_.moving + counts_.fixed), 0}; }

  void restore(const CheckpointReader& from) override { restore_body_state(from, sim_.world(), s_); }
  std::string opening(std::size_t threads, int ranks) override {
    char line[320];
    std::snprintf(line, sizeof line,
                  "%zu moving and %zu fixed bodies (%zu members), dt = %.3g s (%.3f of the critical period), %zu threads%s",
                  counts_.moving, counts_.fixed, counts_.members, s_.dt, s_.dt / s_.critical.period, threads,
                  ranks > 1 ? (" on each of " + std::to_string(ranks) + " ranks").c_str() : "");
    return s_.file.string() + ": " + line;
  }
  std::string warning() const override { return rim_warning(s_); }
  void open_summary(nlohmann::json& summary) override;
  StageReport settle(double progress_seconds) override { return sim_.settle(progress_seconds); }
  void observe(Schedule& observers, const std::filesystem::path& out, const CheckpointReader* from) override;

  std::int64_t last_step() const override { return s_.main_steps(); }
  bool checkpoint_at_end() const override { return s_.output.checkpoint_at_end; }
  double rows(const World&) const override { return static_cast<double>(counts_.moving); }  // body-steps
  std::string rate(const nlohmann::json& summary) const override {
    char text[64];
    std::snprintf(text, sizeof text, "%.3g body-steps/s", summary["body_steps_per_second"].get<double>());
    return text;
  }

  void finish_outputs() override {
    series_->finish(sim_.world());
    if (frames_) frames_->finish(sim_.world());
  }
  void final_results(const std::filesystem::path& out, nlohmann::json& summary) override {
    try {
      const nlohmann::json packing = final_packing(s_, sim_.world(), out);
      const nlohmann::json repose = final_repose(s_, sim_.world());
      if (!packing.is_null()) summary["packing"] = packing;
      if (!repose.empty()) summary["repose"] = repose;
    } catch (const WriteError&) {
      throw;
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("the final packing or repose: ") + e.what());
    }
  }
  void close_summary(nlohmann::json& summary, const StageReport& main) override;
  std::string last_words() const override {
    if (!pictures_ || pictures_->last_picture().empty()) return "";
    return "last picture: " + pictures_->last_picture().string();
  }

 private:
  void restore_observers(const CheckpointReader& from);

  const DemScene& s_;
  DemSimulation sim_;
  BodyCounts counts_;
  BodySeriesOutput* series_ = nullptr;
  BodyFrameOutput* frames_ = nullptr;
  BodyPictureOutput* pictures_ = nullptr;
};

void BodyModel::open_summary(nlohmann::json& summary) {
  summary["bodies"] = {{"moving", counts_.moving}, {"fixed", counts_.fixed}, {"members", counts_.members}};
  for (const BodyShape& sh : s_.bodies->shapes)
    summary["shapes"][sh.name] = {{"parts", sh.shape.parts.size()}, {"mass", sh.props.mass}, {"volume", sh.props.volume},
                                  {"moments", {sh.props.moments[0], sh.props.moments[1], sh.props.moments[2]}}};
  summary["dt"] = s_.dt;
  summary["critical_period"] = s_.critical.period;
  summary["critical_term"] = s_.critical.term;
  summary["rim_critical_period"] = s_.bodies->rim.period;
  summary["rim_critical_term"] = s_.bodies->rim.term;
}

// The observers of the main stage, from the state at its start (layers, the remaining fraction's
// denominator, the pictures' window); a resumed run takes them and the observers' state from its
// checkpoint.
void BodyModel::observe(Schedule& observers, const std::filesystem::path& out, const CheckpointReader* from) {
  World& world = sim_.world();
  const Bodies& bodies = world.tables.get<Bodies>();
  const BodyOutputSpec& bo = s_.bodies->output;
  std::vector<int> layers;
  std::uint64_t initial_moving = 0;
  const double lowest = bo.has_sink ? bo.sink_height : std::numeric_limits<double>::quiet_NaN();
  BodyView view;
  if (from) {
    from->vector("body_run.layers", layers);
    initial_moving = from->value<std::uint64_t>("body_run.initial_moving");
    view = from->value<BodyView>("body_run.view");
    if (layers.size() != bodies.n) from->fail("its layers are not one per body", "resume with the scene of the run that wrote it");
  } else {
    layers = body_layers(bodies, world.resources.get<Gravity>());
    for (std::size_t i = 0; i < bodies.n; ++i) initial_moving += bodies.moving(i);
    view = body_view(bodies, world.tables.get<Members>(), bo.view_axis, bo.picture_size, lowest);
  }
  world.resources.emplace<BodySeriesRow>();
  BodySeriesSettings ss;
  if (s_.output.series_interval > 0) ss.csv = out / "series.csv";
  ss.interval = s_.output.series_interval > 0 ? s_.output.series_interval : 1000 * s_.dt;
  ss.overlap_scale = bo.overlap_scale;
  if (bo.has_outlet) ss.outlet_height = bo.outlet_height;
  ss.initial_moving = initial_moving;
  if (from) ss.resume_rows = from->value<std::uint64_t>("body_series_output.rows");
  for (const Wall& w : s_.walls) ss.wall_names.push_back(w.name);
  series_ = &observers.emplace<BodySeriesOutput>(ss);
  if (s_.output.frame_interval > 0)
    frames_ = &observers.emplace<BodyFrameOutput>(out, s_.output.frame_interval, frame_labels(*s_.bodies), layers);
  if (bo.picture_interval > 0) {
    std::string legend;
    std::vector<PictureLegend::Entry> entries;
    std::vector<Rgb> colours = picture_colours(s_, layers, legend, entries);
    pictures_ = &observers.emplace<BodyPictureOutput>(out / "pictures", bo.picture_interval, view, std::move(colours),
                                                      std::move(legend), std::move(entries));
  }
  std::vector<const Checkpointable*> parts{series_};
  if (frames_) parts.push_back(frames_);
  if (pictures_) parts.push_back(pictures_);
  checkpoints_ = &observers.emplace<CheckpointOutput>(
      CheckpointSettings{out, s_.output.checkpoint_interval, s_.output.checkpoint_keep_all},
      [this, layers, initial_moving, view](CheckpointWriter& w, World& wd) {
        save_body_state(w, wd, s_);
        w.vector("body_run.layers", layers);
        w.value("body_run.initial_moving", initial_moving);
        w.value("body_run.view", view);
      },
      parts);
  observers.build(world);
  if (from) restore_observers(*from);
}

void BodyModel::restore_observers(const CheckpointReader& from) {
  series_->restore(from);
  if (frames_) {
    if (!from.has("body_frame_output.next"))
      from.fail("the run that wrote it had no frames", "resume with output.frame_interval = 0, as that run had");
    frames_->restore(from);
  }
  if (pictures_) {
    if (!from.has("body_picture_output.next"))
      from.fail("the run that wrote it drew no pictures", "resume with output.picture_interval = 0, as that run had");
    pictures_->restore(from);
  }
  checkpoints_->restore(from);
}

void BodyModel::close_summary(nlohmann::json& summary, const StageReport& main) {
  World& world = sim_.world();
  const BodySeriesRow& row = world.resources.get<BodySeriesRow>();
  summary["body_steps_per_second"] =
      main.wall_seconds > 0 ? static_cast<double>(main.steps) * static_cast<double>(counts_.moving) / main.wall_seconds : 0.0;
  summary["member_list_rebuilds"] = world.resources.get<BodyContactState>().rebuilds;
  summary["frames"] = frames_ ? frames_->frames() : 0;
  summary["pictures"] = pictures_ ? pictures_->pictures() : 0;
  summary["final"] = {{"time", row.time},
                      {"ke_translational", row.ke_translational},
                      {"ke_rotational", row.ke_rotational},
                      {"contacts", row.contacts},
                      {"wall_contacts", row.wall_contacts},
                      {"max_overlap_ratio", row.max_overlap_ratio},
                      {"moving", row.moving}};
  if (s_.bodies->output.has_outlet) summary["final"]["remaining_fraction"] = number_or_null(row.remaining_fraction);
}

}  // namespace

int run_body_command(const CliOptions& opt, const DemScene& s, const BodyRunHooks& hooks) {
  RunPlace place;
  place.writer = hooks.writer;
  place.ranks = hooks.ranks;
  place.together = hooks.together;
  place.program = hooks.program;
  std::unique_ptr<BodyModel> model;
  if (hooks.together) hooks.together([&] { model = std::make_unique<BodyModel>(s, hooks.install); });
  else model = std::make_unique<BodyModel>(s, hooks.install);
  model->scene_json = hooks.scene_json;
  return run_model(*model, opt, place);
}

}  // namespace gf

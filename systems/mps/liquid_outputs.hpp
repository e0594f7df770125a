// series.csv and the VTK frames of a liquid run, sampled on the step grid (every round(interval / dt) steps,
// from step 0), with their state in checkpoints: the rows and the frame times written up to it. A resumed run
// keeps those, drops what the stopped run wrote after its checkpoint and continues both files from there.
//
// Frames reuse the DEM frame writer: nodes as points of radius l0/2, "type" = kind + 1 (1 fluid, 2 wall,
// 3 dummy), "velocity" and "speed", plus "pressure" (Pa) and "number_density" (the kernel sum n of the last
// step, at the predicted positions; n0 in the full lattice) of every node.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>

#include "engine/checkpoint_file.hpp"
#include "engine/grains.hpp"
#include "engine/system.hpp"
#include "engine/world.hpp"
#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/liquid_scene.hpp"
#include "systems/output/series_csv.hpp"
#include "systems/output/vtk_frames.hpp"

namespace gf {

// An observer system: the run loop runs it after every step (and at a new run's start), before the
// checkpoint output, which holds its state.
class LiquidOutputs : public SystemBase<LiquidOutputs>, public Checkpointable {
 public:
  using Reads = gf::Reads<FluidNodes, LiquidParams>;
  using Writes = gf::Writes<FrameSeries>;

  // Creates series.csv (output.series_interval > 0) and frames/ (output.frame_interval > 0) in `out`; with
  // `resume`, continues the files of the run that wrote that checkpoint instead.
  LiquidOutputs(const std::filesystem::path& out, const LiquidScene& s, const CheckpointReader* resume);

  std::string_view name() const override { return "liquid_outputs"; }
  // Writes the row and frame due at the world's current step, if any.
  void run(World& w, const StepContext&) override { observe(w); }
  void observe(World& w);
  std::size_t frames() const { return frames_ ? frames_->count() : 0; }
  std::size_t rows() const { return rows_; }

  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  const LiquidScene& s_;
  std::unique_ptr<SeriesCsv> series_;
  std::unique_ptr<FrameSeries> frames_;
  std::int64_t series_every_ = 0, frame_every_ = 0;  // steps, 0: none
  std::size_t rows_ = 0;
  Grains scratch_;
};

}  // namespace gf

// Periodic checkpoints of a run: `checkpoints/checkpoint.gfc` in the run folder, replaced
// atomically each time (a run killed while writing keeps the previous one), plus, when asked,
// a numbered copy per checkpoint. Scheduled after the other observers, so the outputs' own
// state (next sample time, frames written) is saved as of the same step as the world.
#pragma once

#include <filesystem>
#include <functional>
#include <vector>

#include "engine/checkpoint_file.hpp"
#include "engine/grains.hpp"
#include "engine/system.hpp"
#include "systems/output/dem_observers.hpp"
#include "systems/output/layer_output.hpp"
#include "systems/output/residence_csv.hpp"

namespace gf {

struct CheckpointSettings {
  std::filesystem::path dir;  // the run folder; files go to dir/checkpoints
  double interval = 0;        // s of simulated time between checkpoints; 0: only when asked (write)
  bool keep_all = false;      // also keep checkpoint_<step>.gfc for every checkpoint
};

class CheckpointOutput : public SystemBase<CheckpointOutput>, public Checkpointable {
 public:
  // Reads everything a checkpoint holds; the output resources order it after the other observers.
  using Reads = gf::Reads<Position, Velocity, AngularVelocity, Force, Torque, WallForce, WallTorque, Radius, Mass,
                          Species, ParticleId, SeriesRow, FrameSeries, DrumPictures, FlowState, ResidenceFile, LayerFile>;
  using Writes = gf::Writes<>;
  using SaveWorld = std::function<void(CheckpointWriter&, World&)>;

  CheckpointOutput(CheckpointSettings s, SaveWorld save_world, std::vector<const Checkpointable*> parts);
  std::string_view name() const override { return "checkpoint_output"; }
  void run(World& world, const StepContext& now) override;
  bool samples(const World&, const StepContext& now) const override { return due(now); }
  // Writes a checkpoint of the current state now; returns its path.
  std::filesystem::path write(World& world);
  std::size_t written() const { return written_; }

  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  bool due(const StepContext& now) const;  // a checkpoint is due at `now`
  CheckpointSettings s_;
  SaveWorld save_world_;
  std::vector<const Checkpointable*> parts_;
  double next_ = 0;
  std::size_t written_ = 0;
};

}  // namespace gf

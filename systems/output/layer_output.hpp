// layers.csv: the mixture quality of transverse layers of a continuous mixer (layer_cells and
// layer_quality in systems/analysis/mixing.hpp) at fixed distances from the inlet. A sample is
// taken every `interval` seconds; the cells of `pool` consecutive samples are pooled (each cell's
// contents summed over them) and one row per layer written for the pool: time (of its last sample),
// distance (m), vc, lacey, fraction_a, cells, grains (grain visits counted in the pooled cells).
// Flushed as it is written; a resumed run keeps the rows written up to its checkpoint and the
// samples of the pool in progress.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "engine/checkpoint_file.hpp"
#include "engine/system.hpp"
#include "systems/analysis/mixing.hpp"
#include "systems/contact/vec3.hpp"
#include "systems/output/series_csv.hpp"

namespace gf {

struct LayerSettings {
  std::int32_t type_a = 0;           // the key component
  V3<double> inlet{}, axis{1, 0, 0};  // m; unit axis from the inlet along the mixer
  std::vector<double> distances;     // m from the inlet
  double thickness = 0;              // m (the seed: the largest grain diameter)
  double cell = 0;                   // m, edge of the square sample cells in a layer
  int min_grains = 5;                // cells with fewer grains are not counted
  double interval = 0;               // s between samples
  int pool = 1;                      // samples pooled per row
};

// The layers.csv file a LayerOutput writes (a tag for the schedule).
struct LayerFile {};

class LayerOutput : public SystemBase<LayerOutput>, public Checkpointable {
 public:
  using Reads = gf::Reads<Position, Radius, Species>;
  using Writes = gf::Writes<LayerFile>;
  LayerOutput(std::filesystem::path file, LayerSettings s, std::optional<std::size_t> resume_rows);
  std::string_view name() const override { return "layer_output"; }
  void run(World& world, const StepContext& now) override;
  // Whether a sample is due at time t (the step dt sets the tolerance), and taking it from the grains
  // g (a run on ranks gives the grains gathered on one rank).
  bool due(double t, double dt) const;
  void sample(const Grains& g, double t, double dt);
  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  LayerSettings s_;
  std::unique_ptr<SeriesCsv> csv_;
  std::vector<LayerCells> pooled_;  // per distance, the samples of the pool in progress
  int samples_ = 0;                 // in the pool in progress
  double next_ = 0;
  std::size_t rows_ = 0;
};

}  // namespace gf

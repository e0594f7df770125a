// residence.csv of a continuous scene: one row per grain counted out at an outlet, written (and
// flushed) after the step that counted it, so a killed run keeps every row it produced.
// Columns: id, species (0-based, in [[species]] order), mass (kg), entry_time and exit_time (s),
// residence_time (s). A grain present from the start (a fill) was not fed: its entry and residence
// times are nan.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>

#include "engine/checkpoint_file.hpp"
#include "engine/system.hpp"
#include "systems/flow/flow_systems.hpp"
#include "systems/output/series_csv.hpp"

namespace gf {

// The residence CSV a ResidenceOutput writes (a tag for the schedule).
struct ResidenceFile {};

class ResidenceOutput : public SystemBase<ResidenceOutput>, public Checkpointable {
 public:
  using Reads = gf::Reads<>;
  using Writes = gf::Writes<FlowState, ResidenceFile>;
  // A resumed run keeps the first `resume_rows` rows of an existing file (those written up to the
  // checkpoint) and appends after them.
  ResidenceOutput(std::filesystem::path file, std::optional<std::size_t> resume_rows);
  std::string_view name() const override { return "residence_output"; }
  void run(World& world, const StepContext& now) override;
  std::size_t rows() const { return rows_; }
  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  std::unique_ptr<SeriesCsv> csv_;
  std::size_t rows_ = 0;
};

}  // namespace gf

#include "systems/output/residence_csv.hpp"

#include <array>
#include <string>
#include <vector>

namespace gf {

namespace {
std::vector<std::string> residence_columns() {
  return {"id", "species", "mass", "entry_time", "exit_time", "residence_time"};
}
}  // namespace

ResidenceOutput::ResidenceOutput(std::filesystem::path file, std::optional<std::size_t> resume_rows)
    : csv_(std::make_unique<SeriesCsv>(resume_rows ? SeriesCsv::resume(std::move(file), residence_columns(), *resume_rows)
                                                   : SeriesCsv(std::move(file), residence_columns()))),
      rows_(resume_rows.value_or(0)) {}

void ResidenceOutput::run(World& world, const StepContext&) {
  FlowState& f = world.resources.get<FlowState>();
  for (const ExitRecord& r : f.exits) {
    const std::array<double, 6> v{static_cast<double>(r.id), static_cast<double>(r.type), r.mass, r.entry, r.exit,
                                  r.exit - r.entry};
    csv_->append(v);
    ++rows_;
  }
  f.exits.clear();
}

void ResidenceOutput::save(CheckpointWriter& out) const {
  out.value("residence_output.rows", static_cast<std::uint64_t>(rows_));
}
void ResidenceOutput::restore(const CheckpointReader& in) {
  rows_ = in.value<std::uint64_t>("residence_output.rows");
}

}  // namespace gf

#include "systems/output/layer_output.hpp"

#include <array>
#include <string>

#include "systems/analysis/mixing.hpp"

namespace gf {

namespace {
std::vector<std::string> layer_columns() { return {"time", "distance", "vc", "lacey", "fraction_a", "cells", "grains"}; }
}  // namespace

LayerOutput::LayerOutput(std::filesystem::path file, LayerSettings s, std::optional<std::size_t> resume_rows)
    : s_(std::move(s)),
      csv_(std::make_unique<SeriesCsv>(resume_rows ? SeriesCsv::resume(std::move(file), layer_columns(), *resume_rows)
                                                   : SeriesCsv(std::move(file), layer_columns()))),
      rows_(resume_rows.value_or(0)) {}

void LayerOutput::run(World& world, const StepContext& now) {
  if (due(now.t, now.dt)) sample(world.grains, now.t, now.dt);
}

// Samples on the grid k * interval, up to the clock's round-off.
bool LayerOutput::due(double t, double dt) const { return t >= next_ - 1e-6 * dt; }

void LayerOutput::sample(const Grains& g, double t, double dt) {
  while (due(t, dt)) next_ += s_.interval;
  pooled_.resize(s_.distances.size());
  for (std::size_t k = 0; k < s_.distances.size(); ++k)
    pooled_[k].add(layer_cells(g, s_.type_a, s_.inlet, s_.axis, s_.distances[k], s_.thickness, s_.cell));
  if (++samples_ < s_.pool) return;
  for (std::size_t k = 0; k < s_.distances.size(); ++k) {
    const LayerMixing m = layer_quality(pooled_[k], s_.min_grains);
    const std::array<double, 7> v{t,            s_.distances[k], m.vc, m.lacey, m.fraction_a,
                                  static_cast<double>(m.cells), static_cast<double>(m.grains)};
    csv_->append(v);
    ++rows_;
  }
  pooled_.clear();
  samples_ = 0;
}

// The pool in progress as flat arrays (no padding bytes in the checkpoint): per layer its cell
// count, then every cell's coordinates and contents, and the layer's totals.
void LayerOutput::save(CheckpointWriter& out) const {
  out.value("layer_output.next", next_);
  out.value("layer_output.rows", static_cast<std::uint64_t>(rows_));
  out.value("layer_output.samples", samples_);
  std::vector<std::int64_t> counts, keys, grains;
  std::vector<double> volumes, totals;
  for (const LayerCells& l : pooled_) {
    counts.push_back(static_cast<std::int64_t>(l.cells.size()));
    for (const auto& [key, c] : l.cells) {
      keys.insert(keys.end(), {key.first, key.second});
      grains.push_back(c.grains);
      volumes.insert(volumes.end(), {c.volume, c.volume_a});
    }
    totals.insert(totals.end(), {l.volume, l.volume_a, l.volume_sq, l.volume_sq_a});
  }
  out.vector("layer_output.counts", std::move(counts));
  out.vector("layer_output.keys", std::move(keys));
  out.vector("layer_output.grains", std::move(grains));
  out.vector("layer_output.volumes", std::move(volumes));
  out.vector("layer_output.totals", std::move(totals));
}

void LayerOutput::restore(const CheckpointReader& in) {
  next_ = in.value<double>("layer_output.next");
  rows_ = in.value<std::uint64_t>("layer_output.rows");
  samples_ = in.value<int>("layer_output.samples");
  std::vector<std::int64_t> counts, keys, grains;
  std::vector<double> volumes, totals;
  in.vector("layer_output.counts", counts);
  in.vector("layer_output.keys", keys);
  in.vector("layer_output.grains", grains);
  in.vector("layer_output.volumes", volumes);
  in.vector("layer_output.totals", totals);
  std::size_t cells = 0;
  bool counts_ok = true;
  for (const std::int64_t c : counts) {
    counts_ok = counts_ok && c >= 0 && static_cast<std::size_t>(c) <= keys.size();
    if (counts_ok) cells += static_cast<std::size_t>(c);
  }
  if (!counts_ok || samples_ < 0 || samples_ >= s_.pool || totals.size() != 4 * counts.size() || keys.size() != 2 * cells ||
      grains.size() != cells || volumes.size() != 2 * cells || (!counts.empty() && counts.size() != s_.distances.size()))
    in.fail("its layer samples do not match the scene's [analysis.layers]",
            "resume with the scene's original [analysis.layers] table");
  pooled_.assign(counts.size(), LayerCells{});
  std::size_t at = 0;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    LayerCells& l = pooled_[k];
    for (std::int64_t c = 0; c < counts[k]; ++c, ++at)
      l.cells[{keys[2 * at], keys[2 * at + 1]}] = {volumes[2 * at + 1], volumes[2 * at], static_cast<int>(grains[at])};
    l.volume = totals[4 * k];
    l.volume_a = totals[4 * k + 1];
    l.volume_sq = totals[4 * k + 2];
    l.volume_sq_a = totals[4 * k + 3];
  }
}

}  // namespace gf

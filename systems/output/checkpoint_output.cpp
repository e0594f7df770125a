#include "systems/output/checkpoint_output.hpp"

#include <cstdio>

#include "engine/atomic_file.hpp"

namespace gf {

CheckpointOutput::CheckpointOutput(CheckpointSettings s, SaveWorld save_world, std::vector<const Checkpointable*> parts)
    : s_(std::move(s)), save_world_(std::move(save_world)), parts_(std::move(parts)) {
  ensure_directory(s_.dir / "checkpoints");
}

bool CheckpointOutput::due(const StepContext& now) const {
  return s_.interval > 0 && now.t >= next_ - 1e-6 * now.dt;
}

void CheckpointOutput::run(World& world, const StepContext& now) {
  if (!due(now)) return;
  const double t = now.t, dt = now.dt;
  while (t >= next_ - 1e-6 * dt) next_ += s_.interval;  // stays on the grid k * interval
  write(world);
}

std::filesystem::path CheckpointOutput::write(World& world) {
  CheckpointWriter out;
  save_world_(out, world);
  for (const Checkpointable* p : parts_) p->save(out);
  save(out);
  const std::filesystem::path latest = s_.dir / "checkpoints" / "checkpoint.gfc";
  if (s_.keep_all) {
    char name[48];
    std::snprintf(name, sizeof name, "checkpoint_%012lld.gfc", static_cast<long long>(world.clock.step));
    out.write(s_.dir / "checkpoints" / name);
  }
  out.write(latest);
  ++written_;
  return latest;
}

void CheckpointOutput::save(CheckpointWriter& out) const { out.value("checkpoint_output.next", next_); }
void CheckpointOutput::restore(const CheckpointReader& in) { next_ = in.value<double>("checkpoint_output.next"); }

}  // namespace gf

#include "systems/broadphase/broadphase_checkpoint.hpp"

#include <cstdint>

namespace gf {

void save_broadphase(CheckpointWriter& out, const BroadphaseState& bp, const std::string& prefix) {
  const std::string p = prefix + "broadphase.";
  out.value(p + "skin", bp.skin);
  out.value(p + "valid", bp.valid);
  out.value(p + "force_rebuild", bp.force_rebuild);
  out.value(p + "rebuilds", bp.rebuilds);
  out.value(p + "checks", bp.checks);
  out.value(p + "kept", bp.cover.kept);
}

void restore_broadphase(const CheckpointReader& in, BroadphaseState& bp, const std::string& prefix) {
  const std::string p = prefix + "broadphase.";
  bp.valid = in.value<bool>(p + "valid");
  bp.force_rebuild = in.value<bool>(p + "force_rebuild");
  bp.rebuilds = in.value<std::int64_t>(p + "rebuilds");
  bp.checks = in.value<std::int64_t>(p + "checks");
  bp.cover.kept = in.has(p + "kept") ? in.value<std::int64_t>(p + "kept") : 0;
}

}  // namespace gf

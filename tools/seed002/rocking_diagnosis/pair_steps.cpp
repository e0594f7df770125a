// Records how docs/seed002/packing/stroke40/O_unstable/diagnosis.txt was made: resumes the O pour
// (0.04 m strokes, dt 1e-4 s) from its 5.5 s checkpoint (copied to /tmp/o_diag), advances SKIP steps and
// prints members 398 and 497 (the pair the overlap stop named) step by step: overlap both ways and
// the cores' vertices. Build against the Release library from the repository root:
//   c++ -std=c++20 -O2 -DNDEBUG -DTOML_HEADER_ONLY=0 -DTOML_SHARED_LIB=1 -I. -isystem /usr/include/eigen3 \
//     tools/seed002/rocking_diagnosis/pair_steps.cpp -o /tmp/pair_steps build/libgrainflow_core.a \
//     -ltbb -ltomlplusplus -lpng -lz -lccd
//   /tmp/pair_steps 4664 > /tmp/diag/out.txt
#include <cstdio>
#include <exception>
#include "systems/setup/dem_simulation.hpp"
#include "systems/bodies/member_geometry.hpp"
#include "systems/bodies/bodies.hpp"

int main(int argc, char** argv) {
  const long skip = std::atol(argv[1]);
  auto sim = gf::DemSimulation::from_file("scenes/packing_seed002_letters.toml",
      {"shape.0.letter=\"O\"", "shape.0.stroke=0.04", "run.max_overlap=0.3", "run.duration=6"});
  sim.resume(gf::CheckpointReader("/tmp/o_diag/checkpoints/checkpoint.gfc"));
  sim.advance(skip);
  auto& w = sim.world();
  for (int k = 0; k < 30; ++k) {
    auto& b = w.tables.get<gf::Bodies>();
    auto& m = w.tables.get<gf::Members>();
    gf::place_members(b, m);
    const gf::MemberShape sa = gf::member_shape(b, m, 398), sb = gf::member_shape(b, m, 497);
    const gf::MemberContact c = gf::member_member(sa, sb);
    const gf::MemberContact r = gf::member_member(sb, sa);
    std::printf("step %ld delta %.6g n %.4f %.4f %.4f | swapped delta %.6g n %.4f %.4f %.4f\n", skip + k, c.delta,
                c.n.x(), c.n.y(), c.n.z(), r.delta, r.n.x(), r.n.y(), r.n.z());
    std::printf("radius %.9g %.9g\n", sa.radius, sb.radius);
    for (std::size_t i = 0; i < sa.vertices(); ++i) std::printf("VA %ld %.17g %.17g %.17g\n", skip + k, sa.vertex(i).x(), sa.vertex(i).y(), sa.vertex(i).z());
    for (std::size_t i = 0; i < sb.vertices(); ++i) std::printf("VB %ld %.17g %.17g %.17g\n", skip + k, sb.vertex(i).x(), sb.vertex(i).y(), sb.vertex(i).z());
    std::printf("core_distance %.9g kind %d\n", c.core_distance, static_cast<int>(c.kind));
    for (int q = 0; q < 4; ++q) {
      const gf::MemberShape s2 = gf::member_shape(b, m, 496 + q);
      const gf::MemberContact c2 = gf::member_member(sa, s2);
      std::printf("   398 vs %d: delta %.6g\n", 496 + q, c2.delta);
    }
    try { sim.advance(1); } catch (const std::exception& e) { std::printf("stop: %s\n", e.what()); break; }
  }
}

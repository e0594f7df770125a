// The scene head the composite-grain tests share: dt 1e-5 s, a 1 mm skin and the linear
// spring-dashpot law with kn = 1e4 N/m, kt = 6e3 N/m, restitution 0.5 and friction 0.5, no rolling
// spring; `run` adds keys to [run] (duration, gravity), `rest` the shapes, bodies and walls.
#pragma once

#include <string>

namespace gf::test {

inline std::string body_scene(const std::string& run, const std::string& rest) {
  return "[run]\ndt = 1.0e-5\n" + run + "skin = 1.0e-3\n\n"
         "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1.0e4\nkt = 6.0e3\nkr = 0.0\n"
         "en = 0.5\net = 0.5\ner = 0.5\nfriction = 0.5\nrolling_friction = 0.0\n\n" + rest;
}

}  // namespace gf::test

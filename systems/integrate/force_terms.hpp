// The force and torque contributions the integrator sums: each system that produces a force on the
// grains declares its component here (a = sum of terms / m + g, alpha = sum of torques / I). A new
// force (drag from a liquid, say) is one more term, not an edit of the integrator.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "engine/grains.hpp"
#include "engine/type_id.hpp"

namespace gf {

struct Vec3Columns {
  const double* x;
  const double* y;
  const double* z;
};

struct ForceTerm {
  std::string_view name;        // the system that fills it
  std::size_t force = 0;        // component type ids, for the schedule's edges
  std::size_t torque = 0;       // meaningful when has_torque
  bool has_torque = false;
  Vec3Columns (*force_columns)(Grains&) = nullptr;
  Vec3Columns (*torque_columns)(Grains&) = nullptr;
};

// A term whose force lives in component F (columns x, y, z) and, unless T is void, torque in T.
template <class F, class T = void>
ForceTerm force_term(std::string_view name) {
  ForceTerm t;
  t.name = name;
  t.force = type_id<F>();
  t.force_columns = [](Grains& g) -> Vec3Columns {
    F& c = component<F>(g);
    return {c.x.data(), c.y.data(), c.z.data()};
  };
  if constexpr (!std::is_void_v<T>) {
    t.has_torque = true;
    t.torque = type_id<T>();
    t.torque_columns = [](Grains& g) -> Vec3Columns {
      T& c = component<T>(g);
      return {c.x.data(), c.y.data(), c.z.data()};
    };
  }
  return t;
}

inline constexpr std::size_t kMaxForceTerms = 6;

struct ForceTerms {
  std::vector<ForceTerm> list;
};

}  // namespace gf

#include "systems/walls/walls.hpp"

#include <cmath>
#include <string>

#include "engine/checkpoint_file.hpp"

namespace gf {

Vec3d rotate_about(const Vec3d& v, const Vec3d& k, double angle) {
  // Rodrigues: v cos + (k x v) sin + k (k.v)(1 - cos).
  const double c = std::cos(angle), s = std::sin(angle);
  const Vec3d kxv = cross(k, v);
  const double kv = dot(k, v);
  return {v.x * c + kxv.x * s + k.x * kv * (1 - c), v.y * c + kxv.y * s + k.y * kv * (1 - c),
          v.z * c + kxv.z * s + k.z * kv * (1 - c)};
}

void Walls::place(double t, double lag) {
  for (std::size_t i = 0; i < list.size(); ++i) {
    Wall& w = list[i];
    const double a = angle(i, t);
    const Vec3d d = rotation_enabled ? w.motion.offset(t) : Vec3d{0, 0, 0};
    w.cur_velocity = rotation_enabled ? w.motion.rate(t - lag) : Vec3d{0, 0, 0};
    w.cur_spin = (rotation_enabled ? w.omega : 0.0) * w.rot_axis;
    w.cur_origin = w.rot_point + d;
    if (a == 0.0) {
      w.cur_point = w.point + d;
      w.cur_normal = w.normal;
      w.cur_center = w.center + d;
      w.cur_axis = w.axis;
      continue;
    }
    w.cur_point = w.cur_origin + rotate_about(w.point - w.rot_point, w.rot_axis, a);
    w.cur_normal = rotate_about(w.normal, w.rot_axis, a);
    w.cur_center = w.cur_origin + rotate_about(w.center - w.rot_point, w.rot_axis, a);
    w.cur_axis = rotate_about(w.axis, w.rot_axis, a);
  }
}

double wall_gap(const Wall& w, const Vec3d& p, Vec3d& towards) {
  if (w.kind == Wall::Kind::Plane) {
    towards = -w.cur_normal;
    return dot(p - w.cur_point, w.cur_normal);
  }
  const Vec3d q = p - w.cur_center;
  const Vec3d radial = q - dot(q, w.cur_axis) * w.cur_axis;
  const double rho = std::sqrt(dot(radial, radial));
  if (rho > 0.0) {
    towards = (1.0 / rho) * radial;
  } else {
    // On the axis every direction is equally far; pick one perpendicular to the axis.
    const Vec3d trial = std::abs(w.cur_axis.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
    const Vec3d perp = trial - dot(trial, w.cur_axis) * w.cur_axis;
    towards = (1.0 / std::sqrt(dot(perp, perp))) * perp;
  }
  return w.radius - rho;
}

void save_wall_loads(CheckpointWriter& out, const std::string& key, const WallLoads& l) {
  std::vector<double> v;
  for (const WallLoad& w : l.sum) append_wall_load(v, w);
  out.vector(key + ".sum", std::move(v));
  out.value(key + ".steps", l.steps);
}

void restore_wall_loads(const CheckpointReader& in, const std::string& key, WallLoads& l) {
  if (!in.has(key + ".sum")) return;
  std::vector<double> v;
  in.vector(key + ".sum", v);
  in.require(v.size() % kWallLoadNumbers == 0, "the walls' load sums", "resume with the scene that wrote the checkpoint");
  l.sum.resize(v.size() / kWallLoadNumbers);
  for (std::size_t w = 0; w < l.sum.size(); ++w) l.sum[w] = wall_load_of(&v[kWallLoadNumbers * w]);
  l.steps = in.value<std::int64_t>(key + ".steps");
}

}  // namespace gf

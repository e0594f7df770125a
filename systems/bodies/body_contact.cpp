#include "systems/bodies/body_contact.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include <Eigen/Geometry>

#include "engine/run_loop.hpp"
#include "systems/bodies/member_geometry.hpp"
#include "systems/contact/laws.hpp"

namespace gf {

namespace {

using Eigen::Vector3d;

// ---- Broadphase ----------------------------------------------------------------------------------

double largest_bound(const Members& m) {
  double r = 0.0;
  for (std::size_t i = 0; i < m.n; ++i) r = std::max(r, m.bound.radius[i]);
  return r;
}

// The grid coordinates (along the grid's own axes) of the cell with index c.
std::array<std::int64_t, 3> cell_coords(const CellGrid& grid, std::uint32_t c) {
  const std::int64_t ci = c;
  return {ci % grid.dims[0], (ci / grid.dims[0]) % grid.dims[1], ci / (grid.dims[0] * grid.dims[1])};
}

bool within_reach(const Members& m, std::size_t i, std::size_t j, double skin) {
  const double dx = m.centre.x[j] - m.centre.x[i], dy = m.centre.y[j] - m.centre.y[i],
               dz = m.centre.z[j] - m.centre.z[i];
  const double reach = m.bound.radius[i] + m.bound.radius[j] + skin;
  return dx * dx + dy * dy + dz * dz < reach * reach;
}

Motion motion_of(const BodyContactState& s, std::size_t m) {
  return s.motion.size() > m ? static_cast<Motion>(s.motion[m]) : Motion::moving;
}

// Whether members i and j can touch: of different bodies, at least one moving, neither removed.
bool may_touch(const Members& m, const BodyContactState& s, std::size_t i, std::size_t j) {
  if (m.body.row[j] == m.body.row[i]) return false;
  const Motion a = motion_of(s, i), b = motion_of(s, j);
  return a != Motion::removed && b != Motion::removed && (a == Motion::moving || b == Motion::moving);
}

// Member i's partners j > i of other bodies within reach, from the 27 cells around i's, ascending.
void partners_of(const Members& m, const BodyContactState& st, const CellGrid& grid, double skin, std::size_t i,
                 std::vector<std::uint32_t>& out) {
  out.clear();
  if (motion_of(st, i) == Motion::removed) return;
  const auto c = cell_coords(grid, grid.cell_of[i]);
  for (std::int64_t z = std::max<std::int64_t>(c[2] - 1, 0); z <= std::min(c[2] + 1, grid.dims[2] - 1); ++z)
    for (std::int64_t y = std::max<std::int64_t>(c[1] - 1, 0); y <= std::min(c[1] + 1, grid.dims[1] - 1); ++y)
      for (std::int64_t x = std::max<std::int64_t>(c[0] - 1, 0); x <= std::min(c[0] + 1, grid.dims[0] - 1); ++x) {
        const auto cell = static_cast<std::size_t>((z * grid.dims[1] + y) * grid.dims[0] + x);
        for (std::uint32_t s = grid.start[cell]; s < grid.start[cell + 1]; ++s) {
          const std::uint32_t j = grid.order[s];
          if (j > i && may_touch(m, st, i, j) && within_reach(m, i, j, skin)) out.push_back(j);
        }
      }
  std::sort(out.begin(), out.end());
}

// Every pair in reach, in key order (by the lower member, then the higher). A pair of a moving and a
// fixed member lists the moving one as a (the owner), so that the law sees the fixed one as its wall.
void find_pairs(const Members& m, BodyContactState& s, std::vector<std::uint32_t>& a, std::vector<std::uint32_t>& b) {
  s.grid.build({m.centre.x.data(), m.n}, {m.centre.y.data(), m.n}, {m.centre.z.data(), m.n},
               2.0 * largest_bound(m) + s.skin);
  std::vector<std::vector<std::uint32_t>> found(m.n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.n, 64), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) partners_of(m, s, s.grid, s.skin, i, found[i]);
  });
  a.clear(), b.clear();
  for (std::size_t i = 0; i < m.n; ++i)
    for (std::uint32_t j : found[i]) {
      const bool swap = motion_of(s, i) == Motion::fixed;
      a.push_back(swap ? j : static_cast<std::uint32_t>(i)), b.push_back(swap ? static_cast<std::uint32_t>(i) : j);
    }
}

// The history entries of pairs still listed, at their new list indices. Both key lists increase, and
// the old entries are in old list order, so the new entries come out in new list order.
void carry_history(const std::vector<std::uint64_t>& old_keys, const std::vector<std::uint64_t>& new_keys,
                   PairHistory& h) {
  std::size_t kept = 0;
  for (std::size_t e = 0; e < h.size(); ++e) {
    const std::uint64_t key = old_keys[static_cast<std::size_t>(h.pair[e])];
    const auto it = std::lower_bound(new_keys.begin(), new_keys.end(), key);
    if (it == new_keys.end() || *it != key) continue;
    h.pair[kept] = static_cast<std::int32_t>(it - new_keys.begin());
    for (std::size_t q = 0; q < h.width; ++q) h.value[q][kept] = h.value[q][e];
    ++kept;
  }
  h.resize(kept);
  h.map_slots(new_keys.size());
}

// ---- The law's inputs ----------------------------------------------------------------------------

Vector3d body_velocity(const Bodies& b, std::size_t i) { return {b.vel.x[i], b.vel.y[i], b.vel.z[i]}; }
Vector3d body_spin(const Bodies& b, std::size_t i) { return {b.omega.x[i], b.omega.y[i], b.omega.z[i]}; }

// Member m as the law's constants see it (the header says why each field is what it is).
template <class L>
ContactBody<typename L::Material> contact_body(const Bodies& bodies, const Members& members,
                                               const BodyContactModel<L>& model, std::size_t m) {
  const std::uint32_t b = members.body.row[m];
  ContactBody<typename L::Material> c;
  c.mass = bodies.mass.m[b];
  c.inertia = std::min({bodies.inertia.i1[b], bodies.inertia.i2[b], bodies.inertia.i3[b]});
  c.radius = members.dilation.r[m];
  c.material = model.material;
  c.wall = !bodies.moving(b);  // a fixed body meets the others as a wall (infinite mass)
  return c;
}

template <std::size_t K>
void store_constants(const std::array<double, K>& k, std::vector<double>& out, const char* what) {
  for (double v : k)
    if (!std::isfinite(v))
      throw std::invalid_argument(std::string("the contact law's constants for ") + what +
                                  " are not finite: check the bodies' material and the members' dilation radii "
                                  "(a law that needs a radius takes r, which must then be positive)");
  out.insert(out.end(), k.begin(), k.end());
}

// The law's constants of every listed pair and of every member against a wall.
template <class L>
void refresh_constants(const Bodies& bodies, const Members& members, const BodyContactModel<L>& model,
                       MemberPairList& list) {
  list.width = L::kConstants;
  list.constants.clear(), list.wall_constants.clear();
  for (std::size_t k = 0; k < list.pairs(); ++k) {
    const auto b = contact_body(bodies, members, model, list.b[k]);  // a is the moving one of the pair
    store_constants(L::constants(contact_body(bodies, members, model, list.a[k]), b, b.wall ? model.wall : model.pair),
                    list.constants, "a member pair");
  }
  ContactBody<typename L::Material> wall;
  wall.wall = true;
  for (std::size_t m = 0; m < members.n; ++m)
    store_constants(L::constants(contact_body(bodies, members, model, m), wall, model.wall), list.wall_constants,
                    "a member against a wall");
}

void check_members(const Bodies& bodies, const Members& members) {
  for (std::size_t m = 0; m < members.n; ++m)
    if (members.body.row[m] >= bodies.n)
      throw std::invalid_argument("member " + std::to_string(m) + " names body row " +
                                  std::to_string(members.body.row[m]) + ", past the last of " +
                                  std::to_string(bodies.n) + " bodies");
}

// The wall history's shape follows the members and planes; a new shape starts every spring at zero.
void shape_wall_history(MemberWallHistory& w, std::size_t members, std::size_t planes, std::size_t width) {
  w.load.resize(members * planes * MemberWallHistory::kLoad);  // a restored state has none
  if (w.members == members && w.planes == planes && w.width == width) return;
  w.members = members, w.planes = planes, w.width = width;
  w.value.assign(members * planes * width, 0.0);
  w.touching.assign(members * planes, 0);
}

// ---- Evaluation ----------------------------------------------------------------------------------

using Outcome = ContactOutcome;

Vector3d eig(const V3<double>& v) { return {v.x, v.y, v.z}; }

// Runs law L on a touching contact between bodies A (the owner) and B (none for a wall), with the
// law's constants k and history h (read and written).
// A wall moves at wall_velocity and turns at wall_spin (c.arm_b from its rotation point).
template <class L>
Outcome evaluate(const Bodies& bodies, const MemberContact& c, std::size_t body_a, std::ptrdiff_t body_b,
                 const double* k, double* h, double dt, const Vector3d& wall_spin = Vector3d::Zero(),
                 const Vector3d& wall_velocity = Vector3d::Zero()) {
  const bool wall = body_b < 0;
  const auto b = static_cast<std::size_t>(wall ? 0 : body_b);
  const ContactGeometry<double> g =
      contact_geometry(c, body_velocity(bodies, body_a), body_spin(bodies, body_a),
                       wall ? wall_velocity : body_velocity(bodies, b), wall ? wall_spin : body_spin(bodies, b));
  std::array<double, L::kConstants> kc;
  std::copy(k, k + L::kConstants, kc.begin());
  std::array<double, L::kHistory> hs;
  std::copy(h, h + L::kHistory, hs.begin());
  const ContactForce<double> r = L::evaluate(true, g, kc, dt, hs);
  Outcome o;
  o.touching = true;
  o.delta = c.delta;
  o.force = eig(r.force);
  o.torque_a = c.arm_a.cross(o.force) + eig(r.torque_i);
  o.torque_b = c.arm_b.cross(-o.force) + eig(r.torque_j);
  std::copy(hs.begin(), hs.end(), o.history.begin());
  return o;
}

// The listed pairs of b (every one without a split), in parallel: geometry, then the law where the
// members touch.
template <class L>
std::vector<Outcome> evaluate_pairs(const Bodies& bodies, const Members& members,
                                    const std::vector<MemberShape>& shapes, const BodyContactState& s, double dt,
                                    const SplitBlocks& b) {
  const MemberPairList& list = s.list;
  std::vector<Outcome> out(list.pairs());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b.count(list.pairs()), 16), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const std::size_t k = b.item(j);
      const MemberContact c = member_member(shapes[list.a[k]], shapes[list.b[k]]);
      if (!c.touching()) continue;
      std::array<double, kMaxHistory> h{};
      const std::int32_t e = s.history.slot[k];
      for (std::size_t q = 0; q < s.history.width && e >= 0; ++q) h[q] = s.history.value[q][static_cast<std::size_t>(e)];
      out[k] = evaluate<L>(bodies, c, members.body.row[list.a[k]], members.body.row[list.b[k]],
                           &list.constants[k * L::kConstants], h.data(), dt);
    }
  });
  return out;
}

// The members of b against every plane, in parallel; the springs of (member, plane) pairs apart
// reset. Per member, its walls' forces and torques summed in plane order.
template <class L>
std::vector<Outcome> evaluate_walls(const Bodies& bodies, const Members& members, const BodyPlanes& planes,
                                    const std::vector<MemberShape>& shapes, BodyContactState& s, double dt,
                                    bool turning, const SplitBlocks& b) {
  std::vector<Outcome> out(members.n);
  MemberWallHistory& w = s.walls;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b.count(members.n), 16), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const std::size_t m = b.item(j);
      for (std::size_t p = 0; p < planes.list.size(); ++p) {
        double* h = w.at(m, p);
        if (!bodies.moving(members.body.row[m])) {  // fixed on a wall, or removed: no contact
          w.touching[m * w.planes + p] = 0;
          std::fill(h, h + w.width, 0.0);
          continue;
        }
        const BodyPlane& wall = planes.list[p];
        const Vector3d point = wall.point + wall.offset;
        MemberContact c = wall.cylinder ? member_cylinder(shapes[m], point, wall.normal, wall.radius)
                                        : member_plane(shapes[m], point, wall.normal);
        w.touching[m * w.planes + p] = c.touching();
        if (!c.touching()) {
          std::fill(h, h + w.width, 0.0);
          continue;
        }
        // A turning wall's surface moves at v + omega rot_axis x (point - rot_point) under the contact.
        const Vector3d origin = wall.rot_point + wall.offset;
        const double omega = turning ? wall.omega : 0.0;
        if (omega != 0.0) c.arm_b = c.point - origin;
        const std::size_t body = members.body.row[m];
        const Outcome o = evaluate<L>(bodies, c, body, -1, &s.list.wall_constants[m * L::kConstants], h, dt,
                                      omega * wall.rot_axis, wall.velocity);
        std::copy(o.history.begin(), o.history.begin() + static_cast<std::ptrdiff_t>(w.width), h);
        // The load on the member: its force, and its moment about the wall's rotation point.
        const Vector3d centre(bodies.pos.x[body], bodies.pos.y[body], bodies.pos.z[body]);
        const Vector3d moment = (centre - origin).cross(o.force) + o.torque_a;
        double* load = w.load_at(m, p);
        for (int q = 0; q < 3; ++q) load[q] = o.force[q], load[3 + q] = moment[q];
        out[m].touching = true;
        out[m].delta = std::max(out[m].delta, o.delta);
        out[m].force += o.force;
        out[m].torque_a += o.torque_a;
      }
    }
  });
  return out;
}

void add_to_body(Bodies& b, std::size_t i, const Vector3d& f, const Vector3d& t) {
  b.force.x[i] += f.x(), b.force.y[i] += f.y(), b.force.z[i] += f.z();
  b.torque.x[i] += t.x(), b.torque.y[i] += t.y(), b.torque.z[i] += t.z();
}

void zero_loads(Bodies& b) {
  for (ColumnD* c : {&b.force.x, &b.force.y, &b.force.z, &b.torque.x, &b.torque.y, &b.torque.z})
    std::fill(c->begin(), c->end(), 0.0);
}

// A new largest overlap, between members a and b (b = -1: a against a wall).
void note_worst(BodyContactReport& report, OverlapSite& site, const Bodies& bodies, const Members& members,
                double delta, std::int64_t a, std::int64_t b) {
  report.max_overlap = delta;
  const std::uint32_t body = members.body.row[static_cast<std::size_t>(a)];
  site.member[0] = a, site.member[1] = b;
  site.body[0] = body, site.body[1] = b < 0 ? -1 : members.body.row[static_cast<std::size_t>(b)];
  site.centre[0] = bodies.pos.x[body], site.centre[1] = bodies.pos.y[body], site.centre[2] = bodies.pos.z[body];
}

// The pairs' sums in list order (so the result does not depend on the thread count) and the
// history of the touching pairs, packed in list order.
void sum_pairs(Bodies& bodies, const Members& members, const std::vector<Outcome>& out, BodyContactState& s,
               BodyContactReport& report, OverlapSite& site) {
  PairHistory next;
  next.component = s.history.component, next.fields = s.history.fields;
  next.exchange_sign = s.history.exchange_sign, next.width = s.history.width;
  std::size_t n = 0;
  for (const Outcome& o : out) n += o.touching;
  next.resize(n);
  std::size_t e = 0;
  for (std::size_t k = 0; k < out.size(); ++k) {
    const Outcome& o = out[k];
    if (!o.touching) continue;
    next.pair[e] = static_cast<std::int32_t>(k);
    for (std::size_t q = 0; q < next.width; ++q) next.value[q][e] = o.history[q];
    ++e;
    add_to_body(bodies, members.body.row[s.list.a[k]], o.force, o.torque_a);
    add_to_body(bodies, members.body.row[s.list.b[k]], -o.force, o.torque_b);
    if (o.delta > report.max_overlap) note_worst(report, site, bodies, members, o.delta, s.list.a[k], s.list.b[k]);
    report.fixed_contacts += !bodies.moving(members.body.row[s.list.b[k]]);
  }
  next.map_slots(out.size());
  s.history = std::move(next);
  report.pair_contacts = n;
}

void sum_walls(Bodies& bodies, const Members& members, const std::vector<Outcome>& out, const BodyContactState& s,
               BodyContactReport& report, OverlapSite& site) {
  for (std::size_t m = 0; m < out.size(); ++m) {
    if (!out[m].touching) continue;
    add_to_body(bodies, members.body.row[m], out[m].force, out[m].torque_a);
    if (out[m].delta > report.max_overlap) note_worst(report, site, bodies, members, out[m].delta, static_cast<std::int64_t>(m), -1);
  }
  for (std::uint8_t t : s.walls.touching) report.wall_contacts += t;
}

// Each plane's load of this evaluation: its touching members' loads summed in member order (so the
// result does not depend on the thread or process count), the power at the plane's velocity and spin.
void record_plane_loads(const BodyPlanes& planes, BodyContactState& s, bool turning) {
  MemberWallHistory& w = s.walls;
  const std::size_t np = planes.list.size();
  std::vector<double> sums(6 * np, 0.0);
  for (std::size_t m = 0; m < w.members; ++m)
    for (std::size_t p = 0; p < np; ++p) {
      if (!w.touching[m * np + p]) continue;
      const double* l = w.load_at(m, p);
      for (std::size_t q = 0; q < MemberWallHistory::kLoad; ++q) sums[6 * p + q] += l[q];
    }
  std::vector<Vec3d> velocity(np), spin(np);
  for (std::size_t p = 0; p < np; ++p) {
    const BodyPlane& b = planes.list[p];
    const double omega = turning ? b.omega : 0.0;
    velocity[p] = {b.velocity.x(), b.velocity.y(), b.velocity.z()};
    spin[p] = {omega * b.rot_axis.x(), omega * b.rot_axis.y(), omega * b.rot_axis.z()};
  }
  set_wall_loads(sums, s.loads.now, velocity, spin);
}

// The law's history layout on the pair history; a history of another layout is dropped.
template <class L>
void adopt_layout(PairHistory& h) {
  const HistoryLayout layout = L::history();
  if (h.component == layout.component && h.width == layout.fields.size()) return;
  set_layout(h, layout);
  h.slot.clear();
}

}  // namespace

// ---- Public -------------------------------------------------------------------------------------

void place_body_planes(BodyPlanes& planes, double t, double lag, bool moving) {
  for (BodyPlane& b : planes.list) {
    const Vec3d d = moving ? b.motion.offset(t) : Vec3d{0, 0, 0};
    const Vec3d v = moving ? b.motion.rate(t - lag) : Vec3d{0, 0, 0};
    b.offset = {d.x, d.y, d.z};
    b.velocity = {v.x, v.y, v.z};
  }
}

bool member_pairs_stale(const Members& members, const BodyContactState& state) {
  if (!state.valid || state.ref_x.size() != members.n) return true;
  if (!state.motion.empty() && state.motion.size() != members.n) return true;
  const double limit2 = 0.25 * state.skin * state.skin;
  for (std::size_t i = 0; i < members.n; ++i) {
    const double dx = members.centre.x[i] - state.ref_x[i], dy = members.centre.y[i] - state.ref_y[i],
                 dz = members.centre.z[i] - state.ref_z[i];
    if (!(dx * dx + dy * dy + dz * dz <= limit2)) return true;  // a non-finite centre rebuilds too
  }
  return false;
}

void rebuild_member_pairs(const Members& members, BodyContactState& state) {
  if (!(state.skin > 0.0) || !std::isfinite(state.skin))
    throw std::invalid_argument("the member-pair list's skin must be positive and finite");
  const std::vector<std::uint64_t> old_keys = std::move(state.list.key);
  MemberPairList& list = state.list;
  find_pairs(members, state, list.a, list.b);
  list.key.resize(list.a.size());
  for (std::size_t k = 0; k < list.a.size(); ++k) list.key[k] = pair_key(list.a[k], list.b[k]);
  list.constants.clear(), list.wall_constants.clear();
  carry_history(old_keys, list.key, state.history);
  state.ref_x.assign(members.centre.x.begin(), members.centre.x.begin() + static_cast<std::ptrdiff_t>(members.n));
  state.ref_y.assign(members.centre.y.begin(), members.centre.y.begin() + static_cast<std::ptrdiff_t>(members.n));
  state.ref_z.assign(members.centre.z.begin(), members.centre.z.begin() + static_cast<std::ptrdiff_t>(members.n));
  state.valid = true;
  ++state.rebuilds;
}

template <class L>
BodyContactReport compute_body_contacts(Bodies& bodies, const Members& members, const BodyPlanes& planes,
                                        const BodyContactModel<L>& model, BodyContactState& state, double dt,
                                        bool turning, const BodyContactSplit* split) {
  check_members(bodies, members);
  adopt_layout<L>(state.history);
  BodyContactReport report;
  // A body fixed or removed since the last evaluation: the list (and the law's constants) change.
  bool motion_changed = state.motion.size() != members.n;
  state.motion.resize(members.n);
  for (std::size_t m = 0; m < members.n; ++m) {
    const std::uint8_t now = bodies.motion.state[members.body.row[m]];
    motion_changed = motion_changed || state.motion[m] != now;
    state.motion[m] = now;
  }
  if (motion_changed) state.valid = false;
  if (member_pairs_stale(members, state)) {
    rebuild_member_pairs(members, state);
    report.rebuilt = true;
  }
  MemberPairList& list = state.list;
  if (list.width != L::kConstants || list.constants.size() != list.pairs() * L::kConstants ||
      list.wall_constants.size() != members.n * L::kConstants)
    refresh_constants(bodies, members, model, list);
  if (state.history.slot.size() != list.pairs()) state.history.map_slots(list.pairs());
  shape_wall_history(state.walls, members.n, planes.list.size(), L::kHistory);

  std::vector<MemberShape> shapes(members.n);
  tbb::parallel_for(std::size_t(0), members.n, [&](std::size_t m) { shapes[m] = member_shape(bodies, members, m); });
  // Shared among processes: each evaluates its items, then every process holds every outcome.
  const bool shared = split && split->ranks > 1;
  const SplitBlocks b = shared ? split_blocks(*split) : SplitBlocks{};
  std::vector<Outcome> pairs = evaluate_pairs<L>(bodies, members, shapes, state, dt, b);
  std::vector<Outcome> walls = evaluate_walls<L>(bodies, members, planes, shapes, state, dt, turning, b);
  if (shared && !share_outcomes(*split, body_state_hash(bodies), pairs, state.history.width, walls, state.walls, b))
    throw StabilityError("the processes sharing the bodies' contacts hold different states (their hashes differ): "
                         "they must run one build of grainflow_mpi on machines that round alike; run on one kind of "
                         "node, or on one process");
  zero_loads(bodies);
  OverlapSite site;
  sum_pairs(bodies, members, pairs, state, report, site);
  sum_walls(bodies, members, walls, state, report, site);
  record_plane_loads(planes, state, turning);
  state.worst = site;
  state.last = report;
  return report;
}

void check_body_overlap(const BodyContactState& state, const StepContext& step) {
  if (!(state.last.max_overlap > state.overlap_limit)) return;
  const BodyContactReport& r = state.last;
  const OverlapSite& w = state.worst;
  char where[160];
  if (w.member[1] >= 0)
    std::snprintf(where, sizeof where, "member %lld of body %lld against member %lld of body %lld",
                  static_cast<long long>(w.member[0]), static_cast<long long>(w.body[0]),
                  static_cast<long long>(w.member[1]), static_cast<long long>(w.body[1]));
  else
    std::snprintf(where, sizeof where, "member %lld of body %lld against a wall", static_cast<long long>(w.member[0]),
                  static_cast<long long>(w.body[0]));
  char what[512];
  std::snprintf(what, sizeof what,
                "step %lld (%s): a member contact overlaps by %.4g m, past the limit of %.4g m (%s; the first body's "
                "centre at %.4g %.4g %.4g m)",
                static_cast<long long>(step.step), std::string(step.stage).c_str(), r.max_overlap, state.overlap_limit,
                where, w.centre[0], w.centre[1], w.centre[2]);
  throw StabilityError(std::string(what) +
                       " (run.max_overlap of the thinnest shape's smallest dimension): the contacts are too soft for "
                       "the loads or the step too long; raise kn, lower run.dt, or raise run.max_overlap");
}

// The driver for every registered law: the table's external linkage makes the compiler emit them.
template <class... Laws>
constexpr auto body_contact_drivers(LawList<Laws...>) {
  return std::tuple{&compute_body_contacts<Laws>...};
}
extern const auto kBodyContactDrivers = body_contact_drivers(ContactLaws{});

}  // namespace gf

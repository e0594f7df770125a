// The wall drivers' definitions (declared in wall_contact.hpp), included by the two translation units
// that instantiate them: wall_contact.cpp for the laws acting in contact only and
// wall_contact_reaching.cpp for those acting before touching (laws.hpp says why apart).
#pragma once

#include "systems/walls/wall_contact.hpp"

#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <limits>
#include <type_traits>
#include <vector>

#include "systems/broadphase/neighbor_list.hpp"
#include "engine/simd.hpp"
#include "systems/contact/laws.hpp"
#include "systems/contact/sphere_geometry.hpp"
#include "systems/walls/wall_row_blocks.hpp"

namespace gf {

namespace {

// Each wall's load of this evaluation (walls.hpp) from its sums of force and moment.
void record_loads(Walls& walls, const std::vector<double>& sums) {
  const std::size_t nw = walls.list.size();
  std::vector<Vec3d> velocity(nw), spin(nw);
  for (std::size_t w = 0; w < nw; ++w) velocity[w] = walls.list[w].cur_velocity, spin[w] = walls.list[w].cur_spin;
  set_wall_loads(sums, walls.loads.now, velocity, spin);
}

void prepare(Grains& g, Walls& walls, WallHistory& h, double t_contact, double dt) {
  walls.place(t_contact, 0.5 * dt);  // the grains' velocities are the half-step's (walls.hpp)
  if (h.springs.size() != walls.list.size() || h.active.size() != walls.list.size())
    h.shape(walls.list.size(), g.n);
}

// Per-type law constants as columns, so a batch gathers its lanes' values by type. Fixed size
// (scenes have at most kMaxSpecies species): built on the stack each call, no allocation.
struct CoeffColumns {
  alignas(64) double col[kMaxConstants][kMaxSpecies];
  explicit CoeffColumns(const ContactTable& table) {
    for (std::size_t a = 0; a < table.types(); ++a)
      for (std::size_t q = 0; q < table.width(); ++q) col[q][a] = table.wall(a)[q];
  }
};

// The constant holding a law's reach beyond touching (any, unread, for a law in contact only).
template <class Law>
constexpr std::size_t reach_column() {
  if constexpr (ReachingLaw<Law>) return Law::kReach;
  else return 0;
}

// The contact's geometry: the point between the surfaces for a law in contact only, the wall's
// closest point for one acting before touching (the particle may be apart).
template <class Law, class T>
[[gnu::always_inline]] inline SphereContact<T> wall_contact_geometry(const V3<T>& p, const V3<T>& n, const T& gap,
                                                                      const T& ri, const V3<T>& vi, const V3<T>& wi,
                                                                      const V3<T>& wall_w, const V3<T>& wall_o) {
  if constexpr (ReachingLaw<Law>) return sphere_wall_surface(p, n, gap, ri, vi, wi, wall_w, wall_o);
  else return sphere_wall(p, n, gap, ri, vi, wi, wall_w, wall_o);
}

}  // namespace

template <class Law>
bool compute_wall_forces_scalar(Grains& g, Walls& walls, WallHistory& h, const ContactTable& table, double dt,
                                double t_contact, double overlap_limit) {
  prepare(g, walls, h, t_contact, dt);
  const std::size_t nw = walls.list.size();
  constexpr std::size_t K = Law::kConstants, H = Law::kHistory;
  const double lim2 = 2.0 * overlap_limit;
  std::vector<double> sums;
  const bool over = for_wall_row_blocks(g.n_owned, 1024, nw, sums, [&](std::size_t r0, std::size_t r1, double* load,
                                                                      double& worst) {
    for (std::size_t i = r0; i != r1; ++i) {
      const Vec3d p{g.pos.x[i], g.pos.y[i], g.pos.z[i]};
      const double ri = g.radius.r[i];
      Vec3d f{0, 0, 0}, t{0, 0, 0};
      for (std::size_t w = 0; w < nw; ++w) {
        const Wall& wall = walls.list[w];
        double* hs = h.springs[w][i].s;
        Vec3d n;
        const double gap = wall_gap(wall, p, n);
        // A law acting before touching interacts within r + its reach for the row's species.
        double interacting = ri;
        if constexpr (ReachingLaw<Law>) interacting += table.wall(static_cast<std::size_t>(g.species.type[i]))[Law::kReach];
        if (gap >= interacting) {
          for (std::size_t c = 0; c < H; ++c) hs[c] = 0.0;
          h.active[w][i] = 0;
          continue;
        }
        h.active[w][i] = 1;
        worst = std::max(worst, (ri - gap) - lim2 * ri);
        const Vec3d wi = g.spin ? Vec3d{g.omega.x[i], g.omega.y[i], g.omega.z[i]} : Vec3d{0.0, 0.0, 0.0};
        // The wall's translation enters as the grain's velocity relative to it.
        const Vec3d vi = Vec3d{g.vel.x[i], g.vel.y[i], g.vel.z[i]} - wall.cur_velocity;
        const SphereContact<double> sc = wall_contact_geometry<Law>(p, n, gap, ri, vi, wi, wall.cur_spin, wall.cur_origin);
        const double* k = table.wall(static_cast<std::size_t>(g.species.type[i]));
        std::array<double, K> c;
        std::copy(k, k + K, c.begin());
        if constexpr (SizedLaw<Law>)
          if (table.sized()) {  // grains of a size distribution (size_scaling.hpp)
            const auto a = static_cast<std::size_t>(g.species.type[i]);
            Law::resize(c, wall_size_ratio(g.mass.m[i], ri, table.nominal_mass()[a], table.nominal_radius()[a]));
          }
        std::array<double, H> s;
        std::copy(hs, hs + H, s.begin());
        const ContactForce<double> res = Law::evaluate(true, sc.g, c, dt, s);
        std::copy(s.begin(), s.end(), hs);
        const Vec3d tw = sc.li * cross(n, res.force_t) + res.torque_i;
        f = f + res.force;
        t = t + tw;
        const Vec3d m = cross(p - wall.cur_origin, res.force) + tw;
        const double add[6] = {res.force.x, res.force.y, res.force.z, m.x, m.y, m.z};
        for (std::size_t q = 0; q < 6; ++q) load[w * 6 + q] += add[q];
      }
      g.wall_force.x[i] = f.x;
      g.wall_force.y[i] = f.y;
      g.wall_force.z[i] = f.z;
      if (!g.spin) continue;
      g.wall_torque.x[i] = t.x;
      g.wall_torque.y[i] = t.y;
      g.wall_torque.z[i] = t.z;
    }
  });
  record_loads(walls, sums);
  return over;
}

// The same arithmetic, wall by wall over fixed blocks of rows: a first pass computes the gap of
// every row in batches and packs the rows touching the wall now or at the last evaluation (whose
// springs must be reset); the law then runs over the packed rows only, a whole batch at a time
// (in a thin drum about one row in five touches an end wall, and which rows do depends on the
// row order; packed, the cost follows the contacts and not the order). Per row the walls add in
// wall order, as in the scalar twin.
namespace {

constexpr std::size_t kWallBlock = 2048;  // rows per task, a multiple of the batch width
constexpr std::size_t kAhead = 16;        // rows between a prefetch and its use

// Gap to `wall` and the unit normal from the centre towards it, for a batch of positions.
template <class V, class B>
[[gnu::always_inline]] inline B wall_gap_batch(const Wall& wall, const V& p, V& n) {
  if (wall.kind == Wall::Kind::Plane) {
    const V pn{B(wall.cur_normal.x), B(wall.cur_normal.y), B(wall.cur_normal.z)};
    const V pp{B(wall.cur_point.x), B(wall.cur_point.y), B(wall.cur_point.z)};
    n = -pn;
    return dot(p - pp, pn);
  }
  const V ax{B(wall.cur_axis.x), B(wall.cur_axis.y), B(wall.cur_axis.z)};
  const V q = p - V{B(wall.cur_center.x), B(wall.cur_center.y), B(wall.cur_center.z)};
  const V radial = q - dot(q, ax) * ax;
  const B rho = xsimd::sqrt(dot(radial, radial));
  // A lane on the axis is far from the surface (gap = R > r for any grain that fits).
  const B inv = B(1.0) / xsimd::select(rho > B(0.0), rho, B(1.0));
  n = inv * radial;
  return B(wall.radius) - rho;
}

// Lanes of the batch of rows at i within reach of `wall` (gap < r, and for a law acting before
// touching gap < r + the law's reach for the row's species, from the column `wall_reach` by type),
// without the square root and division of the normal: for the cylinder, gap < r is
// rho^2 > (R - r)^2 where R > r.
template <class Law>
[[gnu::always_inline]] inline std::uint32_t reach_bits(const Wall& wall, const Grains& g, std::size_t i,
                                                       const double* wall_reach) {
  using B = BatchD;
  const B px = B::load_aligned(&g.pos.x[i]), py = B::load_aligned(&g.pos.y[i]), pz = B::load_aligned(&g.pos.z[i]);
  B r = B::load_aligned(&g.radius.r[i]);
  if constexpr (ReachingLaw<Law>) r = r + gather32(wall_reach, &g.species.type[i]);
  if (wall.kind == Wall::Kind::Plane) {
    const B gap = (px - B(wall.cur_point.x)) * B(wall.cur_normal.x) + (py - B(wall.cur_point.y)) * B(wall.cur_normal.y) +
                  (pz - B(wall.cur_point.z)) * B(wall.cur_normal.z);
    return lane_bits(gap < r);
  }
  const B qx = px - B(wall.cur_center.x), qy = py - B(wall.cur_center.y), qz = pz - B(wall.cur_center.z);
  const B along = qx * B(wall.cur_axis.x) + qy * B(wall.cur_axis.y) + qz * B(wall.cur_axis.z);
  const B rx = qx - along * B(wall.cur_axis.x), ry = qy - along * B(wall.cur_axis.y),
          rz = qz - along * B(wall.cur_axis.z);
  const B inner = B(wall.radius) - r;
  return lane_bits(rx * rx + ry * ry + rz * rz > inner * inner || inner <= B(0.0));
}

// Bit l set where flag l of the batch is non-zero.
[[gnu::always_inline]] inline std::uint32_t nonzero_bits(const std::uint8_t* flags) {
#if defined(__AVX512BW__) && defined(__AVX512VL__) && !defined(GRAINFLOW_SIMD_256)
  static_assert(kLanes == 8);
  const __m128i v = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(flags));
  return static_cast<std::uint32_t>(_mm_test_epi8_mask(v, v)) & 0xffu;
#else
  std::uint32_t bits = 0;
  for (std::size_t l = 0; l < kLanes; ++l) bits |= static_cast<std::uint32_t>(flags[l] != 0) << l;
  return bits;
#endif
}

// Appends the rows i + l of the set bits to rows[m...] (writing a whole batch), returns the new m.
[[gnu::always_inline]] inline std::size_t append_rows(std::int32_t* rows, std::size_t m, std::size_t i,
                                                      std::uint32_t bits) {
#if defined(__AVX512F__) && defined(__AVX512VL__) && !defined(GRAINFLOW_SIMD_256)
  static_assert(kLanes == 8);
  const __m256i lanes = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(i)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(rows + m),
                      _mm256_maskz_compress_epi32(static_cast<__mmask8>(bits), lanes));
  return m + static_cast<std::size_t>(__builtin_popcount(bits));
#else
  for (std::size_t l = 0; l < kLanes; ++l) {
    rows[m] = static_cast<std::int32_t>(i + l);
    m += (bits >> l) & 1u;
  }
  return m;
#endif
}

}  // namespace

template <class Law>
bool compute_wall_forces(Grains& g, Walls& walls, WallHistory& h, const ContactTable& table, double dt,
                         double t_contact, double overlap_limit) {
  prepare(g, walls, h, t_contact, dt);
  const double lim2 = 2.0 * overlap_limit;
  using B = BatchD;
  using V = V3<B>;
  constexpr std::size_t L = kLanes;
  static_assert(kWallBlock % L == 0);
  const std::size_t nw = walls.list.size();
  constexpr std::size_t K = Law::kConstants, H = Law::kHistory;
  static_assert(H <= sizeof(WallSprings::s) / sizeof(double), "a wall contact's history fits one record");
  const CoeffColumns cc(table);
  // With few species each constant sits in a register, looked up by type with a permute.
  const bool in_register = table.types() <= RegisterTable::capacity;
  RegisterTable reg[K];
  if (in_register)
    for (std::size_t q = 0; q < K; ++q) reg[q] = RegisterTable(cc.col[q], table.types());
  [[maybe_unused]] const bool sized = table.sized();
  const std::size_t nown = g.n_owned;
  const std::size_t nblocks = (nown + kWallBlock - 1) / kWallBlock;
  // Per block: some contact past the overlap limit (checked in the law pass, on values at hand).
  std::vector<std::uint8_t> block_over(nblocks, 0);
  // Per block and wall: the sums of force and moment (walls.hpp), added in block order after.
  std::vector<double> block_load(nblocks * nw * 6, 0.0);
  // Each lane's index, to leave a wall's padding lanes out of its sums.
  alignas(64) double lane_index[L];
  for (std::size_t l = 0; l < L; ++l) lane_index[l] = static_cast<double>(l);
  const B lanes = B::load_aligned(lane_index);
  // The blocks, compiled for grains with and without spin columns (no branch per batch).
  auto run_blocks = [&](auto spin_tag) {
    constexpr bool spin = decltype(spin_tag)::value;
    tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t blk) {
      const std::size_t r0 = blk * kWallBlock, r1 = std::min(nown, r0 + kWallBlock);
      std::uint32_t over = 0;
      for (ColumnD* c : {&g.wall_force.x, &g.wall_force.y, &g.wall_force.z})
        std::fill(c->begin() + r0, c->begin() + r1, 0.0);
      if (spin)
        for (ColumnD* c : {&g.wall_torque.x, &g.wall_torque.y, &g.wall_torque.z})
          std::fill(c->begin() + r0, c->begin() + r1, 0.0);
      // Packed rows of one wall, padded to a whole batch with the last one.
      alignas(64) std::int32_t rows[kWallBlock + kAhead + L];
      for (std::size_t w = 0; w < nw; ++w) {
        const Wall& wall = walls.list[w];
        Column<std::uint8_t>& act = h.active[w];
        std::size_t m = 0;
        for (std::size_t i = r0; i < r1; i += L) {
          const std::uint32_t take = reach_bits<Law>(wall, g, i, cc.col[reach_column<Law>()]) | nonzero_bits(&act[i]);
          m = append_rows(rows, m, i, take & ((1u << std::min(L, r1 - i)) - 1u));
        }
        if (m == 0) continue;
        for (std::size_t l = m; l < m + kAhead + L; ++l) rows[l] = rows[m - 1];
        WallSprings* hs = h.springs[w].data();
        // A spring k of row i is double 8 i + k from the column's start.
        const double* hbase = hs[0].s;
        const V wall_w{B(wall.cur_spin.x), B(wall.cur_spin.y), B(wall.cur_spin.z)};
        const V wall_o{B(wall.cur_origin.x), B(wall.cur_origin.y), B(wall.cur_origin.z)};
        // The wall's translation enters as the grains' velocity relative to it.
        const V wall_v{B(wall.cur_velocity.x), B(wall.cur_velocity.y), B(wall.cur_velocity.z)};
        // The wall's force and moment on the block's rows (walls.hpp), summed lane-wise over the
        // batches, padding lanes left out, and across the lanes after.
        V fsum{B(0.0), B(0.0), B(0.0)}, msum{B(0.0), B(0.0), B(0.0)};
        for (std::size_t q = 0; q < m; q += L) {
          const std::int32_t* idx = &rows[q];
          // The springs and velocities of the packed rows are read nowhere else this step, so they
          // come from far in the cache hierarchy: ask for those of a later batch now.
          for (std::size_t l = 0; l < L; ++l) {
            const auto a = static_cast<std::size_t>(rows[q + kAhead + l]);
            __builtin_prefetch(&hs[a]);
            __builtin_prefetch(&g.vel.x[a]);
            __builtin_prefetch(&g.vel.y[a]);
            __builtin_prefetch(&g.vel.z[a]);
            if (!spin) continue;
            __builtin_prefetch(&g.omega.x[a]);
            __builtin_prefetch(&g.omega.y[a]);
            __builtin_prefetch(&g.omega.z[a]);
          }
          const V p{gather32(g.pos.x.data(), idx), gather32(g.pos.y.data(), idx), gather32(g.pos.z.data(), idx)};
          const B ri = gather32(g.radius.r.data(), idx);
          V n;
          const B gap = wall_gap_batch<V, B>(wall, p, n);
          // Interacting lanes: gap < r, or r + the law's reach for the lane's species.
          const auto touching = [&] {
            if constexpr (ReachingLaw<Law>) {
              alignas(64) double reach[L];
              for (std::size_t l = 0; l < L; ++l)
                reach[l] = cc.col[reach_column<Law>()][g.species.type[static_cast<std::size_t>(idx[l])]];
              return gap < ri + B::load_aligned(reach);
            } else {
              return gap < ri;
            }
          }();
          // The stability check: an overlap ri - gap past lim2 ri (the limit is of the diameter).
          over |= lane_bits(gap < ri - B(lim2) * ri);
          alignas(64) std::int32_t ty[L];
          for (std::size_t l = 0; l < L; ++l) ty[l] = g.species.type[static_cast<std::size_t>(idx[l])];
          std::array<B, K> c;
          for (std::size_t k = 0; k < K; ++k) c[k] = in_register ? reg[k].lookup(ty) : gather32(cc.col[k], ty);
          if constexpr (SizedLaw<Law>)
            if (sized)  // grains of a size distribution (size_scaling.hpp)
              Law::resize(c, wall_size_ratio(gather32(g.mass.m.data(), idx), ri, gather32(table.nominal_mass(), ty),
                                             gather32(table.nominal_radius(), ty)));
          const V wi = spin ? V{gather32(g.omega.x.data(), idx), gather32(g.omega.y.data(), idx),
                                gather32(g.omega.z.data(), idx)}
                            : V{B(0.0), B(0.0), B(0.0)};
          const V vi = V{gather32(g.vel.x.data(), idx), gather32(g.vel.y.data(), idx), gather32(g.vel.z.data(), idx)} -
                       wall_v;
          const SphereContact<B> sc = wall_contact_geometry<Law>(p, n, gap, ri, vi, wi, wall_w, wall_o);
          alignas(64) std::int32_t at[L];
          for (std::size_t l = 0; l < L; ++l) at[l] = idx[l] * 8;
          std::array<B, H> s;
          for (std::size_t k = 0; k < H; ++k) s[k] = gather32(hbase + k, at);
          const ContactForce<B> res = Law::evaluate(touching, sc.g, c, B(dt), s);
          const V t = sc.li * cross(n, res.force_t) + res.torque_i;
          {
            const auto live = lanes < B(static_cast<double>(std::min(L, m - q)));
            const V mo = cross(p - wall_o, res.force) + t;
            fsum = fsum + V{xsimd::select(live, res.force.x, B(0.0)), xsimd::select(live, res.force.y, B(0.0)),
                            xsimd::select(live, res.force.z, B(0.0))};
            msum = msum + V{xsimd::select(live, mo.x, B(0.0)), xsimd::select(live, mo.y, B(0.0)),
                            xsimd::select(live, mo.z, B(0.0))};
          }
          // Lanes back to their rows (rows are distinct within one wall's list).
          constexpr std::size_t F = H + 6;
          alignas(64) double out[F][L];
          B vals[F];
          for (std::size_t k = 0; k < H; ++k) vals[k] = s[k];
          const B sums[6] = {res.force.x, res.force.y, res.force.z, t.x, t.y, t.z};
          for (std::size_t k = 0; k < 6; ++k) vals[H + k] = sums[k];
          const std::uint32_t now = lane_bits(touching);
          for (std::size_t f = 0; f < F; ++f) vals[f].store_aligned(out[f]);
          const std::size_t valid = std::min(L, m - q);
          for (std::size_t l = 0; l < valid; ++l) {
            const auto i = static_cast<std::size_t>(idx[l]);
            for (std::size_t k = 0; k < H; ++k) hs[i].s[k] = out[k][l];
            g.wall_force.x[i] += out[H][l];
            g.wall_force.y[i] += out[H + 1][l];
            g.wall_force.z[i] += out[H + 2][l];
            act[i] = static_cast<std::uint8_t>((now >> l) & 1u);
            if (!spin) continue;
            g.wall_torque.x[i] += out[H + 3][l];
            g.wall_torque.y[i] += out[H + 4][l];
            g.wall_torque.z[i] += out[H + 5][l];
          }
        }
        double* load = &block_load[(blk * nw + w) * 6];
        const B sums[6] = {fsum.x, fsum.y, fsum.z, msum.x, msum.y, msum.z};
        for (std::size_t k = 0; k < 6; ++k) load[k] += xsimd::hadd(sums[k]);
      }
      block_over[blk] = over != 0;
    });
  };
  if (g.spin)
    run_blocks(std::true_type{});
  else
    run_blocks(std::false_type{});
  record_loads(walls, add_wall_blocks(block_load, nw));
  return std::any_of(block_over.begin(), block_over.end(), [](std::uint8_t b) { return b != 0; });
}

// Both drivers for each law of a LawList: a table with external linkage makes the compiler emit them.
template <class... Laws>
constexpr auto wall_drivers(LawList<Laws...>) {
  return std::array{std::pair{&compute_wall_forces<Laws>, &compute_wall_forces_scalar<Laws>}...};
}

}  // namespace gf

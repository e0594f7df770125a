// The pair drivers' definitions (declared in pair_contact.hpp), included by the two translation units
// that instantiate them: pair_contact.cpp for the laws acting in contact only and
// pair_contact_reaching.cpp for those acting before touching (laws.hpp says why apart).
#pragma once

#include "systems/contact/pair_contact.hpp"

#include <algorithm>
#include <cstring>

#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "engine/simd.hpp"
#include "systems/contact/laws.hpp"
#include "systems/contact/sphere_geometry.hpp"

namespace gf {

namespace {

// Pairs per prefilter block: a multiple of the batch width, small enough for load balance.
constexpr std::size_t kBlock = 2048;
static_assert(kBlock % kLanes == 0, "blocks start on whole batches");
// Contacts between a spring prefetch and its use in the law.
constexpr std::size_t kAheadSprings = 64;

// The per-contact columns hold one extra row, kept zero. The history being written takes the live
// one's layout (they are swapped after each evaluation).
void size_outputs(PairForces& out, const PairHistory& h, std::size_t np, std::size_t nc) {
  if (out.next.width != h.width || out.next.component != h.component) {
    out.next.component = h.component;
    out.next.fields = h.fields;
    out.next.exchange_sign = h.exchange_sign;
    out.next.width = h.width;
  }
  for (Column<std::int32_t>* c : {&out.ci, &out.cj, &out.ctype, &out.cslot}) c->resize(nc + 1);
  out.next.resize(nc);
  out.next.slot.resize(np);
  std::fill(out.next.slot.begin() + np, out.next.slot.begin() + out.next.slot.padded(), -1);
  for (ColumnD* c : {&out.fx, &out.fy, &out.fz}) {
    c->resize(nc + 1);
    (*c)[nc] = 0.0;
  }
  for (ColumnD* c : {&out.tix, &out.tiy, &out.tiz, &out.tjx, &out.tjy, &out.tjz}) c->resize(out.record_torques ? nc : 0);
}

// History of the last evaluation for contact c (entry `slot` of the old history, -1 for a new
// contact, which starts from zero).
void carry_history(const PairHistory& old, std::int32_t slot, PairHistory& next, std::size_t c) {
  const bool found = slot >= 0;
  const auto e = static_cast<std::size_t>(found ? slot : 0);
  for (std::size_t q = 0; q < old.width; ++q) next.value[q][c] = found ? old.value[q][e] : 0.0;
}

// Compaction of list pairs [k0, k1) into contacts from index c: the contact's indices and the map
// from list pair to contact (the new history's slot). One pair at a time.
std::int32_t compact_scalar(const NeighborList& list, const PairHistory& h, PairForces& out, std::size_t k0,
                            std::size_t k1, std::int32_t c) {
  for (std::size_t k = k0; k < k1; ++k) {
    const std::int32_t t = out.touching[k];
    out.next.slot[k] = t ? c : -1;
    // Only touching pairs write their slot: a block's slot past its last contact is the next
    // block's first, written concurrently by another thread.
    if (t) {
      out.next.pair[c] = static_cast<std::int32_t>(k);
      out.ci[c] = list.i_lane[k];
      out.cj[c] = list.j_lane[k];
      out.ctype[c] = list.type_pair[k];
      out.cslot[c] = h.slot[k];
    }
    c += t;
  }
  return c;
}

#if defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__) && defined(__AVX512VPOPCNTDQ__)
#define GF_COMPACT_AVX512 1
// The same, sixteen pairs at a time: the touching lanes' indices are compressed in registers and
// stored whole (the lanes past this group's contacts are overwritten by the next group), except
// within sixteen of `c_end`, the block's last contact, past which the next block writes: there
// under a mask. A touching pair's contact index is the group's base plus the count of touching
// lanes below it.
std::int32_t compact_avx512(const NeighborList& list, const PairHistory& h, PairForces& out, std::size_t k0,
                            std::size_t k1, std::int32_t c, std::int32_t c_end) {
  const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i below = _mm512_setr_epi32(0x0, 0x1, 0x3, 0x7, 0xf, 0x1f, 0x3f, 0x7f, 0xff, 0x1ff, 0x3ff, 0x7ff,
                                          0xfff, 0x1fff, 0x3fff, 0x7fff);
  const __m512i vminus = _mm512_set1_epi32(-1);
  std::size_t k = k0;
  for (; k + 16 <= k1; k += 16) {
    const __m128i tb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&out.touching[k]));
    const __mmask16 m = _mm_test_epi8_mask(tb, tb);
    const __m512i rank = _mm512_add_epi32(
        _mm512_set1_epi32(c), _mm512_popcnt_epi32(_mm512_and_si512(_mm512_set1_epi32(m), below)));
    _mm512_storeu_si512(&out.next.slot[k], _mm512_mask_blend_epi32(m, vminus, rank));
    const int cnt = __builtin_popcount(m);
    if (cnt == 0) continue;
    const auto w = static_cast<__mmask16>(c + 16 <= c_end ? 0xffffu : (1u << cnt) - 1u);
    const __m512i kk = _mm512_maskz_compress_epi32(m, _mm512_add_epi32(_mm512_set1_epi32(static_cast<int>(k)), iota));
    _mm512_mask_storeu_epi32(&out.next.pair[c], w, kk);
    auto pack = [&](std::int32_t* dst, const std::int32_t* src) {
      _mm512_mask_storeu_epi32(dst, w, _mm512_maskz_compress_epi32(m, _mm512_loadu_si512(src + k)));
    };
    pack(&out.ci[c], list.i_lane.data());
    pack(&out.cj[c], list.j_lane.data());
    pack(&out.ctype[c], list.type_pair.data());
    pack(&out.cslot[c], h.slot.data());
    c += cnt;
  }
  return compact_scalar(list, h, out, k, k1, c);
}
#endif

// True when the batch of slots is one increasing run (s, s+1, ...).
inline bool is_run(const std::int32_t* sl) {
  for (std::size_t l = 1; l < kLanes; ++l)
    if (sl[l] != sl[0] + static_cast<std::int32_t>(l)) return false;
  return true;
}

// Torques on i (0-2) and on j (3-5) of a slab's contacts [c0, c1), indexed c - c0: a per-task
// buffer, read by the slab's sums right after the law writes it.
struct SlabTorques {
  std::size_t c0 = 0;
  double* t[6] = {};
};

// Geometry, law and torques for one contact; shared by the scalar tail and the scalar driver.
template <class Law>
void evaluate_one(const Grains& g, std::size_t i, std::size_t j, PairHistory& h, const ContactTable& table, double dt,
                  PairForces& out, std::size_t c, const SlabTorques& st) {
  const V3<double> d{g.pos.x[j] - g.pos.x[i], g.pos.y[j] - g.pos.y[i], g.pos.z[j] - g.pos.z[i]};
  const double dist = std::sqrt(dot(d, d));
  const V3<double> wi = g.spin ? V3<double>{g.omega.x[i], g.omega.y[i], g.omega.z[i]} : V3<double>{0.0, 0.0, 0.0};
  const V3<double> wj = g.spin ? V3<double>{g.omega.x[j], g.omega.y[j], g.omega.z[j]} : V3<double>{0.0, 0.0, 0.0};
  const V3<double> vij{g.vel.x[i] - g.vel.x[j], g.vel.y[i] - g.vel.y[j], g.vel.z[i] - g.vel.z[j]};
  const SphereContact<double> sc = sphere_sphere(d, dist, 1.0 / dist, g.radius.r[i], g.radius.r[j], vij, wi, wj);
  const double* k = table.pair(static_cast<std::size_t>(g.species.type[i]), static_cast<std::size_t>(g.species.type[j]));
  std::array<double, Law::kConstants> cf;
  std::copy(k, k + Law::kConstants, cf.begin());
  if constexpr (SizedLaw<Law>)
    if (table.sized()) {
      const auto a = static_cast<std::size_t>(g.species.type[i]), b = static_cast<std::size_t>(g.species.type[j]);
      const double* m0 = table.nominal_mass();
      const double* r0 = table.nominal_radius();
      Law::resize(cf, pair_size_ratio(g.mass.m[i], g.mass.m[j], g.radius.r[i], g.radius.r[j], m0[a], m0[b], r0[a], r0[b]));
    }
  std::array<double, Law::kHistory> s;
  for (std::size_t q = 0; q < Law::kHistory; ++q) s[q] = h.value[q][c];
  const ContactForce<double> res = Law::evaluate(true, sc.g, cf, dt, s);
  for (std::size_t q = 0; q < Law::kHistory; ++q) h.value[q][c] = s[q];
  const V3<double> nxf = cross(sc.g.n, res.force_t);
  out.fx[c] = res.force.x;
  out.fy[c] = res.force.y;
  out.fz[c] = res.force.z;
  st.t[0][c - st.c0] = sc.li * nxf.x + res.torque_i.x;
  st.t[1][c - st.c0] = sc.li * nxf.y + res.torque_i.y;
  st.t[2][c - st.c0] = sc.li * nxf.z + res.torque_i.z;
  // On j the force is -F and the lever -L_j n: the tangential torque has the same sign as i's.
  st.t[3][c - st.c0] = sc.lj * nxf.x + res.torque_j.x;
  st.t[4][c - st.c0] = sc.lj * nxf.y + res.torque_j.y;
  st.t[5][c - st.c0] = sc.lj * nxf.z + res.torque_j.z;
}

// The slab that sums row j's partner sides: the owned rows' slabs of `rows` rows, then the ghost
// rows' (from the first row past the n owned ones).
inline std::size_t target_slab(std::size_t j, std::size_t n, std::size_t rows) {
  return j < n ? j / rows : (n + rows - 1) / rows + (j - n) / rows;
}

// Sums into Force and Torque by slabs of owner rows. A slab's contacts are one run of the packed
// list (contacts keep list order, rows own list runs); each adds to its owner and, when the partner
// is in the same slab (partners are later rows), to the partner too, in contact order. A partner in
// a later slab gets its share through the list of that (slab, target) pair, added after every slab
// is done, in slab order. The columns read stream in order; the slab's rows are summed in per-task
// records that stay in cache, then written to the Force and Torque columns once. Plain restrict
// pointers held in locals, so that the stores into the records are not taken to change the
// columns read.
struct SlabSums {
  double* __restrict F[3];
  double* __restrict T[3];
  const std::int32_t* __restrict ci;
  const std::int32_t* __restrict cj;
  const double* __restrict f[3];

  // acc: the slab's rows as records of kAcc doubles (force, torque), a per-task buffer: a
  // contact's share to a row then touches one cache line, not six columns.
  static constexpr std::size_t kAcc = 8;
  void run(std::size_t a, std::size_t b, std::size_t n, std::size_t rows, std::size_t c0, std::size_t c1,
           const SlabTorques& st, double* __restrict acc, std::vector<PairForces::Spill>* spill) const {
    const std::int32_t* __restrict ri = ci;
    const std::int32_t* __restrict rj = cj;
    const double* __restrict fx = f[0];
    const double* __restrict fy = f[1];
    const double* __restrict fz = f[2];
    // The slab's torques, indexed c - c0.
    const double* __restrict tix = st.t[0];
    const double* __restrict tiy = st.t[1];
    const double* __restrict tiz = st.t[2];
    const double* __restrict tjx = st.t[3];
    const double* __restrict tjy = st.t[4];
    const double* __restrict tjz = st.t[5];
    std::fill(acc, acc + (b - a) * kAcc, 0.0);
    for (std::size_t c = c0; c < c1; ++c) {
      const std::size_t q = c - c0;
      const auto i = static_cast<std::size_t>(ri[c]), j = static_cast<std::size_t>(rj[c]);
      double* __restrict ai = acc + (i - a) * kAcc;
      ai[0] += fx[c];
      ai[1] += fy[c];
      ai[2] += fz[c];
      ai[3] += tix[q];
      ai[4] += tiy[q];
      ai[5] += tiz[q];
      if (j < b) {
        double* __restrict aj = acc + (j - a) * kAcc;
        aj[0] -= fx[c];
        aj[1] -= fy[c];
        aj[2] -= fz[c];
        aj[3] += tjx[q];
        aj[4] += tjy[q];
        aj[5] += tjz[q];
      } else {  // a later slab's row, or a ghost row (slabs past the owned ones, from n on)
        spill[target_slab(j, n, rows)].push_back({static_cast<std::uint32_t>(j), fx[c], fy[c], fz[c], tjx[q], tjy[q], tjz[q]});
      }
    }
    double* cols[6] = {F[0], F[1], F[2], T[0], T[1], T[2]};
    const std::size_t ncols = T[0] ? 6 : 3;  // no torque columns when grains do not rotate
    for (std::size_t k = 0; k < ncols; ++k) {
      double* __restrict col = cols[k];
      for (std::size_t r = a; r < b; ++r) col[r] = acc[(r - a) * kAcc + k];
    }
  }
};

// Contacts before list pair k (contacts keep list order): the count up to k's block, then the
// block's touching pairs before k.
std::size_t contacts_before(const PairForces& out, std::size_t k) {
  const std::size_t b = k / kBlock;
  std::size_t c = out.block_start[b];
  for (std::size_t q = b * kBlock; q < k; ++q) c += out.touching[q];
  return c;
}

// Counts of touching pairs per block of kBlock list pairs, summed: block_start[b] contacts come
// before block b.
void count_blocks(PairForces& out, std::size_t np) {
  const std::size_t nblocks = (np + kBlock - 1) / kBlock;
  out.block_start.assign(nblocks + 1, 0);
  for (std::size_t b = 0; b < nblocks; ++b) {
    std::uint32_t n = 0;
    for (std::size_t k = b * kBlock; k < std::min(np, (b + 1) * kBlock); ++k) n += out.touching[k];
    out.block_start[b + 1] = out.block_start[b] + n;
  }
}

// Runs law(c0, c1) over each slab's contacts, then that slab's sums, one task per slab; then the
// shares set aside for later slabs.
template <class Law>
void evaluate_and_sum(Grains& g, const NeighborList& list, PairForces& out, Law&& law) {
  const std::size_t n = g.n_owned;
  const std::size_t rows = slab_rows(n);
  const std::size_t ns = (n + rows - 1) / rows;
  // Target slabs of the partner sides: the owned rows' and, past them, the image rows' (periodic
  // boundaries), which start from zero and are folded into their owners by PeriodicFold.
  const std::size_t nt = target_slab(g.n + rows - 1, n, rows);
  if (out.spill.size() < ns * nt) out.spill.resize(ns * nt);
  for (ColumnD* c : {&g.force.x, &g.force.y, &g.force.z}) std::fill(c->begin() + n, c->end(), 0.0);
  if (g.spin)
    for (ColumnD* c : {&g.torque.x, &g.torque.y, &g.torque.z}) std::fill(c->begin() + n, c->end(), 0.0);
  const SlabSums sums{{g.force.x.data(), g.force.y.data(), g.force.z.data()},
                      {g.spin ? g.torque.x.data() : nullptr, g.spin ? g.torque.y.data() : nullptr,
                       g.spin ? g.torque.z.data() : nullptr},
                      out.ci.data(),
                      out.cj.data(),
                      {out.fx.data(), out.fy.data(), out.fz.data()}};
  tbb::parallel_for(std::size_t(0), ns, [&](std::size_t s) {
    const std::size_t a = s * rows, b = std::min(n, a + rows);
    const std::size_t c0 = contacts_before(out, list.offsets[a]), c1 = contacts_before(out, list.offsets[b]);
    // This thread's torque buffer, kept from call to call (no allocation once it has grown).
    thread_local std::vector<double> scratch;
    const std::size_t stride = (c1 - c0 + 2 * kLanes - 1) / kLanes * kLanes;
    if (scratch.size() < 6 * stride) scratch.resize(6 * stride);
    SlabTorques st{c0, {}};
    for (std::size_t k = 0; k < 6; ++k) st.t[k] = scratch.data() + k * stride;
    law(c0, c1, st);
    if (out.record_torques) {
      ColumnD* cols[6] = {&out.tix, &out.tiy, &out.tiz, &out.tjx, &out.tjy, &out.tjz};
      for (std::size_t k = 0; k < 6; ++k) std::copy(st.t[k], st.t[k] + (c1 - c0), cols[k]->begin() + c0);
    }
    thread_local std::vector<double, xsimd::aligned_allocator<double, 64>> acc;  // rows on cache lines
    if (acc.size() < rows * SlabSums::kAcc) acc.resize(rows * SlabSums::kAcc);
    std::vector<PairForces::Spill>* spill = &out.spill[s * nt];
    for (std::size_t t = s + 1; t < nt; ++t) spill[t].clear();
    sums.run(a, b, n, rows, c0, c1, st, acc.data(), spill);
  });
  tbb::parallel_for(std::size_t(1), nt, [&](std::size_t t) {
    double* __restrict Fx = sums.F[0];
    double* __restrict Fy = sums.F[1];
    double* __restrict Fz = sums.F[2];
    double* __restrict Tx = sums.T[0];
    double* __restrict Ty = sums.T[1];
    double* __restrict Tz = sums.T[2];
    for (std::size_t s = 0; s < std::min(t, ns); ++s)
      for (const PairForces::Spill& e : out.spill[s * nt + t]) {
        Fx[e.j] -= e.fx;
        Fy[e.j] -= e.fy;
        Fz[e.j] -= e.fz;
        if (!Tx) continue;
        Tx[e.j] += e.tx;
        Ty[e.j] += e.ty;
        Tz[e.j] += e.tz;
      }
  });
}

}  // namespace

template <class Law>
bool compute_pair_forces_scalar(Grains& g, const NeighborList& list, PairHistory& h, const ContactTable& table,
                                double dt, PairForces& out, double overlap_limit) {
  const double lim2 = 2.0 * overlap_limit;
  bool over = false;
  const std::size_t np = list.pairs();
  out.touching.resize(padded_size(np));
  for (std::size_t k = 0; k < np; ++k) {
    const std::size_t i = list.i[k], j = list.j[k];
    const double dx = g.pos.x[j] - g.pos.x[i], dy = g.pos.y[j] - g.pos.y[i], dz = g.pos.z[j] - g.pos.z[i];
    const double rs = g.radius.r[i] + g.radius.r[j];
    const double d2 = dx * dx + dy * dy + dz * dz;
    if constexpr (ReachingLaw<Law>) {
      // Interacting within the reach beyond touching (the overlap test below stays on r_i + r_j).
      const double rt = rs + table.pair(static_cast<std::size_t>(g.species.type[i]),
                                        static_cast<std::size_t>(g.species.type[j]))[Law::kReach];
      out.touching[k] = d2 < rt * rt;
    } else {
      out.touching[k] = d2 < rs * rs;
    }
    const double deep = rs - lim2 * std::min(g.radius.r[i], g.radius.r[j]);  // closer: past the limit
    over = over || d2 < deep * deep;
  }
  count_blocks(out, np);
  const std::size_t nc = out.block_start.back();
  if (h.slot.size() != np) h.map_slots(np);
  size_outputs(out, h, np, nc);
  compact_scalar(list, h, out, 0, np, 0);
  evaluate_and_sum(g, list, out, [&](std::size_t c0, std::size_t c1, const SlabTorques& st) {
    for (std::size_t c = c0; c < c1; ++c) {
      const auto k = static_cast<std::size_t>(out.next.pair[c]);
      carry_history(h, out.cslot[c], out.next, c);
      evaluate_one<Law>(g, list.i[k], list.j[k], out.next, table, dt, out, c, st);
    }
  });
  std::swap(h, out.next);
  return over;
}

template <class Law>
bool compute_pair_forces(Grains& g, const NeighborList& list, PairHistory& h, const ContactTable& table, double dt,
                         PairForces& out, double overlap_limit) {
  const double lim2 = 2.0 * overlap_limit;
  using B = BatchD;
  using V = V3<B>;
  constexpr std::size_t L = kLanes;
  const std::size_t np = list.pairs();
  out.touching.resize(padded_size(np));

  // Every column of the table is allocated to this many rows (whole batches).
  const std::size_t rows = g.pos.x.padded();

  // 1. Overlap test per pair; counts per block of pairs. The stability check rides along: a pair
  // closer than r_i + r_j - lim2 min(r_i, r_j) overlaps past the limit (a compare on numbers at hand).
  // A law that acts before touching takes the pairs within r_i + r_j + its reach (per type pair).
  if constexpr (ReachingLaw<Law>) {
    out.reach.assign(static_cast<std::size_t>(kMaxSpecies * kMaxSpecies), 0.0);
    for (std::size_t a = 0; a < table.types(); ++a)
      for (std::size_t b = 0; b < table.types(); ++b)
        out.reach[a * static_cast<std::size_t>(kMaxSpecies) + b] = table.pair(a, b)[Law::kReach];
  }
  const std::size_t nblocks = (np + kBlock - 1) / kBlock;
  out.block_start.assign(nblocks + 1, 0);
  out.block_over.assign(nblocks, 0);
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t b) {
    const std::size_t k0 = b * kBlock, k1 = std::min(np, k0 + kBlock);
    std::uint32_t count = 0, over = 0;
    const B blim2(lim2);
    for (std::size_t k = k0; k < k1; k += L) {
      // Pairs are in owner order: the owners of a batch are a few adjacent rows.
      const RowWindow wi = row_window(&list.i_lane[k], rows);
      const std::int32_t* bj = &list.j_lane[k];
      const B dx = gather32(g.pos.x.data(), bj) - load_rows(g.pos.x.data(), wi);
      const B dy = gather32(g.pos.y.data(), bj) - load_rows(g.pos.y.data(), wi);
      const B dz = gather32(g.pos.z.data(), bj) - load_rows(g.pos.z.data(), wi);
      const B rj = gather32(g.radius.r.data(), bj), ri = load_rows(g.radius.r.data(), wi);
      const B rs = rj + ri;
      // Blocks start at multiples of the batch width, so a batch's flags never reach into
      // another block's (past the last pair they fall in the column's padding, and are 0).
      const B d2 = dx * dx + dy * dy + dz * dz;
      const std::uint32_t valid = (1u << std::min(L, k1 - k)) - 1u;
      std::uint32_t bits;
      if constexpr (ReachingLaw<Law>) {
        const B rt = rs + gather32(out.reach.data(), &list.type_pair[k]);
        bits = lane_bits(d2 < rt * rt) & valid;
      } else {
        bits = lane_bits(d2 < rs * rs) & valid;
      }
      const B deep = rs - blim2 * xsimd::min(ri, rj);
      over |= lane_bits(d2 < deep * deep) & bits;
#if defined(__BMI2__)
      static_assert(kLanes == 8 || kLanes == 4);
      const std::uint64_t bytes = _pdep_u64(bits, 0x0101010101010101ull);
      std::memcpy(&out.touching[k], &bytes, L);
#else
      for (std::size_t l = 0; l < L; ++l) out.touching[k + l] = static_cast<std::uint8_t>((bits >> l) & 1u);
#endif
      count += static_cast<std::uint32_t>(__builtin_popcount(bits));
    }
    out.block_start[b + 1] = count;
    out.block_over[b] = over != 0;
  });
  for (std::size_t b = 0; b < nblocks; ++b) out.block_start[b + 1] += out.block_start[b];
  const std::size_t nc = out.block_start[nblocks];
  size_outputs(out, h, np, nc);

  // 2. Packed contact list in list order, each contact with the slot of its spring.
  if (h.slot.size() != np) h.map_slots(np);
  const std::size_t ntypes = table.types();
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t b) {
    const std::size_t k0 = b * kBlock, k1 = std::min(np, k0 + kBlock);
    const auto c = static_cast<std::int32_t>(out.block_start[b]);
#ifdef GF_COMPACT_AVX512
    compact_avx512(list, h, out, k0, k1, c, static_cast<std::int32_t>(out.block_start[b + 1]));
#else
    compact_scalar(list, h, out, k0, k1, c);
#endif
  });

  // 3. Geometry and law over whole batches of contacts; the remainder through the scalar path.
  constexpr std::size_t K = Law::kConstants, H = Law::kHistory;
  for (std::size_t q = 0; q < K; ++q) out.coeff[q].clear();
  for (std::size_t a = 0; a < ntypes; ++a)
    for (std::size_t t = 0; t < static_cast<std::size_t>(kMaxSpecies); ++t) {
      const double* v = table.pair(a, std::min(t, ntypes - 1));
      for (std::size_t q = 0; q < K; ++q) out.coeff[q].push_back(v[q]);
    }
  // A constant that is the same for every type pair is broadcast instead of gathered.
  for (std::size_t q = 0; q < K; ++q)
    out.coeff_uniform[q] = std::all_of(out.coeff[q].begin(), out.coeff[q].end(),
                                       [&](double x) { return x == out.coeff[q][0]; });
  // With few species (a binary mixture has four type pairs) each varying constant sits in a
  // register, indexed by the compact type pair species_i * ntypes + species_j.
  const bool in_register = ntypes * ntypes <= RegisterTable::capacity;
  RegisterTable reg[K];
  if (in_register)
    for (std::size_t q = 0; q < K; ++q) {
      double v[RegisterTable::capacity] = {};
      for (std::size_t a = 0; a < ntypes; ++a)
        for (std::size_t t = 0; t < ntypes; ++t) v[a * ntypes + t] = out.coeff[q][a * kMaxSpecies + t];
      reg[q] = RegisterTable(v, ntypes * ntypes);
    }
  auto coeff = [&](std::size_t q, const std::int32_t* idx, const std::int32_t* compact) {
    return out.coeff_uniform[q] ? B(out.coeff[q][0])
                                : (in_register ? reg[q].lookup(compact) : gather32(out.coeff[q].data(), idx));
  };
  // Whole batches of a slab's contacts from its first; the remainder through the scalar path.
  [[maybe_unused]] const bool sized = table.sized();
  auto law = [&](std::size_t cbeg, std::size_t cend, const SlabTorques& st) {
    const bool spin = g.spin;
    std::size_t c0 = cbeg;
    for (; c0 + L <= cend; c0 += L) {
      // Contacts are in owner order: the owners of a batch are a few adjacent rows, loaded whole
      // and permuted into lanes; partners are scattered and gathered.
      const RowWindow bi = row_window(&out.ci[c0], rows);
      const std::int32_t* bj = &out.cj[c0];
      const std::int32_t* bt_idx = &out.ctype[c0];
      const V d{gather32(g.pos.x.data(), bj) - load_rows(g.pos.x.data(), bi),
                gather32(g.pos.y.data(), bj) - load_rows(g.pos.y.data(), bi),
                gather32(g.pos.z.data(), bj) - load_rows(g.pos.z.data(), bi)};
      const B ri = load_rows(g.radius.r.data(), bi), rj = gather32(g.radius.r.data(), bj);
      // The distance correctly rounded (the overlap is its small difference from r_i + r_j), the
      // reciprocal from the estimate (touching pairs are apart by more than 0).
      const B d2 = dot(d, d);
      const V wi = spin ? V{load_rows(g.omega.x.data(), bi), load_rows(g.omega.y.data(), bi),
                            load_rows(g.omega.z.data(), bi)}
                        : V{B(0.0), B(0.0), B(0.0)};
      const V wj = spin ? V{gather32(g.omega.x.data(), bj), gather32(g.omega.y.data(), bj),
                            gather32(g.omega.z.data(), bj)}
                        : V{B(0.0), B(0.0), B(0.0)};
      const V vij{load_rows(g.vel.x.data(), bi) - gather32(g.vel.x.data(), bj),
                  load_rows(g.vel.y.data(), bi) - gather32(g.vel.y.data(), bj),
                  load_rows(g.vel.z.data(), bi) - gather32(g.vel.z.data(), bj)};
      const SphereContact<B> sc = sphere_sphere(d, xsimd::sqrt(d2), rsqrt_of(d2), ri, rj, vij, wi, wj);
      alignas(64) std::int32_t compact[L];
      static_assert(kMaxSpecies == 64);
      for (std::size_t l = 0; l < L; ++l)
        compact[l] = (bt_idx[l] >> 6) * static_cast<std::int32_t>(ntypes) + (bt_idx[l] & 63);
      std::array<B, K> cf;
      for (std::size_t q = 0; q < K; ++q) cf[q] = coeff(q, bt_idx, compact);
      if constexpr (SizedLaw<Law>)
        if (sized) {  // grains of a size distribution: the constants of these grains (size_scaling.hpp)
          alignas(64) std::int32_t ta[L], tb[L];
          for (std::size_t l = 0; l < L; ++l) ta[l] = bt_idx[l] >> 6, tb[l] = bt_idx[l] & 63;
          const double* m0 = table.nominal_mass();
          const double* r0 = table.nominal_radius();
          Law::resize(cf, pair_size_ratio(load_rows(g.mass.m.data(), bi), gather32(g.mass.m.data(), bj), ri, rj,
                                          gather32(m0, ta), gather32(m0, tb), gather32(r0, ta), gather32(r0, tb)));
        }
      PairHistory& nh = out.next;
      // History of the last evaluation: between rebuilds a batch's contacts usually all persist
      // and sit in a run of the old history, read with plain loads; otherwise gathered by slot.
      const std::int32_t* sl = &out.cslot[c0];
      // The old history is one stream among many and is read once: ask for that of a batch
      // kAheadSprings contacts on (the slot there, when it has one, is a few entries from sl[0] +
      // kAheadSprings).
      if (c0 + kAheadSprings < cend) {
        const std::int32_t ahead = out.cslot[c0 + kAheadSprings];
        if (ahead >= 0) {
          const auto e = static_cast<std::size_t>(ahead);
          for (std::size_t q = 0; q < H; ++q) __builtin_prefetch(h.value[q].data() + e);
        }
      }
      std::array<B, H> s;
      if (sl[0] >= 0 && sl[L - 1] - sl[0] == static_cast<std::int32_t>(L - 1) && is_run(sl)) {
        const auto e = static_cast<std::size_t>(sl[0]);
        for (std::size_t q = 0; q < H; ++q) s[q] = B::load_unaligned(&h.value[q][e]);
      } else {
        for (std::size_t q = 0; q < H; ++q) s[q] = gather32_or_zero(h.value[q].data(), sl);
      }
      const auto all = B(0.0) == B(0.0);
      const ContactForce<B> res = Law::evaluate(all, sc.g, cf, B(dt), s);
      for (std::size_t q = 0; q < H; ++q) s[q].store_unaligned(&nh.value[q][c0]);
      const V nxf = cross(sc.g.n, res.force_t);
      (sc.li * nxf.x + res.torque_i.x).store_unaligned(&st.t[0][c0 - st.c0]);
      (sc.li * nxf.y + res.torque_i.y).store_unaligned(&st.t[1][c0 - st.c0]);
      (sc.li * nxf.z + res.torque_i.z).store_unaligned(&st.t[2][c0 - st.c0]);
      res.force.x.store_unaligned(&out.fx[c0]);
      res.force.y.store_unaligned(&out.fy[c0]);
      res.force.z.store_unaligned(&out.fz[c0]);
      (sc.lj * nxf.x + res.torque_j.x).store_unaligned(&st.t[3][c0 - st.c0]);
      (sc.lj * nxf.y + res.torque_j.y).store_unaligned(&st.t[4][c0 - st.c0]);
      (sc.lj * nxf.z + res.torque_j.z).store_unaligned(&st.t[5][c0 - st.c0]);
    }
    for (std::size_t c = c0; c < cend; ++c) {
      const std::size_t k = static_cast<std::size_t>(out.next.pair[c]);
      carry_history(h, out.cslot[c], out.next, c);
      evaluate_one<Law>(g, list.i[k], list.j[k], out.next, table, dt, out, c, st);
    }
  };
  // 4. The law and the sums, slab by slab.
  evaluate_and_sum(g, list, out, law);
  std::swap(h, out.next);
  return std::any_of(out.block_over.begin(), out.block_over.end(), [](std::uint8_t v) { return v != 0; });
}

// Both drivers for each law of a LawList: a table with external linkage makes the compiler emit them.
template <class... Laws>
constexpr auto pair_drivers(LawList<Laws...>) {
  return std::array{std::pair{&compute_pair_forces<Laws>, &compute_pair_forces_scalar<Laws>}...};
}

}  // namespace gf

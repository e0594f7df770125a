#!/usr/bin/env python3
"""Ablation variants of the pair driver, for timing what each part of it costs.

Rewrites systems/contact/pair_contact_kernels.hpp in a scratch work tree (never the main one) into
one variant, whose pair_contact_bench is then timed against the unchanged one:
  base          unchanged
  noread        the springs of the last evaluation not read (constants instead)
  nowrite       the new springs not stored
  localpartner  the partner's velocity and spin gathered from the owner's rows (cache-resident)
                instead of the partner's: the cost of those six partner gathers
  lawtwice      the law evaluated a second time on perturbed input: the cost of its arithmetic
  nosums        the slab sums skipped
  runsum        the owner's sums carried in registers (branch-free select) into a second record
                per row; the partner sides as before
  runsum_scalar the same written with a plain conditional (which the compiler turned into a branch)
  noprefilter   after the first 20 evaluations, each batch's touching flags taken from the last
                evaluation's (the same positions in the benchmark) instead of the overlap test: the
                cost of the test's gathers and arithmetic, which a cheaper test (in float, or over
                cluster-pair tiles) could save at most
Each variant but base computes wrong forces: for timing only.

  git worktree add /tmp/ablate HEAD
  /usr/bin/python3 tools/contact/pair_ablation.py /tmp/ablate VARIANT
  cmake --build /tmp/ablate/build --target pair_contact_bench
"""
import sys

tree, v = sys.argv[1], sys.argv[2]
p = tree + '/systems/contact/pair_contact_kernels.hpp'
s = open(p).read()
def rep(old, new):
    global s
    assert s.count(old) == 1, old
    s = s.replace(old, new)
if v=='noread':
    rep("""      if (sl[0] >= 0 && sl[L - 1] - sl[0] == static_cast<std::int32_t>(L - 1) && is_run(sl)) {""","""      if (true) { for (std::size_t q = 0; q < H; ++q) s[q] = B(1e-9 * static_cast<double>(q)); } else if (sl[0] >= 0 && sl[L - 1] - sl[0] == static_cast<std::int32_t>(L - 1) && is_run(sl)) {""")
elif v=='nowrite':
    rep("      const ContactForce<B> res = Law::evaluate(all, sc.g, cf, B(dt), s);","      ContactForce<B> res = Law::evaluate(all, sc.g, cf, B(dt), s);")
    rep("""      for (std::size_t q = 0; q < H; ++q) s[q].store_unaligned(&nh.value[q][c0]);""","""      res.force.x = res.force.x + s[0] * B(0.0) + s[1] * B(0.0) + s[2] * B(0.0) + s[3] * B(0.0) + s[4] * B(0.0) + s[5] * B(0.0); (void)nh;""")
elif v=='localpartner':
    rep("""      const V wj = spin ? V{gather32(g.omega.x.data(), bj), gather32(g.omega.y.data(), bj),
                            gather32(g.omega.z.data(), bj)}""","""      const std::int32_t* bjx = &out.ci[c0];
      const V wj = spin ? V{gather32(g.omega.x.data(), bjx), gather32(g.omega.y.data(), bjx),
                            gather32(g.omega.z.data(), bjx)}""")
    rep("""      const V vij{load_rows(g.vel.x.data(), bi) - gather32(g.vel.x.data(), bj),
                  load_rows(g.vel.y.data(), bi) - gather32(g.vel.y.data(), bj),
                  load_rows(g.vel.z.data(), bi) - gather32(g.vel.z.data(), bj)};""","""      const V vij{load_rows(g.vel.x.data(), bi) - gather32(g.vel.x.data(), bjx),
                  load_rows(g.vel.y.data(), bi) - gather32(g.vel.y.data(), bjx),
                  load_rows(g.vel.z.data(), bi) - gather32(g.vel.z.data(), bjx)};""")
elif v=='lawtwice':
    rep("""      const ContactForce<B> res = Law::evaluate(all, sc.g, cf, B(dt), s);""","""      std::array<B, H> s2 = s;
      ContactGeometry<B> g2 = sc.g; g2.v.x = g2.v.x * B(1.01); g2.w.y = g2.w.y * B(1.01); g2.n.x = g2.n.x * B(0.999);
      const ContactForce<B> res0 = Law::evaluate(all, g2, cf, B(dt), s2);
      ContactForce<B> res = Law::evaluate(all, sc.g, cf, B(dt), s);
      res.force.x = res.force.x + res0.force.x * B(0.0) + s2[0] * B(0.0) + res0.torque_i.y * B(0.0);""")
elif v=='nosums':
    rep("""    sums.run(a, b, n, rows, c0, c1, st, acc.data(), spill);""","""    if (std::getenv("GF_SUMS")) sums.run(a, b, n, rows, c0, c1, st, acc.data(), spill);""")
    s=s.replace("#include <cstring>","#include <cstring>\n#include <cstdlib>")
elif v in ('runsum', 'runsum_scalar'):
    rep("""    std::fill(acc, acc + (b - a) * kAcc, 0.0);
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
""","""    std::fill(acc, acc + (b - a) * kAcc, 0.0);
    std::fill(has_own, has_own + (b - a), std::uint8_t(0));
    using V4 = double __attribute__((vector_size(32)));
    using M4 = std::int64_t __attribute__((vector_size(32)));
    using V2 = double __attribute__((vector_size(16)));
    using M2 = std::int64_t __attribute__((vector_size(16)));
    V4 run0 = {0, 0, 0, 0};
    V2 run1 = {0, 0};
    std::size_t prev = b;
    for (std::size_t c = c0; c < c1; ++c) {
      const std::size_t q = c - c0;
      const auto i = static_cast<std::size_t>(ri[c]), j = static_cast<std::size_t>(rj[c]);
      const double* __restrict ai = acc + (i - a) * kAcc;
      double* __restrict oi = own + (i - a) * kAcc;
      const std::int64_t same = -static_cast<std::int64_t>(i == prev);
      prev = i;
      const M4 m4 = {same, same, same, same};
      const M2 m2 = {same, same};
      V4 base0;
      V2 base1;
      std::memcpy(&base0, ai, sizeof base0);
      std::memcpy(&base1, ai + 4, sizeof base1);
      const V4 add0 = {fx[c], fy[c], fz[c], tix[q]};
      const V2 add1 = {tiy[q], tiz[q]};
      run0 = (m4 != 0 ? run0 : base0) + add0;
      run1 = (m2 != 0 ? run1 : base1) + add1;
      std::memcpy(oi, &run0, sizeof run0);
      std::memcpy(oi + 4, &run1, sizeof run1);
      has_own[i - a] = 1;
""")
    rep("""      for (std::size_t r = a; r < b; ++r) col[r] = acc[(r - a) * kAcc + k];""","""      for (std::size_t r = a; r < b; ++r) col[r] = has_own[r - a] ? own[(r - a) * kAcc + k] : acc[(r - a) * kAcc + k];""")
    rep("""           const SlabTorques& st, double* __restrict acc, std::vector<PairForces::Spill>* spill) const {""","""           const SlabTorques& st, double* __restrict acc, double* __restrict own, std::uint8_t* __restrict has_own,
           std::vector<PairForces::Spill>* spill) const {""")
    rep("""    if (acc.size() < rows * SlabSums::kAcc) acc.resize(rows * SlabSums::kAcc);""","""    if (acc.size() < 2 * rows * SlabSums::kAcc) acc.resize(2 * rows * SlabSums::kAcc);
    thread_local std::vector<std::uint8_t> has_own;
    if (has_own.size() < rows) has_own.resize(rows);""")
    rep("""    sums.run(a, b, n, rows, c0, c1, st, acc.data(), spill);""","""    sums.run(a, b, n, rows, c0, c1, st, acc.data(), acc.data() + rows * SlabSums::kAcc, has_own.data(), spill);""")
    if v == 'runsum_scalar':
        rep("""      const std::int64_t same = -static_cast<std::int64_t>(i == prev);
      prev = i;
      const M4 m4 = {same, same, same, same};
      const M2 m2 = {same, same};
      V4 base0;
      V2 base1;
      std::memcpy(&base0, ai, sizeof base0);
      std::memcpy(&base1, ai + 4, sizeof base1);
      const V4 add0 = {fx[c], fy[c], fz[c], tix[q]};
      const V2 add1 = {tiy[q], tiz[q]};
      run0 = (m4 != 0 ? run0 : base0) + add0;
      run1 = (m2 != 0 ? run1 : base1) + add1;
      std::memcpy(oi, &run0, sizeof run0);
      std::memcpy(oi + 4, &run1, sizeof run1);""", """      const bool same = i == prev;
      prev = i;
      const double add[6] = {fx[c], fy[c], fz[c], tix[q], tiy[q], tiz[q]};
      for (std::size_t k = 0; k < 6; ++k) {
        run[k] = (same ? run[k] : ai[k]) + add[k];
        oi[k] = run[k];
      }""")
        rep("""    using V4 = double __attribute__((vector_size(32)));
    using M4 = std::int64_t __attribute__((vector_size(32)));
    using V2 = double __attribute__((vector_size(16)));
    using M2 = std::int64_t __attribute__((vector_size(16)));
    V4 run0 = {0, 0, 0, 0};
    V2 run1 = {0, 0};""", """    double run[6] = {0, 0, 0, 0, 0, 0};""")
elif v=='noprefilter':
    rep("""  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t b) {
    const std::size_t k0 = b * kBlock, k1 = std::min(np, k0 + kBlock);
    std::uint32_t count = 0, over = 0;""", """  static int evaluations = 0;
  const bool cached = ++evaluations > 20;
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t b) {
    const std::size_t k0 = b * kBlock, k1 = std::min(np, k0 + kBlock);
    std::uint32_t count = 0, over = 0;
    if (cached) {
      for (std::size_t k = k0; k < k1; k += L) {
        std::uint64_t bytes;
        std::memcpy(&bytes, &out.touching[k], L);
        const std::uint32_t valid = (1u << std::min(L, k1 - k)) - 1u;
        count += static_cast<std::uint32_t>(__builtin_popcount(static_cast<std::uint32_t>(_pext_u64(bytes, 0x0101010101010101ull)) & valid));
      }
      out.block_start[b + 1] = count;
      return;
    }""")
elif v!='base':
    raise SystemExit(f'pair_ablation: unknown variant {v}')
open(p,'w').write(s)

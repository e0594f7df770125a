#!/usr/bin/env python3
"""Ablation variants of the wall driver, for timing what a packed list of wall contacts could save.

Rewrites systems/walls/wall_contact_kernels.hpp of a work tree into one variant, whose grainflow is
then timed end to end against the unchanged one:
  base       unchanged
  nosprings  the wall springs neither read nor prefetched nor stored (zeros instead): the most a
             contiguous spring list could save, since it still reads and writes one record a contact
Each variant but base computes wrong forces: for timing only.

  cp build/grainflow /tmp/base
  /usr/bin/python3 tools/contact/wall_ablation.py . nosprings
  cmake --build build --target grainflow && cp build/grainflow /tmp/nosprings
  git checkout systems/walls/wall_contact_kernels.hpp && cmake --build build --target grainflow
  ROUNDS=5 tools/contact/bench_before_after.sh /tmp/base /tmp/nosprings scenes/drum_seed000_flowing.toml
"""
import sys

tree, v = sys.argv[1], sys.argv[2]
p = tree + '/systems/walls/wall_contact_kernels.hpp'
s = open(p).read()


def rep(old, new):
    global s
    assert s.count(old) == 1, old
    s = s.replace(old, new)


if v == 'nosprings':
    rep("""            __builtin_prefetch(&hs[a]);
""", "")
    rep("""          for (std::size_t k = 0; k < H; ++k) s[k] = gather32(hbase + k, at);""",
        """          for (std::size_t k = 0; k < H; ++k) s[k] = B(0.0);
          (void)hbase;
          (void)at;""")
    rep("""            for (std::size_t k = 0; k < H; ++k) hs[i].s[k] = out[k][l];
""", "")
elif v != 'base':
    sys.exit(f"no variant {v!r}: base, nosprings")
open(p, 'w').write(s)

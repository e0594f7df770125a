#!/bin/bash
# Alternated rounds of the pair kernel's benchmark with the prefilter in double, in float with the
# double fallback, and in float trusted (the bound).
# Needs the prototype applied: git apply studies/contact/results/float_prefilter.patch, then rebuild
# pair_contact_bench; its variants are switched by the environment (GF_PREFILTER_DOUBLE, GF_PREFILTER_TRUST).
#   studies/contact/prefilter_rounds.sh > studies/contact/results/bench_float_prefilter.csv
echo "round,variant,threads,median_ms"
for r in 1 2 3 4 5; do
  for v in double float float_trusted; do
    unset GF_PREFILTER_DOUBLE GF_PREFILTER_TRUST
    [ $v = double ] && export GF_PREFILTER_DOUBLE=1
    [ $v = float_trusted ] && export GF_PREFILTER_TRUST=1
    for t in 1 2; do
      m=$(./build/bench/pair_contact_bench --benchmark_filter="simd/threads:$t/" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true 2>/dev/null | awk '/_median/{print $2}')
      echo "$r,$v,$t,$m"
    done
  done
done

#!/usr/bin/env bash
# Runs the same torte_bench cases in a SIMD build and in a scalar-only build (TORTE_SCALAR_ONLY=ON, i.e.
# HWY_COMPILE_ONLY_SCALAR) and prints, per case, both rates and the speedup:
#   workload=<case> simd_mrays=<x> scalar_mrays=<y> speedup=<x/y>
# (simd_msamples/scalar_msamples for the shading cases of bench_shading.cc, whose rate counter is Msamples).
# Usage: bench/scalar_vs_simd.sh SIMD_TORTE_BENCH SCALAR_TORTE_BENCH [FILTER [extra Google Benchmark args...]]
# Default filter: the wide8 traversal cases of primary rays (closest hit) and shadow rays (any hit), single rays
# and packets of 8 and 16, the shading cases (wavefront kernels, per-hit baseline, phase-2 BSDF evaluation) and
# the light BVH's descent (one receiver at a time, and the batch in vector lanes).
# Used by `make bench-scalar-vs-simd`.
set -euo pipefail
if (($# < 2)); then
  sed -n '2,7p' "$0" >&2
  exit 2
fi
simd=$1 scalar=$2
filter=${3:-'/(primary/closest|shadow/any)/wide8/|^(shading|eval|light_bvh)/'}
shift $(($# >= 3 ? 3 : 2))
extra=("$@")
((${#extra[@]})) || extra=(--benchmark_min_time=0.1)

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for variant in simd scalar; do
  bin=${!variant}
  echo "== $variant: $bin --benchmark_filter='$filter' ${extra[*]}" >&2
  "$bin" --benchmark_filter="$filter" --benchmark_out="$tmp/$variant.json" --benchmark_out_format=json \
    "${extra[@]}" >&2
  if [[ ! -s $tmp/$variant.json ]]; then
    echo "scalar_vs_simd: $variant run produced no results (skipped, see above)" >&2
    exit 0
  fi
done

# Google Benchmark's JSON is pretty-printed one field per line: pick name, Mrays and error flags per run, and
# the Highway target from the context.
extract() {
  awk '
    /"torte_target":/ { t = $2; gsub(/[",]/, "", t); print "#target", t }
    /"name":/ { n = $2; gsub(/[",]/, "", n); name = n; err = 0 }
    /"aggregate_name": "(mean|stddev|cv)"/ { name = "" }
    /"error_occurred": true/ { err = 1 }
    /"(Mrays|Msamples)":/ {
      u = $1; gsub(/[":]/, "", u); v = $2; gsub(/,/, "", v); if (name != "") print name, v, err, tolower(u)
    }
  ' "$1"
}
extract "$tmp/simd.json" >"$tmp/simd.txt"
extract "$tmp/scalar.json" >"$tmp/scalar.txt"
simd_target=$(awk '$1 == "#target" { print $2 }' "$tmp/simd.txt")
scalar_target=$(awk '$1 == "#target" { print $2 }' "$tmp/scalar.txt")
echo "# scalar vs SIMD: SIMD build dispatches to $simd_target, scalar-only build to $scalar_target (1 thread, CPU time)"
if [[ $scalar_target != SCALAR ]]; then
  echo "scalar_vs_simd: WARNING: the scalar-only build reports target '$scalar_target', not SCALAR" >&2
fi
awk '
  NR == FNR {
    if ($1 != "#target") { if (!($1 in simd)) order[++n] = $1; simd[$1] = $2; bad[$1] = $3; unit[$1] = $4 }
    next
  }
  $1 != "#target" { scalar[$1] = $2; bad[$1] = bad[$1] || $3 }
  END {
    status = 0
    for (i = 1; i <= n; ++i) {
      k = order[i]
      if (!(k in scalar)) continue
      if (bad[k]) { printf "workload=%s FAILED (a run reported an error, see above)\n", k; status = 1; continue }
      printf "workload=%s simd_%s=%.3f scalar_%s=%.3f speedup=%.2f\n", k, unit[k], simd[k], unit[k], scalar[k],
             simd[k] / scalar[k]
    }
    exit status
  }
' "$tmp/simd.txt" "$tmp/scalar.txt"

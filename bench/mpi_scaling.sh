#!/usr/bin/env bash
# Distributed rendering on this box (docs/distributed.md): render seconds of one process against mpirun with 2
# ranks, each rank one thread (so 2 ranks use the 2 cores a 2-thread process would), and the cost of one work unit
# (tile, pass) measured on a render that does almost nothing else. Medians of N runs.
# Usage: bench/mpi_scaling.sh <torte binary> [N=3] [scene ...]   (scenes: cornell lucy; default both)
set -euo pipefail
torte=${1:?usage: mpi_scaling.sh <torte binary> [N] [scene ...]}
n=${2:-3}
shift $(($# >= 2 ? 2 : $#))
scenes=("$@")
[[ ${#scenes[@]} -gt 0 ]] || scenes=(cornell lucy)
src=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mpirun=(mpirun --oversubscribe --allow-run-as-root)

# The render seconds of the summary line ("render WxH, S spp: build B, render R s; ...").
render_seconds() { sed -n 's/^render [0-9]*x[0-9]*, [0-9]* spp[^:]*: build [^,]*, render \([0-9.]*\) s;.*/\1/p' "$1" | tail -1; }
median() { printf '%s\n' "$@" | sort -g | sed -n "$((($# + 1) / 2))p"; }
run() {  # run LABEL COMMAND...: median render seconds of N runs
  local label=$1 times=()
  shift
  for ((i = 0; i < n; ++i)); do
    "$@" >/dev/null 2>"$work/err.txt" || { cat "$work/err.txt" >&2; exit 1; }
    times+=("$(render_seconds "$work/err.txt")")
  done
  median "${times[@]}"
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) cores"
for s in "${scenes[@]}"; do
  case "$s" in
    cornell) script=$src/scenes/cornell-box.lua args=(width=256 height=256 spp=64) ;;
    lucy) script=$src/scenes/lucy-scale.lua args=(width=400 height=300 spp=16) ;;
    *) echo "unknown scene $s (cornell, lucy)" >&2; exit 2 ;;
  esac
  args+=(output="$work/out.exr")
  one1=$(run one1 "$torte" --threads 1 "$script" "${args[@]}")
  one2=$(run one2 "$torte" --threads 2 "$script" "${args[@]}")
  two=$(run two "${mpirun[@]}" -n 2 "$torte" --threads 1 "$script" "${args[@]}")
  printf '%-8s 1 process x 1 thread %6.2f s | 1 process x 2 threads %6.2f s | 2 ranks x 1 thread %6.2f s | ' \
    "$s" "$one1" "$one2" "$two"
  printf 'speed-up 1 -> 2 ranks %.2fx (2 threads: %.2fx)\n' "$(echo "$one1 / $two" | bc -l)" \
    "$(echo "$one1 / $one2" | bc -l)"
done

# Per-unit cost: a 512x512 frame of 16 spp at max_depth 0 is 1024 tiles x 5 passes of camera rays only.
args=(width=512 height=512 spp=16 max_depth=0 output="$work/out.exr")
base=$(run base "$torte" --threads 1 "$src/scenes/cornell-box.lua" "${args[@]}")
dist=$(run dist "${mpirun[@]}" -n 2 "$torte" --threads 1 "$src/scenes/cornell-box.lua" "${args[@]}")
units=$(sed -n 's/^distributed over [0-9]* ranks: .* of the \([0-9]*\) units.*/\1/p' "$work/err.txt" | tail -1)
units=${units:-1}
printf 'work units: %d; 1 process %.3f s, 2 ranks %.3f s: %.1f us per unit over the ideal half\n' "$units" "$base" \
  "$dist" "$(echo "($dist - $base / 2) / $units * 1000000" | bc -l)"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

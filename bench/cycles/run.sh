#!/usr/bin/env bash
# make bench-cycles: the same scene rendered by torte and by Blender's Cycles (CPU), both times, their ratio and the
# region means of both images (bench/cycles/compare.py). torte's time is the whole process (start-up, scene build,
# render, EXR output); Cycles' is its render call (bench/cycles/cycles_common.py), Blender's start-up excluded.
# Usage: bench/cycles/run.sh <torte binary> [scene ...]   scenes: cornell (default: cornell dragon)
# Environment: SIZE (256), SPP (1024), BOUNCES (64), THREADS (2), OUT (out/bench-cycles), DATA (meshes directory).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
torte=${1:?usage: run.sh <torte binary> [cornell] [dragon]}
shift
scenes=("$@")
((${#scenes[@]})) || scenes=(cornell dragon)
SIZE=${SIZE:-256} SPP=${SPP:-1024} BOUNCES=${BOUNCES:-64} THREADS=${THREADS:-2}
OUT=${OUT:-out/bench-cycles}
DATA=${DATA:-$here/../../../shared/data/meshes}
py=/usr/bin/python3  # Debian's python3 (python3-openimageio, python3-numpy), not a pyenv shim
mkdir -p "$OUT"
command -v blender >/dev/null || { echo "run.sh: blender not found (scripts/install-deps.sh --cycles)" >&2; exit 1; }

now() { date +%s.%N; }
summary=()
for scene in "${scenes[@]}"; do
  case "$scene" in
    cornell) lua=scenes/cornell-box.lua; blend=(cornell_box.py); extra=(); cmp=(--cornell) ;;
    dragon)  lua=scenes/dragon-bench.lua; ply="$DATA/dragon/dragon_100k_binary_le.ply"
             [[ -f $ply ]] || { echo "run.sh: $ply not found (set DATA)" >&2; exit 1; }
             blend=(dragon.py); extra=("data=$DATA"); cmp=() ;;
    *) echo "run.sh: unknown scene $scene (cornell, dragon)" >&2; exit 2 ;;
  esac
  plyarg=(); [[ $scene == dragon ]] && plyarg=("ply=$ply")
  echo "== $scene: ${SIZE}x${SIZE}, $SPP spp, $BOUNCES bounces, $THREADS threads" >&2
  t0=$(now)
  "$torte" --threads "$THREADS" "$lua" width="$SIZE" height="$SIZE" spp="$SPP" max_depth="$BOUNCES" \
    "${extra[@]}" output="$OUT/$scene-torte.exr" >&2
  t1=$(now)
  torte_s=$(echo "$t1 - $t0" | bc -l)
  cycles_log=$(blender -b --factory-startup --python "$here/${blend[0]}" -- out="$OUT/$scene-cycles.exr" \
    size="$SIZE" spp="$SPP" bounces="$BOUNCES" threads="$THREADS" "${plyarg[@]}" 2>&1) ||
    { echo "$cycles_log" >&2; echo "run.sh: Blender failed" >&2; exit 1; }
  cycles_s=$(echo "$cycles_log" | sed -n 's/^cycles_render_seconds=//p')
  [[ -n $cycles_s ]] || { echo "$cycles_log" >&2; echo "run.sh: no render time from Blender" >&2; exit 1; }
  "$py" "$here/compare.py" "$OUT/$scene-torte.exr" "$OUT/$scene-cycles.exr" "${cmp[@]}" | tee "$OUT/$scene-regions.txt"
  diff=$(sed -n 's/^regions_max_rel_diff=\([0-9.]*\).*/\1/p' "$OUT/$scene-regions.txt")
  ratio=$(echo "$cycles_s / $torte_s" | bc -l)
  line=$(printf '%-8s torte %7.2f s   cycles %7.2f s   ratio %5.2fx   regions max diff %5.2f %%' \
    "$scene" "$torte_s" "$cycles_s" "$ratio" "$(echo "100 * $diff" | bc -l)")
  echo "$line"
  summary+=("$line")
done
echo "== summary ($(date -u +%FT%TZ), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) CPUs," \
     "$(blender --version 2>/dev/null | head -1))"
printf '%s\n' "${summary[@]}"
echo "acceptance (issue 23): cornell ratio >= 3.0x and every region within 1 %"

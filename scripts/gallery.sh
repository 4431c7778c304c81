#!/usr/bin/env bash
# Renders the gallery: the four figures of the seed (dort, "Physically-based rendering: a piece of cake", Špaček
# 2016) and one image per shipped scene, to OUT_DIR/<name>.png, and writes OUT_DIR/gallery.md: a markdown table
# with each image's command, wall time, peak resident memory (GNU time) and geometry (from --stats).
#
#   scripts/gallery.sh BUILD_DIR OUT_DIR [NAME ...]      (make gallery: scripts/gallery.sh build docs/gallery)
#
# NAMEs pick some images (e.g. `scripts/gallery.sh build /tmp/g cornell-box shapes`); gallery.md then lists only
# those. An image whose data in ../shared/data is missing is skipped with a message; a render that fails is
# reported and the script goes on, then exits 1. The sizes are chosen so the whole gallery takes about 6 minutes
# on 2 cores. Each render's output goes to out/gallery-logs/<name>.log (GALLERY_LOG_DIR overrides the folder).
set -euo pipefail

if (($# < 2)); then
  echo "usage: $0 BUILD_DIR OUT_DIR [NAME ...]" >&2
  exit 2
fi
build_dir=$1
out_dir=$2
shift 2
wanted=("$@")

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
data=$repo/../shared/data
torte=$build_dir/torte
[[ $torte == /* ]] || torte=$PWD/$torte
if [[ ! -x $torte ]]; then
  echo "gallery: $torte not found or not executable (make build first)" >&2
  exit 1
fi
gnu_time=/usr/bin/time
if [[ ! -x $gnu_time ]]; then
  echo "gallery: $gnu_time (GNU time, Debian package 'time') is missing: run scripts/install-deps.sh" >&2
  exit 1
fi

mkdir -p "$out_dir"
out_dir=$(cd "$out_dir" && pwd)
log_dir=${GALLERY_LOG_DIR:-$repo/out/gallery-logs}
mkdir -p "$log_dir"

# name | data it needs (paths below ../shared/data, comma-separated; empty: none) | scene and arguments
# The seed's figures first (figure*: they use materials.lua, lucy-scale.lua and minecraft.lua), then the other
# shipped scenes (not bench-*.lua).
images=(
  "figure1-minecraft|minecraft/bluenbt-1.20.1-paper|scenes/minecraft.lua width=960 height=540 spp=32"
  "figure2-buddha-materials|meshes/happy-buddha/happy_vrip_res3.ply|scenes/materials.lua width=960 height=360 spp=256"
  "figure3-lucy-igi|meshes/lucy/lucy_100k.obj,meshes/dragon/dragon_100k_binary_le.ply,meshes/bunny/bun_zipper.ply|scenes/lucy-scale.lua integrator=igi spp=64 width=800 height=600"
  "figure4-minecraft-direct|minecraft/prismarine-1.16|scenes/minecraft.lua world=prismarine-1.16 integrator=direct spp=16 width=960 height=540"
  "cornell-box||scenes/cornell-box.lua width=400 height=400 spp=128"
  "shapes||scenes/shapes.lua width=400 height=300 spp=64"
  "textures||scenes/textures.lua width=640 height=360 spp=64"
  "lights||scenes/lights.lua width=400 height=300 spp=64"
  "instancing||scenes/instancing.lua width=800 height=500 spp=32"
  "many-lights||scenes/many-lights.lua width=480 height=270 spp=32"
  "caustic||scenes/caustic.lua width=400 height=300 spp=64 integrator=vcm"
  "mirror-lit||scenes/mirror-lit.lua width=400 height=300 spp=128 integrator=bdpt"
  "door-gap||scenes/door-gap.lua width=400 height=300 spp=128 integrator=bdpt"
  "dragon-bench|meshes/dragon/dragon_100k_binary_le.ply|scenes/dragon-bench.lua width=640 height=320 spp=64"
)

# 28303536 -> "28.3 M", 5080231 -> "5.08 M", 20544 -> "20.5 k", 32 -> "32"
human() {
  awk -v n="$1" 'BEGIN {
    if (n >= 1e9) printf "%.3g G", n / 1e9; else if (n >= 1e6) printf "%.3g M", n / 1e6;
    else if (n >= 1e4) printf "%.3g k", n / 1e3; else printf "%d", n }'
}

for w in "${wanted[@]}"; do
  known=0
  for entry in "${images[@]}"; do [[ ${entry%%|*} == "$w" ]] && known=1; done
  if ((!known)); then
    echo "gallery: unknown image '$w' (known: $(printf '%s ' "${images[@]%%|*}"))" >&2
    exit 2
  fi
done

table=()
failed=()
t_all=$(date +%s)
for entry in "${images[@]}"; do
  IFS='|' read -r name needs cmd <<<"$entry"
  if ((${#wanted[@]} > 0)); then
    pick=0
    for w in "${wanted[@]}"; do [[ $w == "$name" ]] && pick=1; done
    ((pick)) || continue
  fi
  missing=""
  if [[ -n $needs ]]; then
    IFS=',' read -r -a paths <<<"$needs"
    for p in "${paths[@]}"; do [[ -e $data/$p ]] || missing+=" $p"; done
  fi
  shown="torte $cmd"
  if [[ -n $missing ]]; then
    echo "gallery: skipping $name: ../shared/data lacks$missing" >&2
    table+=("| $name | \`$shown\` | skipped: no${missing} in ../shared/data | | |")
    continue
  fi
  read -r -a args <<<"$cmd"
  png=$out_dir/$name.png
  log=$log_dir/$name.log
  echo "gallery: $name: $shown" >&2
  # From the repository root, so the command is the one shown; --stats for the geometry column.
  if ! (cd "$repo" && "$gnu_time" -f "gallery-time %e %M" "$torte" --stats "${args[@]}" -o "$png") >"$log" 2>&1; then
    echo "gallery: $name FAILED; the end of $log:" >&2
    tail -n 15 "$log" >&2
    failed+=("$name")
    table+=("| $name | \`$shown\` | failed | | |")
    continue
  fi
  read -r seconds kib < <(awk '/^gallery-time / {print $2, $3}' "$log" | tail -n 1)
  # The last render's scene statistics: "primitives P (triangles T); I instances of G groups placing N; ..."
  prims=$(sed -n 's/^  primitives \([0-9]*\) .*/\1/p' "$log" | tail -n 1)
  tris=$(sed -n 's/^  primitives [0-9]* (triangles \([0-9]*\)).*/\1/p' "$log" | tail -n 1)
  placed=$(sed -n 's/^  primitives .* placing \([0-9]*\);.*/\1/p' "$log" | tail -n 1)
  voxels=$(sed -n 's/^voxel grid: \([0-9]*\) voxels.*/\1/p' "$log" | tail -n 1)
  geometry="$(human "${tris:-0}") triangles"
  if ((${prims:-0} > ${tris:-0})); then geometry="$(human "$prims") primitives ($geometry)"; fi
  if [[ -n $placed && $placed != 0 ]]; then geometry="$(human "$placed") triangles as placed by instances"; fi
  if [[ -n $voxels ]]; then geometry+=", $(human "$voxels") voxels"; fi
  mem=$(awk -v k="$kib" 'BEGIN { m = k / 1024; if (m >= 1024) printf "%.2f GiB", m / 1024; else printf "%.0f MiB", m }')
  size=$(awk -v b="$(stat -c %s "$png")" 'BEGIN { printf "%.0f KB", b / 1000 }')
  echo "gallery: $name: ${seconds} s, peak ${mem}, ${geometry}, wrote $png ($size)" >&2
  table+=("| $name | \`$shown\` | ${seconds} s | ${mem} | ${geometry} |")
done
t_all=$(($(date +%s) - t_all))

shown_dir=$(realpath --relative-to="$repo" "$out_dir")
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
version=$("$torte" --version 2>/dev/null | head -n 1 || true)
{
  echo "<!-- written by scripts/gallery.sh; $(date -u '+%Y-%m-%d %H:%M UTC') -->"
  echo "Rendered by \`scripts/gallery.sh\` (\`make gallery\`) with ${version:-torte} on $(nproc) cores of ${cpu:-an unknown CPU}"
  echo "(load average $(cut -d' ' -f1-3 /proc/loadavg) at the end), ${t_all} s in all. Time: wall clock of the whole"
  echo "process (scene build included); memory: peak resident set size (GNU time); geometry: the last render's"
  echo "\`--stats\`. Commands run from the repository root, each with \`--stats -o ${shown_dir}/<name>.png\`."
  echo
  echo "| image | command | time | peak memory | geometry |"
  echo "|---|---|---|---|---|"
  printf '%s\n' "${table[@]}"
} >"$out_dir/gallery.md"
echo "gallery: wrote $out_dir/gallery.md; ${t_all} s in all" >&2
if ((${#failed[@]} > 0)); then
  echo "gallery: failed: ${failed[*]}" >&2
  exit 1
fi

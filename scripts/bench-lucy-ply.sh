#!/bin/sh
# Issue 25: lucy-scale's 28,303,536 triangles written to binary PLY with mesh:save, then loaded with
# torte.mesh.load and rendered; prints the peak resident set of both runs (the goal: <= 2.0 GB from load to
# image). Usage: scripts/bench-lucy-ply.sh [build/torte] [extra lucy-scale arguments]
set -eu
torte=${1:-build/torte}
[ $# -gt 0 ] && shift
dir=out/lucy-ply
mkdir -p "$dir"
peak() { grep "Maximum resident" "$1" | awk '{printf "%.2f GB\n", $6 / 1048576}'; }
/usr/bin/time -v "$torte" scenes/lucy-scale.lua save_ply="$dir" output="$dir/grown.exr" "$@" 2> "$dir/grown.log"
echo "grown and saved:  peak RSS $(peak "$dir/grown.log")"
ls -l "$dir"/*.ply
/usr/bin/time -v "$torte" scenes/lucy-scale.lua ply_dir="$dir" output="$dir/loaded.exr" "$@" 2> "$dir/loaded.log"
grep -E "^(scene|memory per|render )" "$dir/loaded.log" || true
echo "loaded from PLY:  peak RSS $(peak "$dir/loaded.log")"

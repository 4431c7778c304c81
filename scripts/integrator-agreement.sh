#!/usr/bin/env bash
# Does every integrator converge to the same image as `path` (issue 24)? Renders scenes/cornell-box.lua at W x H
# with `path` at REF_SPP (seed 7) and with each integrator at SPP (seed 1), and prints each one's mean and its
# worst T x T tile mean against the path render, relative. The tests do the same on a small Cornell-like box
# at sample counts a test suite can afford; this is the long version.
# Usage: scripts/integrator-agreement.sh [build dir]; W, H (64x64), T (16), SPP (1024), REF_SPP (4096) and
# INTEGRATORS ("direct igi lt bdpt vcm ppm mlt"; direct at max_depth 1 against path at max_depth 1) override the
# defaults. Needs scripts/install-deps.sh --plots. Writes to out/integrator-agreement/.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
W=${W:-64}
H=${H:-64}
T=${T:-16}
SPP=${SPP:-1024}
REF_SPP=${REF_SPP:-4096}
INTEGRATORS=(${INTEGRATORS:-lt bdpt vcm ppm mlt igi direct})
OUT=out/integrator-agreement
mkdir -p "$OUT"
bash scripts/install-deps.sh --plots
render() {  # output integrator spp seed [args]
  local out=$1 integrator=$2 spp=$3 seed=$4
  shift 4
  [[ -f $out ]] || "$BUILD/torte" --quiet scenes/cornell-box.lua width="$W" height="$H" spp="$spp" seed="$seed" \
    integrator="$integrator" output="$out" "$@"
}
render "$OUT/path-$REF_SPP-${W}x$H.exr" path "$REF_SPP" 7
render "$OUT/path1-$REF_SPP-${W}x$H.exr" path "$REF_SPP" 7 max_depth=1
for i in "${INTEGRATORS[@]}"; do
  if [[ $i == direct ]]; then
    render "$OUT/$i-$SPP-${W}x$H.exr" "$i" "$SPP" 1 max_depth=1
  else
    render "$OUT/$i-$SPP-${W}x$H.exr" "$i" "$SPP" 1
  fi
done
/usr/bin/python3 - "$OUT" "$W" "$H" "$T" "$SPP" "$REF_SPP" "${INTEGRATORS[@]}" <<'PY'
import sys, numpy as np, OpenImageIO as oiio
out, w, h, t, spp, ref_spp = sys.argv[1:7]
t = int(t)
def load(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)[:, :, :3].mean(axis=2)
for i in sys.argv[7:]:
    ref = load(f"{out}/{'path1' if i == 'direct' else 'path'}-{ref_spp}-{w}x{h}.exr")
    img = load(f"{out}/{i}-{spp}-{w}x{h}.exr")
    tiles = [(img[y:y + t, x:x + t].mean() / ref[y:y + t, x:x + t].mean() - 1) for y in range(0, ref.shape[0], t)
             for x in range(0, ref.shape[1], t)]
    worst = max(tiles, key=abs)
    print(f"{i:6s} {spp} spp against path {ref_spp} spp: mean {img.mean() / ref.mean() - 1:+.2%}, "
          f"worst {t}x{t} tile {worst:+.2%}")
PY

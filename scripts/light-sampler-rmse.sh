#!/usr/bin/env bash
# Many-light sampling against light selection by power (docs/lights-and-sampling.md): for each scene, a long
# reference (light BVH), then both samplers at SPP samples per pixel; prints each one's RMSE, render time (the EXR's
# torte:render_seconds) and the RMSE at equal time, RMSE * sqrt(time) (Monte Carlo error falls as 1/sqrt(time)).
# Usage: scripts/light-sampler-rmse.sh [build dir] [spp] [reference spp]; W, H set the size (default 240x135).
# Needs python3-numpy and python3-openimageio (scripts/install-deps.sh --cycles). Writes to out/light-sampler/.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
SPP=${2:-16}
REF_SPP=${3:-1024}
W=${W:-240}
H=${H:-135}
OUT=out/light-sampler
mkdir -p "$OUT"
scenes=(${SCENES:-many-lights materials textures cornell-box})
for s in "${scenes[@]}"; do
  ref="$OUT/$s-ref$REF_SPP-${W}x$H.exr"
  [[ -f $ref ]] || "$BUILD/torte" --quiet "scenes/$s.lua" width=$W height=$H spp="$REF_SPP" seed=7 output="$ref"
  for ls in bvh power; do
    # The shipped scenes take no light_sampler argument: a wrapper sets it on every torte.render{} call.
    cat > "$OUT/wrap-$ls.lua" <<LUA
local real = torte.render
torte.render = function(t) t.light_sampler = "$ls"; return real(t) end
dofile("scenes/$s.lua")
LUA
    "$BUILD/torte" --quiet "$OUT/wrap-$ls.lua" width=$W height=$H spp="$SPP" seed=1 output="$OUT/$s-$ls.exr"
  done
done
/usr/bin/python3 - "$OUT" "$REF_SPP" "$W" "$H" "${scenes[@]}" <<'PY'
import sys, numpy as np, OpenImageIO as oiio
out, ref_spp, w, h, scenes = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5:]
def load(path):
    b = oiio.ImageBuf(path)
    return b.get_pixels(oiio.FLOAT)[:, :, :3], float(b.spec().get_float_attribute("torte:render_seconds"))
for s in scenes:
    ref, _ = load(f"{out}/{s}-ref{ref_spp}-{w}x{h}.exr")
    r = {}
    for ls in ("bvh", "power"):
        img, t = load(f"{out}/{s}-{ls}.exr")
        e = float(np.sqrt(((img - ref) ** 2).mean()))
        r[ls] = (e, t, e * np.sqrt(t))
        print(f"{s} {ls}: RMSE {e:.5f} in {t:.2f} s, RMSE at equal time {r[ls][2]:.5f}")
    print(f"{s}: the light BVH's RMSE at equal time is {r['power'][2] / r['bvh'][2]:.2f}x lower than by power")
PY

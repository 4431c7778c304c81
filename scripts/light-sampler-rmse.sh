#!/usr/bin/env bash
# Many-light sampling against light selection by power (docs/lights-and-sampling.md): for each scene, a long
# reference (light BVH), then both samplers at SPP samples per pixel; prints each one's RMSE, render time (the EXR's
# torte:render_seconds) and the RMSE at equal time, RMSE * sqrt(time) (Monte Carlo error falls as 1/sqrt(time)),
# over all pixels and over those that do not show an emitter (the reference's emission AOV is zero there).
# The reference is two independent halves A and B of REF_SPP / 2 samples each (seeds 7 and 8): for an image X
# independent of both, the mean of (X - A)(X - B) estimates X's mean squared error against the true image without
# the references' own noise, which (X - (A + B) / 2)^2 would add. That noise is not small everywhere: one
# sunlit caustic path in minecraft-cave's 1,024-sample reference (one pixel at 2.4 where the truth is 0.001) held
# half of the squared error of every image measured against it. Both figures are printed.
# Usage: scripts/light-sampler-rmse.sh [build dir] [spp] [reference spp]; W, H set the size (default 240x135),
# SCENES the scenes (default below; minecraft.lua is the bluenbt world in daylight, minecraft-cave.lua its ancient
# city underground, lit by candles, soul fire and lava; both are skipped without their world in ../shared/data),
# REPS the renders per sampler (default 3, seeds 1..REPS, the two samplers interleaved so that load changes hit
# both alike): the error is over all of them (the root of the mean squared error), the time their median.
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
REPS=${REPS:-3}
scenes=(${SCENES:-many-lights materials textures cornell-box minecraft minecraft-cave})
kept=()
for s in "${scenes[@]}"; do
  if [[ $s == minecraft* && ! -d ../shared/data/minecraft/bluenbt-1.20.1-paper ]]; then
    echo "$s: skipped (../shared/data/minecraft/bluenbt-1.20.1-paper is absent: the scene would be an empty sky)"
    continue
  fi
  # With their emission layers: the pixels that show an emitter are left out of the second RMSE below.
  for half in A B; do
    ref="$OUT/$s-ref$half$((REF_SPP / 2))-${W}x$H.exr"
    [[ -f $ref ]] || "$BUILD/torte" --quiet --aovs emission "scenes/$s.lua" width=$W height=$H spp=$((REF_SPP / 2)) \
      seed=$([[ $half == A ]] && echo 7 || echo 8) output="$ref"
  done
  kept+=("$s")
  for ls in bvh power; do
    # The shipped scenes take no light_sampler argument: a wrapper sets it on every torte.render{} call.
    cat > "$OUT/wrap-$ls.lua" <<LUA
local real = torte.render
torte.render = function(t) t.light_sampler = "$ls"; return real(t) end
torte.script_dir = "$PWD/scenes"  -- the scene's own directory, which its paths are relative to
dofile("scenes/$s.lua")
LUA
  done
  for ((rep = 1; rep <= REPS; ++rep)); do
    for ls in bvh power; do
      "$BUILD/torte" --quiet "$OUT/wrap-$ls.lua" width=$W height=$H spp="$SPP" seed=$rep output="$OUT/$s-$ls-$rep.exr"
    done
  done
done
/usr/bin/python3 - "$OUT" "$REF_SPP" "$W" "$H" "$REPS" "${kept[@]}" <<'PY'
import sys, numpy as np, OpenImageIO as oiio
out, ref_spp, w, h, reps, scenes = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]), sys.argv[6:]
def load(path):
    b = oiio.ImageBuf(path)
    names = list(b.spec().channelnames)
    px = b.get_pixels(oiio.FLOAT)
    rgb = px[:, :, [names.index(c) for c in ("R", "G", "B")]]
    emission = px[:, :, [names.index(c) for c in ("emission.R", "emission.G", "emission.B")]] \
        if "emission.R" in names else None
    return rgb, emission, float(b.spec().get_float_attribute("torte:render_seconds"))
half = int(ref_spp) // 2
for s in scenes:
    a, emission_a, _ = load(f"{out}/{s}-refA{half}-{w}x{h}.exr")
    b, emission_b, _ = load(f"{out}/{s}-refB{half}-{w}x{h}.exr")
    ref = (a + b) / 2
    # Pixels that show an emitter (in either half): their noise is how much of the pixel the emitter covers, which
    # no light sampler changes (10,000 beads of two pixels each cover much of many-lights.lua).
    lit = np.all(emission_a == 0, axis=2) & np.all(emission_b == 0, axis=2) if emission_a is not None \
        else np.ones(ref.shape[:2], bool)
    print(f"{s}: {int((~lit).sum())} of {lit.size} pixels show an emitter")
    r = {}
    for ls in ("bvh", "power"):
        se, sel, naive, ts = [], [], [], []
        for rep in range(1, reps + 1):
            img, _, t = load(f"{out}/{s}-{ls}-{rep}.exr")
            cross = (img - a) * (img - b)  # unbiased for the squared error against the true image
            se.append(cross.mean())
            sel.append(cross[lit].mean())
            naive.append(((img - ref) ** 2)[lit].mean())
            ts.append(t)
        rms = lambda v: float(np.sqrt(max(np.mean(v), 0)))
        e, el, t = rms(se), rms(sel), float(np.median(ts))
        r[ls] = (e * np.sqrt(t), el * np.sqrt(t))
        print(f"{s} {ls}: RMSE {e:.5f} in {t:.2f} s (median of {', '.join(f'{x:.2f}' for x in ts)}), at equal "
              f"time {r[ls][0]:.5f}; without emitter pixels {el:.5f} (against (A + B) / 2: {rms(naive):.5f}), "
              f"at equal time {r[ls][1]:.5f}")
    print(f"{s}: the light BVH's RMSE at equal time is {r['power'][0] / r['bvh'][0]:.2f}x lower than by power, "
          f"{r['power'][1] / r['bvh'][1]:.2f}x without the pixels that show emitters")
PY

#!/usr/bin/env bash
# Measures the denoiser (docs/output.md): for each scene, RMSE against a 4096-spp reference of the 16-spp image
# raw and denoised (--denoise), the texture detail kept in a crop of textures.lua, and the crops (raw, denoised,
# reference) into docs/denoise-crops.png.
# Usage: [SCENES='a b ...'] scripts/denoise-rmse.sh [build dir] [reference spp]   (needs python3-numpy and python3-openimageio:
# scripts/install-deps.sh --cycles installs them). Writes to out/denoise/; references already there are reused
# (192x144 at 4096 spp: 0.5 to 3 minutes each on 2 cores, rendered niced, one at a time).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
REF_SPP=${2:-4096}
W=${W:-192}
H=${H:-144}
OUT=out/denoise
mkdir -p "$OUT"
# SCENES='materials lights' measures others (their references are rendered the first time, as above).
read -r -a scenes <<<"${SCENES:-cornell-box textures shapes many-lights}"
for s in "${scenes[@]}"; do
  ref="$OUT/$s-ref$REF_SPP.exr"
  if [[ ! -f $ref ]]; then
    nice -n 10 "$BUILD/torte" --quiet "scenes/$s.lua" width=$W height=$H spp="$REF_SPP" output="$ref"
  fi
  start=$(date +%s%N)
  "$BUILD/torte" --quiet "scenes/$s.lua" width=$W height=$H spp=16 seed=1 output="$OUT/$s-raw16.exr"
  mid=$(date +%s%N)
  "$BUILD/torte" --quiet --denoise "scenes/$s.lua" width=$W height=$H spp=16 seed=1 output="$OUT/$s-dn16.exr"
  end=$(date +%s%N)
  echo "$s: raw 16 spp $(( (mid - start) / 1000000 )) ms, denoised $(( (end - mid) / 1000000 )) ms (whole process)"
done
# Crop of textures.lua's detail (x, y, width, height at 192x144, scaled to W x H): the cube's 3D checker, the cow's
# patches and the wood, on which blur would show.
read -r CX CY CW CH <<<"$(( 52 * W / 192 )) $(( 40 * H / 144 )) $(( 64 * W / 192 )) $(( 48 * H / 144 ))"
/usr/bin/python3 - "$OUT" "$REF_SPP" "$CX $CY $CW $CH" "${scenes[@]}" <<'PY'
import sys, numpy as np, OpenImageIO as oiio
out, ref_spp, (cx, cy, cw, ch), scenes = sys.argv[1], sys.argv[2], map(int, sys.argv[3].split()), sys.argv[4:]
def rgb(path, prefix=None):
    b = oiio.ImageBuf(path); a = b.get_pixels(oiio.FLOAT); names = list(b.spec().channelnames)
    ch = [names.index(c if prefix is None else prefix + "." + c) for c in "RGB"]
    return a[:, :, ch]
for s in scenes:
    ref = rgb(f"{out}/{s}-ref{ref_spp}.exr")
    raw = rgb(f"{out}/{s}-raw16.exr"); dn = rgb(f"{out}/{s}-dn16.exr")
    noisy = rgb(f"{out}/{s}-dn16.exr", "noisy")
    assert np.array_equal(raw, noisy), "the noisy layer is the raw render"
    e_raw = np.sqrt(((raw - ref) ** 2).mean()); e_dn = np.sqrt(((dn - ref) ** 2).mean())
    print(f"{s}: RMSE raw {e_raw:.5f}, denoised {e_dn:.5f}: {e_raw / e_dn:.2f}x lower (reference {ref_spp} spp)")
    if s != "textures":
        continue
    # Texture detail in the crop: the energy of the albedo's high frequencies (pixel minus its 3x3 mean) that the
    # denoised image shares with the reference, relative to the reference's (1 = all kept, 0 = blurred flat), and
    # the crop's own RMSE. The raw image is too noisy for the first to mean anything.
    sl = (slice(cy, cy + ch), slice(cx, cx + cw))
    def high(a):
        p = np.pad(a, ((1, 1), (1, 1), (0, 0)), mode="edge")
        box = sum(p[1 + dy:p.shape[0] - 1 + dy, 1 + dx:p.shape[1] - 1 + dx] for dy in (-1, 0, 1) for dx in (-1, 0, 1)) / 9
        return (a - box)[sl]
    hr, hd = high(ref), high(dn)
    kept = (hd * hr).sum() / (hr * hr).sum()
    crop = lambda a: np.sqrt(((a[sl] - ref[sl]) ** 2).mean())
    print(f"  crop {cw}x{ch}+{cx}+{cy}: RMSE raw {crop(raw):.5f}, denoised {crop(dn):.5f}; high-frequency detail "
          f"kept {kept:.2f} (projection on the reference's)")
PY
# Crops of textures.lua's detail: raw, denoised, reference (4x), for docs/denoise-crops.png.
[[ " ${scenes[*]} " == *" textures "* ]] || exit 0
c="$OUT/textures"
crop="${CW}x${CH}+${CX}+${CY}"
oiiotool "$c-raw16.png" --cut $crop --resize:filter=box $((CW * 4))x$((CH * 4)) -o "$OUT/crop-raw.png"
oiiotool "$c-dn16.png" --cut $crop --resize:filter=box $((CW * 4))x$((CH * 4)) -o "$OUT/crop-dn.png"
oiiotool "$c-ref$REF_SPP.png" --cut $crop --resize:filter=box $((CW * 4))x$((CH * 4)) -o "$OUT/crop-ref.png"
oiiotool "$OUT/crop-raw.png" "$OUT/crop-dn.png" "$OUT/crop-ref.png" --mosaic:pad=4 3x1 -o docs/denoise-crops.png
echo "wrote docs/denoise-crops.png"

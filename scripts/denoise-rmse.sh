#!/usr/bin/env bash
# Measures the denoiser (docs/output.md): for each scene, RMSE against a long reference of the 16-spp image
# raw and denoised (--denoise), and crops of textures.lua (raw, denoised, reference) into docs/denoise-crops.png.
# Usage: scripts/denoise-rmse.sh [build dir] [reference spp]   (needs python3-numpy and python3-openimageio:
# scripts/install-deps.sh --cycles installs them). Writes to out/denoise/.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
REF_SPP=${2:-4096}
W=${W:-192}
H=${H:-144}
OUT=out/denoise
mkdir -p "$OUT"
scenes=(cornell-box textures shapes)
for s in "${scenes[@]}"; do
  ref="$OUT/$s-ref$REF_SPP.exr"
  if [[ ! -f $ref ]]; then
    "$BUILD/torte" --quiet "scenes/$s.lua" width=$W height=$H spp="$REF_SPP" output="$ref"
  fi
  start=$(date +%s%N)
  "$BUILD/torte" --quiet "scenes/$s.lua" width=$W height=$H spp=16 seed=1 output="$OUT/$s-raw16.exr"
  mid=$(date +%s%N)
  "$BUILD/torte" --quiet --denoise "scenes/$s.lua" width=$W height=$H spp=16 seed=1 output="$OUT/$s-dn16.exr"
  end=$(date +%s%N)
  echo "$s: raw 16 spp $(( (mid - start) / 1000000 )) ms, denoised $(( (end - mid) / 1000000 )) ms (whole process)"
done
/usr/bin/python3 - "$OUT" "$REF_SPP" "${scenes[@]}" <<'PY'
import sys, numpy as np, OpenImageIO as oiio
out, ref_spp, scenes = sys.argv[1], sys.argv[2], sys.argv[3:]
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
PY
# Crops of textures.lua's detail: raw, denoised, reference (2x, nearest), for docs/denoise-crops.png.
c="$OUT/textures"
crop="64x48+64+72"
oiiotool "$c-raw16.png" --crop $crop --resize:filter=box 256x192 -o "$OUT/crop-raw.png"
oiiotool "$c-dn16.png" --crop $crop --resize:filter=box 256x192 -o "$OUT/crop-dn.png"
oiiotool "$c-ref$REF_SPP.png" --crop $crop --resize:filter=box 256x192 -o "$OUT/crop-ref.png"
oiiotool "$OUT/crop-raw.png" "$OUT/crop-dn.png" "$OUT/crop-ref.png" --mosaic:pad=4 3x1 -o docs/denoise-crops.png
echo "wrote docs/denoise-crops.png"

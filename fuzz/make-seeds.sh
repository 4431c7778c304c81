#!/usr/bin/env bash
# Remakes the seed corpora of fuzz/corpus/ from ../shared/data (fuzz/README.md, "Seeds"). Needs build/torte
# (make build) and oiiotool (openimageio-tools). Usage: fuzz/make-seeds.sh [DATA_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
data=${1:-../shared/data}
build/torte --quiet fuzz/make_seeds.lua data="$data" out=fuzz/corpus
# Images: the Spot cow's texture scaled down, in every format the image harness names by extension
# (fuzz_image.cc: byte 0 = extension index, byte 1 = texture options), plus a grey and a 16-bit variant.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p fuzz/corpus/image
i=0
for ext in png jpg exr hdr ppm tga bmp tif; do
  oiiotool "$data/meshes/spot/spot_texture.png" --eraseattrib ICCProfile --resize 8x8 -o "$tmp/spot.$ext"
  { printf "\\$(printf '%03o' $i)\\$(printf '%03o' $((i * 5 % 48)))"; cat "$tmp/spot.$ext"; } > "fuzz/corpus/image/spot-8x8.$ext"
  i=$((i + 1))
done
oiiotool "$data/meshes/spot/spot_texture.png" --eraseattrib ICCProfile --resize 6x5 --ch R -o "$tmp/grey.png"
{ printf '\000\005'; cat "$tmp/grey.png"; } > fuzz/corpus/image/spot-grey-6x5.png
oiiotool "$data/meshes/spot/spot_texture.png" --eraseattrib ICCProfile --resize 4x4 -d uint16 -o "$tmp/deep.tif"
{ printf '\007\026'; cat "$tmp/deep.tif"; } > fuzz/corpus/image/spot-16bit-4x4.tif
oiiotool "$data/meshes/spot/spot_texture.png" --eraseattrib ICCProfile --resize 16x16 --tile 8 8 -d half -o "$tmp/tiled.exr"
{ printf '\002\012'; cat "$tmp/tiled.exr"; } > fuzz/corpus/image/spot-tiled-16x16.exr
oiiotool "$tmp/spot.exr" "$tmp/spot.exr" --siappend -o "$tmp/multipart.exr"
{ printf '\002\001'; cat "$tmp/multipart.exr"; } > fuzz/corpus/image/spot-two-parts-8x8.exr
ls -l fuzz/corpus/image

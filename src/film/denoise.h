// A feature-guided denoiser for renders with albedo, normal and depth layers (render/aov_pass.h).
//
// Intel Open Image Denoise, the usual choice, is not packaged for Debian 12, so torte filters by hand: an
// edge-avoiding à-trous wavelet filter (Dammertz et al. 2010) with SVGF-like luminance weights (Schied et al.
// 2017), on the image divided by its albedo. Texture detail lives in the albedo, so it survives the filtering
// untouched; what is smoothed is the lighting, and only between pixels whose normals, depths and albedos agree
// and whose lighting differs by less than its estimated noise. The noise estimate is robust (a median of
// residuals), so a highlight or a shadow edge is not mistaken for noise, and the lighting compared is a median
// over the pixel and its 4-neighbours, so a firefly is spread over its neighbours rather than kept. A render's
// "variance" layer (the variance of each pixel's mean luminance; torte.render writes it with denoise = true)
// keeps one-pixel glints whose samples agree out of that median. A "glossiness" layer (written with denoise =
// true) sets how closely normals must agree: strictly on glossy surfaces, loosely on diffuse ones.
#pragma once
#include "film/image.h"

namespace torte {

struct DenoiseOptions {
  float strength = 1;  // scales the luminance tolerance (in standard deviations of the noise estimate); > 0
  int iterations = 5;  // à-trous passes, steps 1, 2, 4, ...: the filter reaches 2^(iterations + 2) pixels across
};

/// The denoised image: `image`'s pixels filtered as above, its layers kept, plus a layer "noisy" (R, G, B)
/// holding the input pixels. Pixels that an "emission" layer (when present) shows on an emitter are that emission
/// plus their albedo times the lighting of the nearest surface pixels (up to 16 pixels away; beyond, they keep their
/// values). Throws torte::Error when a layer it needs ("albedo", "normal", "depth") is missing, when
/// one of those or a "variance" layer does not match the image's size, or when the options are out of range.
Image denoise(const Image& image, const DenoiseOptions& options = {});

}  // namespace torte

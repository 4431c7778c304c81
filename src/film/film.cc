#include "film/film.h"

#include <algorithm>

namespace torte {

void Film::merge_splats(std::span<const SplatBuffer* const> buffers) {
  for (const SplatBuffer* b : buffers) {
    if (b->size() == 0) continue;
    if (splats_.empty()) splats_.assign(sums_.size(), Rgb(0));
    for (const SplatBuffer::Splat& s : b->splats()) splats_[s.pixel] += s.value;
  }
}

double mean_luminance_variance(const PixelSum& sum, float moment, uint32_t n) {
  if (n < 2 || !(sum.weight > 0)) return 0;
  const double mean = double(sum.weighted.luminance()) / double(sum.weight);
  const double second = double(moment) / double(sum.weight);
  return std::max(0.0, second - mean * mean) / double(n - 1);
}

Image Film::image(float splat_scale) const {
  Image out(width_, height_);
  for (size_t i = 0; i < sums_.size(); ++i) {
    const PixelSum& px = sums_[i];
    const Rgb camera = px.weight != 0 ? px.weighted / px.weight : Rgb(0);
    out.pixels[i] = splats_.empty() ? camera : camera + splats_[i] * splat_scale;
  }
  return out;
}

}  // namespace torte

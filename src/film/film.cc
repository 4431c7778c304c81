#include "film/film.h"

namespace torte {

void Film::merge_splats(std::span<const SplatBuffer* const> buffers) {
  for (const SplatBuffer* b : buffers) {
    if (b->size() == 0) continue;
    if (splats_.empty()) splats_.assign(sums_.size(), Rgb(0));
    for (const SplatBuffer::Splat& s : b->splats()) splats_[s.pixel] += s.value;
  }
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

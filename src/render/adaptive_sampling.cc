#include "render/adaptive_sampling.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace torte {

AdaptiveSampler::AdaptiveSampler(int width, int height, float threshold, int min_spp)
    : width_(width), height_(height), threshold_(threshold), min_spp_(uint32_t(std::max(min_spp, 2))),
      active_count_(size_t(width) * size_t(height)) {
  if (!enabled()) return;
  active_.assign(active_count_, 1);
  spp_.assign(active_count_, 0);
  error_.assign(active_count_, 0.0f);
}

float AdaptiveSampler::pixel_error(const PixelSum& sum, float moment, uint32_t n) {
  if (n < 2 || !(sum.weight > 0)) return 0;
  const double mean = double(sum.weighted.luminance()) / double(sum.weight);
  return float(std::sqrt(mean_luminance_variance(sum, moment, n)) / std::max(std::fabs(mean), double(kDarkFloor)));
}

size_t AdaptiveSampler::end_pass(const Film& film, int pass_spp) {
  if (!enabled()) return active_count_;
  const size_t w = size_t(width_), h = size_t(height_);
  const std::span<const PixelSum> sums = film.sums();
  const std::span<const float> moments = film.moments();
  parallel_for(size_t(0), h, [&](size_t y) {
    for (size_t x = 0; x < w; ++x) {
      const size_t p = y * w + x;
      if (active_[p]) spp_[p] += uint32_t(pass_spp);
      error_[p] = pixel_error(sums[p], moments.empty() ? 0.0f : moments[p], spp_[p]);
    }
  });
  // Stop a pixel only when every pixel of its 3x3 neighbourhood is below the threshold. Each row writes only its
  // own flags and reads errors (not flags), so rows are independent.
  parallel_for(size_t(0), h, [&](size_t y) {
    for (size_t x = 0; x < w; ++x) {
      const size_t p = y * w + x;
      if (!active_[p] || spp_[p] < min_spp_) continue;
      float worst = 0;
      for (size_t yy = y > 0 ? y - 1 : 0; yy <= std::min(y + 1, h - 1); ++yy)
        for (size_t xx = x > 0 ? x - 1 : 0; xx <= std::min(x + 1, w - 1); ++xx) worst = std::max(worst, error_[yy * w + xx]);
      if (worst < threshold_) active_[p] = 0;
    }
  });
  active_count_ = size_t(std::count(active_.begin(), active_.end(), uint8_t(1)));
  return active_count_;
}

}  // namespace torte

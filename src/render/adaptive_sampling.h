// Adaptive sampling (`noise_threshold` on torte.render{}): pixels stop taking samples once their estimate is good
// enough, so the samples go where the image is still noisy. The error of a pixel is the relative standard error of
// its mean luminance, sqrt(Var / n) / max(mean, kDarkFloor), from the film's sums of w L and w L^2; a pixel stops
// when its own error and its eight neighbours' are below the threshold (a lone pixel whose samples all missed a
// small bright feature is not stopped while its neighbours see it). Decisions are taken only between passes,
// from sums that do not depend on threads or scheduling, so the image stays bitwise deterministic for a seed.
#pragma once
#include <cstdint>
#include <vector>

#include "film/film.h"

namespace torte {

class AdaptiveSampler {
 public:
  /// Luminance below which errors are measured against this instead of the mean: near-black pixels would
  /// otherwise take every sample for noise nobody can see.
  static constexpr float kDarkFloor = 0.01f;

  /// Off (every pixel always active) when threshold is 0. Pixels are judged once they have min_spp samples.
  AdaptiveSampler(int width, int height, float threshold, int min_spp);

  bool enabled() const { return threshold_ > 0; }
  /// One byte per pixel, nonzero while the pixel takes samples; null when adaptive sampling is off.
  const uint8_t* active() const { return enabled() ? active_.data() : nullptr; }
  size_t active_count() const { return active_count_; }

  /// After a pass in which every active pixel took `pass_spp` samples: counts them and, from min_spp on, stops
  /// the pixels whose neighbourhood has converged. Returns the pixels still active.
  size_t end_pass(const Film& film, int pass_spp);

  /// Samples each pixel took (empty when off).
  const std::vector<uint32_t>& pixel_spp() const { return spp_; }

  /// The relative standard error of pixel p's mean luminance after n samples (0 for n < 2 or a black pixel).
  static float pixel_error(const PixelSum& sum, float moment, uint32_t n);

 private:
  int width_, height_;
  float threshold_;
  uint32_t min_spp_;
  std::vector<uint8_t> active_;
  std::vector<uint32_t> spp_;
  std::vector<float> error_;  // scratch of end_pass
  size_t active_count_;
};

}  // namespace torte

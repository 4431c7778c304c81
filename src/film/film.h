// The film: what samples of a render add up to. Camera samples add to their own pixel (weighted, filter
// importance sampling); splats add radiance at any image position (light tracing and BDPT connect to the camera
// from anywhere in the scene). Both are thread-safe and bitwise deterministic for any thread count:
//   - add_sample: each pixel is written by one work item at a time (render tiles own their pixels);
//   - splats go into a SplatBuffer owned by one work item (not by a thread), and merge_splats adds buffers in the
//     order given (work-item order), so every pixel sums its splats in the same order on every run.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/rgb.h"
#include "core/vec.h"
#include "film/image.h"

namespace torte {

/// Accumulated camera samples of one pixel: sum of weight * L and sum of weights (16 bytes).
struct PixelSum {
  Rgb weighted;
  float weight = 0;
};
static_assert(sizeof(PixelSum) == 16);

/// The variance of a pixel's mean luminance after n samples from its sums (`moment`: the sum of w luminance^2):
/// the unbiased sample variance of one sample over n; 0 for n < 2 or an empty pixel.
double mean_luminance_variance(const PixelSum& sum, float moment, uint32_t n);

/// Splats recorded by one work item, in the order it made them; merged into the film later.
class SplatBuffer {
 public:
  struct Splat {
    uint32_t pixel;
    Rgb value;
  };
  /// Records `value` at raster position `raster` ((0,0) the image's top-left corner, pixels of size 1) of a
  /// width x height film; positions outside the image and non-finite values are dropped (returns false).
  bool splat(Vec2f raster, Rgb value, int width, int height) {
    if (!(raster.x >= 0 && raster.y >= 0 && raster.x < float(width) && raster.y < float(height))) return false;
    if (!value.is_finite()) return false;
    splats_.push_back({uint32_t(int(raster.y)) * uint32_t(width) + uint32_t(int(raster.x)), value});
    return true;
  }
  /// Appends a splat made elsewhere (a checkpoint, another process); `s.pixel` must lie in the film.
  void append(const Splat& s) { splats_.push_back(s); }
  void clear() { splats_.clear(); }
  size_t size() const { return splats_.size(); }
  std::span<const Splat> splats() const { return splats_; }

 private:
  std::vector<Splat> splats_;
};

class Film {
 public:
  Film() = default;
  /// A black width x height film (no bounds checks here: render() validates the size).
  Film(int width, int height)
      : width_(width), height_(height), sums_(size_t(width) * size_t(height)) {}

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return sums_.size(); }

  /// Adds camera sample L with filter weight w to pixel `pixel` (linear index). Callers that run in parallel
  /// must own disjoint pixels; the film does no locking on this path (one add per camera sample).
  void add_sample(uint32_t pixel, Rgb L, float w) {
    PixelSum& px = sums_[pixel];
    px.weighted += L * w;
    px.weight += w;
    if (!moments_.empty()) {
      const float y = L.luminance();
      moments_[pixel] += w * y * y;
    }
  }

  /// Also sums w * luminance(L)^2 per pixel from now on (adaptive sampling's variance estimate, 4 bytes a
  /// pixel); films that do not ask never pay for it.
  void track_moments() { moments_.assign(sums_.size(), 0.0f); }
  /// The sums of w * luminance^2 (empty unless track_moments was called).
  std::span<const float> moments() const { return moments_; }
  std::span<float> moments() { return moments_; }
  /// Restores the moments (a checkpoint's; `m` empty or one per pixel).
  void set_moments(std::vector<float> m) { moments_ = std::move(m); }
  /// The variance of pixel i's mean luminance after n samples (mean_luminance_variance; 0 without moments).
  float mean_variance(size_t i, uint32_t n) const {
    return moments_.empty() ? 0.0f : float(mean_luminance_variance(sums_[i], moments_[i], n));
  }

  /// A buffer for splats at arbitrary positions of this film.
  bool splat(SplatBuffer& buffer, Vec2f raster, Rgb value) const {
    return buffer.splat(raster, value, width_, height_);
  }

  /// Adds the splats of `buffers` in the order given (one thread; the order fixes the floating-point sums). The
  /// splat array (12 bytes a pixel) is allocated by the first merge: camera-only renders never pay for it.
  void merge_splats(std::span<const SplatBuffer* const> buffers);
  void merge_splats(const SplatBuffer& buffer) {
    const SplatBuffer* b = &buffer;
    merge_splats(std::span<const SplatBuffer* const>(&b, 1));
  }

  const PixelSum& sum(uint32_t pixel) const { return sums_[pixel]; }
  /// The raw sums, for checkpoints and for moving tiles between processes (distributed rendering): a film
  /// restored from them continues summing exactly where the saved one stopped.
  std::span<PixelSum> sums() { return sums_; }
  std::span<const PixelSum> sums() const { return sums_; }
  /// The splat sums (empty until the first merge) and their restoration (`s` empty or one per pixel).
  std::span<const Rgb> splat_sums() const { return splats_; }
  void set_splat_sums(std::vector<Rgb> s) { splats_ = std::move(s); }
  Rgb splat_sum(uint32_t pixel) const { return splats_.empty() ? Rgb(0) : splats_[pixel]; }

  /// The image: weighted mean of the camera samples of each pixel (black without any) plus the pixel's splat sum
  /// times `splat_scale` (e.g. 1 / light paths per pixel).
  Image image(float splat_scale = 1) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<PixelSum> sums_;
  std::vector<Rgb> splats_;  // empty until the first merge_splats
  std::vector<float> moments_;  // empty unless track_moments
};

}  // namespace torte

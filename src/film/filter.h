// Pixel reconstruction filters, all separable: f(x, y) = f1(x) f1(y). Sampled by filter importance sampling
// (as pbrt-v4 does): each camera sample picks its offset from the filter's |f| and carries weight f/pdf, and it
// only contributes to its own pixel. Tiles then never write into each other, which keeps rendering
// deterministic under any thread schedule. A sample's raster position is reflected at the image's edges
// (filter_raster_position), so every pixel is a weighted average of what lies inside the frame whatever the
// radius: a radius larger than the image blurs the frame instead of looking beside it (where a camera sees mostly
// nothing, and the image turned black).
#pragma once
#include <string>
#include <vector>

#include "core/vec.h"

namespace torte {

enum class FilterKind { Box, Triangle, Gaussian, Mitchell };

class Filter {
 public:
  static Filter box(float radius = 0.5f);
  static Filter triangle(float radius = 1.0f);
  static Filter gaussian(float radius = 1.5f, float sigma = 0.5f);
  static Filter mitchell(float radius = 2.0f, float b = 1.0f / 3, float c = 1.0f / 3);

  FilterKind kind() const { return kind_; }
  float radius() const { return radius_; }
  // f(x, y) for an offset (x, y) in pixels from the pixel centre; 0 outside the radius.
  float evaluate(Vec2f p) const { return eval_1d(p.x) * eval_1d(p.y); }
  float eval_1d(float x) const;

  struct Sample {
    Vec2f offset;  // in [-radius, radius]^2, pixels
    // f(offset) / (pdf(offset) * c), c = the integral of |f| (of its table, for Gaussian and Mitchell): exactly 1
    // for box and triangle, which are sampled exactly, close to +-1 for the tabulated ones; negative in
    // Mitchell's lobes. The film divides by the sum of weights, so c cancels.
    float weight;
  };
  Sample sample(Vec2f u) const;

 private:
  Filter(FilterKind kind, float radius, float p0, float p1);
  float sample_1d(float u, float* weight) const;
  FilterKind kind_;
  float radius_;
  float p0_, p1_;  // Gaussian: sigma, 1/(2 sigma^2); Mitchell: B, C
  // Gaussian and Mitchell: |f1| at evenly spaced nodes over [0, radius] (f1 is even), sampled as a piecewise-linear
  // density, and its normalized running integral at the nodes (cdf_.front() = 0, cdf_.back() = 1).
  std::vector<float> table_, cdf_;
};

/// The raster position of a filter sample of pixel (px, py) with offset `offset` from the pixel centre, mirrored
/// at the image's edges into [0, width] x [0, height] (as often as needed: the radius may exceed the image).
Vec2f filter_raster_position(int px, int py, Vec2f offset, int width, int height);

}  // namespace torte

#include "film/filter.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace torte {

namespace {

void check_positive(const char* filter, const char* name, float v) {
  if (!(v > 0) || !std::isfinite(v))
    throw Error(std::string(filter) + " filter " + name + " must be a positive number (got " + std::to_string(v) +
                ")");
}

// Table resolution over [0, radius]. Mitchell's shape does not depend on the radius, and its even bin count puts
// a node on the kink at radius/2, so the piecewise-linear table follows both smooth pieces. The Gaussian narrows
// as radius/sigma grows, so it gets at least 32 bins per sigma.
int table_bins(FilterKind kind, float radius, float sigma) {
  constexpr int kMin = 256, kMax = 1 << 16;
  if (kind != FilterKind::Gaussian) return kMin;
  const double n = std::ceil(32.0 * radius / sigma);
  return n >= kMax ? kMax : std::max(kMin, int(n));
}

}  // namespace

Filter Filter::box(float radius) {
  check_positive("box", "radius", radius);
  return Filter(FilterKind::Box, radius, 0, 0);
}

Filter Filter::triangle(float radius) {
  check_positive("triangle", "radius", radius);
  return Filter(FilterKind::Triangle, radius, 0, 0);
}

Filter Filter::gaussian(float radius, float sigma) {
  check_positive("gaussian", "radius", radius);
  check_positive("gaussian", "sigma", sigma);
  const float k = 1 / (2 * sigma * sigma);
  // x^2 * k must stay finite for every |x| <= radius, or the profile turns into NaN (0 * inf at x = 0).
  if (!std::isfinite(k) || !std::isfinite(radius * radius * k))
    throw Error("gaussian filter sigma " + std::to_string(sigma) + " is too small for radius " +
                std::to_string(radius));
  return Filter(FilterKind::Gaussian, radius, sigma, k);
}

Filter Filter::mitchell(float radius, float b, float c) {
  check_positive("mitchell", "radius", radius);
  if (!std::isfinite(b) || !std::isfinite(c))
    throw Error("mitchell filter B and C must be finite numbers (got B = " + std::to_string(b) +
                ", C = " + std::to_string(c) + ")");
  return Filter(FilterKind::Mitchell, radius, b, c);
}

Filter::Filter(FilterKind kind, float radius, float p0, float p1) : kind_(kind), radius_(radius), p0_(p0), p1_(p1) {
  if (kind == FilterKind::Box || kind == FilterKind::Triangle) return;  // sampled in closed form
  const int n = table_bins(kind, radius, p0);
  table_.resize(n + 1);
  cdf_.resize(n + 1);
  for (int i = 0; i <= n; ++i) table_[i] = std::fabs(eval_1d(float(double(radius) * i / n)));
  // Trapezoid areas in double: the running sum must not stall on tiny Gaussian tails.
  std::vector<double> sum(n + 1, 0.0);
  for (int i = 0; i < n; ++i) sum[i + 1] = sum[i] + 0.5 * (double(table_[i]) + table_[i + 1]);
  if (!(sum[n] > 0) || !std::isfinite(sum[n]))
    throw Error("filter is zero everywhere inside its radius " + std::to_string(radius) + "; check its parameters");
  for (int i = 0; i < n; ++i) cdf_[i] = float(sum[i] / sum[n]);
  cdf_[n] = 1;  // exactly, so every u < 1 finds a bin
}

float Filter::eval_1d(float x) const {
  const float ax = std::fabs(x);
  switch (kind_) {
    case FilterKind::Box:
      return ax <= radius_ ? 1.0f : 0.0f;
    case FilterKind::Triangle:
      return std::max(0.0f, radius_ - ax);
    case FilterKind::Gaussian: {
      if (!(ax < radius_)) return 0;
      // exp(-a) - exp(-b) written as -exp(-a) expm1(a - b): no cancellation when sigma >> radius, where both
      // exponentials round to 1 in float.
      const float a = ax * ax * p1_, b = radius_ * radius_ * p1_;
      return std::max(0.0f, -std::exp(-a) * std::expm1(a - b));
    }
    case FilterKind::Mitchell: {
      // Mitchell & Netravali (1988), support [-2, 2] stretched to [-radius, radius] (pbrt's convention). The
      // kernel integrates to 1 over [-2, 2], so over [-radius, radius] f1 integrates to radius / 2.
      const float t = 2 * ax / radius_, B = p0_, C = p1_;
      if (t < 1)
        return ((12 - 9 * B - 6 * C) * t * t * t + (-18 + 12 * B + 6 * C) * t * t + (6 - 2 * B)) / 6;
      if (t < 2)
        return ((-B - 6 * C) * t * t * t + (6 * B + 30 * C) * t * t + (-12 * B - 48 * C) * t + (8 * B + 24 * C)) / 6;
      return 0;
    }
  }
  return 0;
}

float Filter::sample_1d(float u, float* weight) const {
  const float r = radius_;
  switch (kind_) {
    case FilterKind::Box:
      *weight = 1;
      return (2 * u - 1) * r;
    case FilterKind::Triangle:
      // Inverse CDF of pdf (r - |x|) / r^2, one half-triangle per half of u; weight f/(pdf r^2) = 1.
      *weight = 1;
      return u < 0.5f ? -r * (1 - std::sqrt(2 * u)) : r * (1 - std::sqrt(2 - 2 * u));
    default:
      break;
  }
  // f1 is even: the first bit of u picks the side, the rest samples |x| from the table.
  const bool negative = u < 0.5f;
  const float v = negative ? 2 * u : 2 * u - 1;  // exact in float
  const int n = int(table_.size()) - 1;
  // Bins of zero area have cdf_[i] == cdf_[i+1] and can never satisfy cdf_[i] <= v < cdf_[i+1].
  const int i = std::clamp(int(std::upper_bound(cdf_.begin(), cdf_.end(), v) - cdf_.begin()) - 1, 0, n - 1);
  const double a = table_[i], b = table_[i + 1];
  const double span = double(cdf_[i + 1]) - cdf_[i];
  const double t = span > 0 ? std::clamp((v - cdf_[i]) / span, 0.0, 1.0) : 0.0;
  // Position s in the bin whose area under the line from a to b is the fraction t of the bin's area:
  // (b - a) s^2 / 2 + a s = t (a + b) / 2, solved in the form that needs no division by (b - a).
  const double denom = a + std::sqrt(a * a + t * (b * b - a * a));
  const double s = denom > 0 ? std::min(1.0, t * (a + b) / denom) : 0.0;
  const float x = std::min(r, float((i + s) * r / n));
  const double density = a + (b - a) * s;  // the table's |f1| at x, proportional to the pdf
  *weight = density > 0 ? float(eval_1d(x) / density) : 0.0f;
  return negative ? -x : x;
}

Filter::Sample Filter::sample(Vec2f u) const {
  float wx, wy;
  const float x = sample_1d(u.x, &wx);
  const float y = sample_1d(u.y, &wy);
  return {Vec2f(x, y), wx * wy};
}

namespace {
// x mirrored into [0, size]: the reflection has period 2 size. Double keeps the pixel's own position exact for
// offsets of any size a float radius allows.
float reflect_into(double x, double size) {
  double r = std::fmod(x, 2 * size);
  if (r < 0) r += 2 * size;
  if (r > size) r = 2 * size - r;
  return float(r);
}
}  // namespace

Vec2f filter_raster_position(int px, int py, Vec2f offset, int width, int height) {
  const double x = px + 0.5 + double(offset.x), y = py + 0.5 + double(offset.y);
  // Inside the image (every sample of a small filter away from the edges): exactly the old float sum.
  if (x >= 0 && x <= width && y >= 0 && y <= height)
    return {float(px) + 0.5f + offset.x, float(py) + 0.5f + offset.y};
  return {reflect_into(x, width), reflect_into(y, height)};
}

}  // namespace torte

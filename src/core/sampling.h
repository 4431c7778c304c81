// Warping functions from [0,1)^n to common domains, their pdfs, discrete distributions and MIS weights.
// Every routine here has a chi-square test in tests/test_sampling.cc.
#pragma once
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/vec.h"

namespace torte {

inline Vec2f sample_uniform_disk_concentric(Vec2f u);  // unit disk, pdf 1/pi
Vec3f sample_uniform_sphere(Vec2f u);           // pdf 1/(4 pi)
constexpr float uniform_sphere_pdf() { return 1.0f / (4 * kPi); }
Vec3f sample_uniform_hemisphere(Vec2f u);       // z >= 0, pdf 1/(2 pi)
constexpr float uniform_hemisphere_pdf() { return 1.0f / (2 * kPi); }
inline Vec3f sample_cosine_hemisphere(Vec2f u);  // z >= 0, pdf cos(theta)/pi
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0 ? cos_theta * kInvPi : 0; }
// Uniform over the cone of directions around +z with cos(theta) >= cos_theta_max.
Vec3f sample_uniform_cone(Vec2f u, float cos_theta_max);
inline float uniform_cone_pdf(float cos_theta_max) { return 1.0f / (2 * kPi * (1 - cos_theta_max)); }
// Uniform barycentrics (b0, b1, b2) over a triangle (Heitz 2019 low-distortion map).
inline Vec3f sample_uniform_triangle(Vec2f u);

// Power heuristic with beta = 2 (Veach 1997).
inline float power_heuristic(float nf, float f_pdf, float ng, float g_pdf) {
  const float f = nf * f_pdf, g = ng * g_pdf;
  if (f == kInfinity) return 1;  // a delta strategy always wins
  if (f == 0) return 0;
  return (f * f) / (f * f + g * g);
}

inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;  // the largest float below 1

// Piecewise-constant 1D distribution over n bins of [0,1) built from non-negative weights. If all weights are
// zero it falls back to uniform so sampling stays defined.
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::span<const float> weights);
  size_t size() const { return func_.size(); }
  float integral() const { return integral_; }  // sum of weights / n (the average weight)
  // Picks bin i with probability weights[i] / sum; *pmf receives that probability, *u_remapped a fresh uniform.
  int sample_discrete(float u, float* pmf = nullptr, float* u_remapped = nullptr) const {
    if (uniform_) {  // inline: an emitting quad's triangle is chosen once per light sample
      const int n = int(func_.size());
      const float x = (u >= 0 ? std::min(u, kOneMinusEpsilon) : 0.0f) * float(n);  // NaN and u < 0 pick bin 0
      const int i = std::min(int(x), n - 1);
      if (pmf) *pmf = uniform_pmf_;
      if (u_remapped) *u_remapped = std::clamp(x - float(i), 0.0f, kOneMinusEpsilon);
      return i;
    }
    return sample_by_search(u, pmf, u_remapped);
  }
  float pmf(int i) const;
  // Continuous sample in [0,1) with density func/integral; *pdf receives it, *bin the bin index.
  float sample_continuous(float u, float* pdf = nullptr, int* bin = nullptr) const;

 private:
  std::vector<float> func_, cdf_;
  float integral_ = 0;
  int sample_by_search(float u, float* pmf, float* u_remapped) const;
  // Equal weights (one weight, a quad's two triangles, a constant environment row): the bin is floor(u n), no
  // search; the constructor sets it, so a default-constructed (empty) distribution searches.
  bool uniform_ = false;
  float uniform_pmf_ = 0;  // pmf(i) of every bin when uniform_, so sampling and pmf() agree to the bit
};

// Piecewise-constant 2D distribution over [0,1)^2 on an nu x nv grid of non-negative weights (row-major,
// weights[v * nu + u]): a marginal distribution over rows and one conditional distribution per row (pbrt's
// Distribution2D). Densities are with respect to area in [0,1)^2; pdf(p) equals the density sample() reports.
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(std::span<const float> weights, int nu, int nv);
  int nu() const { return int(conditional_.size() ? conditional_[0].size() : 0); }
  int nv() const { return int(conditional_.size()); }
  float integral() const { return marginal_.integral(); }  // average weight
  // Continuous sample in [0,1)^2; *pdf receives its density.
  Vec2f sample(Vec2f u, float* pdf = nullptr) const;
  float pdf(Vec2f p) const;

 private:
  std::vector<Distribution1D> conditional_;  // one per row v
  Distribution1D marginal_;                   // over rows, weighted by the row averages
};

// The warps every shading event calls are inline: out of line, their call and latency chains could not
// overlap with the caller's work.
namespace sampling_detail {

// mask ? a : b for a mask of all ones or all zeros, in bit operations: clang turns a plain select of floats into a
// branch for SSE2, which mispredicts half the time on random samples.
inline float select_bits(uint32_t mask, float a, float b) {
  return std::bit_cast<float>((std::bit_cast<uint32_t>(a) & mask) | (std::bit_cast<uint32_t>(b) & ~mask));
}

// sin and cos of |phi| <= pi/4 from their Taylor series (truncation error below 2e-9, under one float ulp of the
// results): the concentric map only needs this range, and a libm call per BSDF sample was 3 % of a Cornell render.
inline void sincos_quarter_turn(float phi, float* s, float* c) {
  const float p2 = phi * phi;
  *s = phi * (1 + p2 * (-1.0f / 6 + p2 * (1.0f / 120 + p2 * (-1.0f / 5040 + p2 * (1.0f / 362880)))));
  *c = 1 + p2 * (-0.5f + p2 * (1.0f / 24 + p2 * (-1.0f / 720 + p2 * (1.0f / 40320 + p2 * (-1.0f / 3628800)))));
}

}  // namespace sampling_detail

inline Vec2f sample_uniform_disk_concentric(Vec2f u) {
  // Shirley & Chiu 1997: maps concentric squares to concentric circles, so strata of u stay compact on the disk
  // (better than the polar map for stratified and low-discrepancy samples). The angle is pi/4 * (y/x) in the
  // wedges around the x axis and pi/2 - pi/4 * (x/y) around the y axis, so both need sin and cos of an angle in
  // [-pi/4, pi/4] only (cos(pi/2 - a) = sin(a)).
  // Selects instead of branches: u is random, so a branch on the wedge mispredicts half the time.
  const float x = 2 * u.x - 1, y = 2 * u.y - 1;
  const uint32_t x_wedge = 0u - uint32_t(std::fabs(x) > std::fabs(y));  // all ones in the x wedge
  const float r = sampling_detail::select_bits(x_wedge, x, y), other = sampling_detail::select_bits(x_wedge, y, x);
  if (r == 0) return {0, 0};  // the centre (then x = y = 0)
  float s, c;
  sampling_detail::sincos_quarter_turn((kPi / 4) * (other / r), &s, &c);
  return {r * sampling_detail::select_bits(x_wedge, c, s), r * sampling_detail::select_bits(x_wedge, s, c)};
}

inline Vec3f sample_cosine_hemisphere(Vec2f u) {
  // Malley's method: uniform on the disk, projected up to the hemisphere, has density cos(theta)/pi.
  const Vec2f d = sample_uniform_disk_concentric(u);
  return {d.x, d.y, std::sqrt(std::max(0.0f, 1 - d.x * d.x - d.y * d.y))};
}

inline Vec3f sample_uniform_triangle(Vec2f u) {
  // Heitz 2019, "A Low-Distortion Map Between Triangle and Square": shrinks the square's lower or upper half
  // (split along the diagonal) onto the triangle. Unlike the sqrt map it keeps strata compact and needs no sqrt.
  // Both halves in one expression: the half of the smaller coordinate comes off both (u.x - u.x/2 = u.x/2 exactly).
  // u is random, so a branch on the half mispredicts half the time.
  const float h = std::min(u.x, u.y) / 2;
  const float b0 = u.x - h, b1 = u.y - h;
  return {b0, b1, std::max(0.0f, 1 - b0 - b1)};
}

}  // namespace torte
